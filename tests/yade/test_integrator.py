# PendularIntegrator against YADE's NewtonIntegrator, whose step it does (expected values: the same
# scene run with NewtonIntegrator alone, scene.engines(integrator='newton')).
# - Wet packings of 300 spheres in boxes of walls and of facets under gravity, 1000 steps, with what
#   NewtonIntegrator's step depends on: Cundall damping (0 and 0.2, gravity damped and not,
#   dampGravity), a sphere with isDamped=False, spheres with some degrees of freedom blocked, a
#   fixed sphere moved by its velocity alone, fixed spheres spinning with one angular velocity (a
#   rotating wall: PendularIntegrator reuses the rotation of the step) and another, and the collider's flag (NewtonIntegrator.maxVelocitySq,
#   which PendularIntegrator writes back: a wrong flag changes when the collider runs, counted by its
#   numAction).
# - yade -j1: the same operations in the same order on the same numbers: positions, velocities,
#   angular velocities and orientations bit-identical, and the collider run as often.
# - yade -j2 (ctest runs this file with -j1 and with -j2): both runs on two threads, the per-body
#   passes too (parallelBodies = 0; by default they run on one thread below 1 000 bodies). The
#   integration of a body does not depend on the others, but the interaction loop's force sums and
#   the collider's parallel insertion do, so the two runs may differ by round-off: bound 1e-9 of the
#   scale as in test_loop.py (measured there: at most 2.4e-12 after 2000 steps).
# - A scene with a clump is handed to NewtonIntegrator's own step (nHandedOver counts the steps),
#   with the same results as NewtonIntegrator alone.
# - The bodies' objects and the check for clumps come from PendularLoop's gathering of the same step
#   (fromLoop) in these scenes, and from a pass of the integrator's own when an engine between them may
#   change the bodies: a PyRunner there that makes a sphere aspherical at step 500 (the body container
#   unchanged) must have the step handed over from that step on, with the same results as
#   NewtonIntegrator alone.
# - Engine lists that would move the bodies twice or not at all raise a ValueError naming the cause.
import os

from yade import O
from yade.wrapper import NewtonIntegrator, PyRunner

import stress
from testing import Checker
from yade_capillary import scene

ck = Checker("test_integrator")
STEPS = 1000
BOUND = 1e-9
RMIN = 0.5e-3
parallel = O.numThreads > 1


def build(box, damping, damp_gravity, integrator, clump=False, extra=()):
    stress.box_packing(300, "willett_full", rmin=RMIN, ratio=2.0, box=box, porosity=0.85, speed=1.0, friction=0.3)
    spheres = [b for b in O.bodies if b.shape.__class__.__name__ == "Sphere"]
    spheres[0].state.isDamped = False
    spheres[1].state.blockedDOFs = "xZ"
    spheres[2].state.blockedDOFs = "yzXY"
    spheres[3].state.blockedDOFs = "xyzXYZ"  # fixed: moved by its velocity only
    spheres[3].state.vel, spheres[3].state.angVel = (0.01, -0.02, 0.005), (3.0, 1.0, -2.0)
    # Fixed spheres spinning as parts of one rotating wall (the same angular velocity, whose rotation
    # PendularIntegrator makes once and reuses), one of them with another angular velocity in between.
    for k, w in ((7, (3.0, 1.0, -2.0)), (8, (3.0, 1.0, -2.0)), (9, (0.0, 0.0, 5.0)), (10, (3.0, 1.0, -2.0))):
        spheres[k].state.blockedDOFs = "xyzXYZ"
        spheres[k].state.angVel = w
    if clump:
        O.bodies.clump([spheres[4].id, spheres[5].id])
    O.engines = scene.engines(gravity=(0, 0, -9.81), damping=damping, integrator=integrator, extra=extra)
    for e in O.engines:
        if isinstance(e, NewtonIntegrator):
            e.dampGravity = damp_gravity
        if parallel and hasattr(e, "parallelBodies"):
            e.parallelBodies = 0  # the per-body passes of PendularLoop and PendularIntegrator on both threads
    O.dt = scene.stable_dt(0.1)
    O.run(STEPS, True)
    state = [(tuple(b.state.pos), tuple(b.state.vel), tuple(b.state.angVel), tuple(b.state.ori)) for b in O.bodies if b is not None]
    engines = {type(e).__name__: e for e in O.engines}
    return state, engines["InsertionSortCollider"].numAction, engines.get("PendularIntegrator")


def worst(a, b):
    """Largest difference [in RMIN for positions, in the largest speed for velocities, in that speed
    over RMIN for angular velocities, absolute for the orientations' unit quaternions]."""
    vmax = max(max(abs(x) for x in s[1]) for s in a) or 1.0
    scales = (RMIN, vmax, vmax / RMIN, 1.0)
    return max(max(abs(x - y) for x, y in zip(sa[k], sb[k])) / scales[k] for sa, sb in zip(a, b) for k in range(4))


for box in ("walls", "facets"):
    for damping, damp_gravity in ((0.0, True), (0.2, True), (0.2, False)):
        tag = "%s, damping %g, dampGravity %s, %d thread(s)" % (box, damping, damp_gravity, O.numThreads)
        ref, ref_runs, _ = build(box, damping, damp_gravity, "newton")
        got, runs, integrator = build(box, damping, damp_gravity, "pendular")
        ck.true(integrator.nIntegrated == len(ref) and integrator.nHandedOver == 0 and integrator.fromLoop,
                "%s: PendularIntegrator integrated all %d bodies itself (%d), from PendularLoop's gathering (%s), and handed no step "
                "over (%d: %s)" % (tag, len(ref), integrator.nIntegrated, integrator.fromLoop, integrator.nHandedOver, integrator.handedOverBecause))
        ck.true(10 < runs == ref_runs < STEPS, "%s: the collider ran %d times, %d with NewtonIntegrator alone (its flag maxVelocitySq)"
                % (tag, runs, ref_runs))
        if parallel:
            d = worst(ref, got)
            ck.true(d <= BOUND, "%s: positions, velocities, angular velocities, orientations within %g of the scale of "
                    "NewtonIntegrator's (largest difference %.3g)" % (tag, BOUND, d))
        else:
            ck.true(got == ref, "%s: positions, velocities, angular velocities and orientations of all %d bodies bit-identical to "
                    "NewtonIntegrator's (largest difference %.3g of the scale)" % (tag, len(ref), worst(ref, got)))

ref, ref_runs, _ = build("walls", 0.0, True, "newton", clump=True)
got, runs, integrator = build("walls", 0.0, True, "pendular", clump=True)
ck.true(integrator.nHandedOver == STEPS and integrator.nIntegrated == 0 and integrator.handedOverBecause == "clumps",
        "scene with a clump: every step handed to NewtonIntegrator (%d of %d, because %r)" % (integrator.nHandedOver, STEPS,
                                                                                          integrator.handedOverBecause))
ck.true(runs == ref_runs and (got == ref or worst(ref, got) <= BOUND), "scene with a clump: the same results as NewtonIntegrator alone")

# A PyRunner between PendularLoop and the integrators that makes a sphere aspherical during the run (with
# unequal moments of inertia, so that NewtonIntegrator's aspherical rotation gives another orientation).
CHANGE_AT = 500


def aspherical_once():
    if O.iter == CHANGE_AT:
        b = [b for b in O.bodies if b.shape.__class__.__name__ == "Sphere"][6]
        b.aspherical = True
        b.state.inertia = (b.state.inertia[0], 2 * b.state.inertia[0], 3 * b.state.inertia[0])


ref, ref_runs, _ = build("walls", 0.0, True, "newton", extra=[PyRunner(command="aspherical_once()", iterPeriod=1)])
got, runs, integrator = build("walls", 0.0, True, "pendular", extra=[PyRunner(command="aspherical_once()", iterPeriod=1)])
ck.true(not integrator.fromLoop and integrator.nHandedOver == STEPS - CHANGE_AT and integrator.handedOverBecause.startswith("aspherical"),
        "a PyRunner between the loop and the integrators makes a sphere aspherical at step %d: the bodies read by the integrator "
        "itself (fromLoop %s) and the steps from then on handed to NewtonIntegrator (%d of %d, because %r)"
        % (CHANGE_AT, integrator.fromLoop, integrator.nHandedOver, STEPS, integrator.handedOverBecause))
if parallel:
    ck.true(runs == ref_runs and worst(ref, got) <= BOUND, "aspherical from step %d: the results of NewtonIntegrator alone within %g "
            "(largest difference %.3g)" % (CHANGE_AT, BOUND, worst(ref, got)))
else:
    ck.true(runs == ref_runs and got == ref, "aspherical from step %d: the results of NewtonIntegrator alone, bit for bit (largest "
            "difference %.3g)" % (CHANGE_AT, worst(ref, got)))

# An engine that changes what NewtonIntegrator does, added to the list of a running scene (the
# integrator scans the list again when it changes): GlobalStiffnessTimeStepper may scale densities.
from yade.wrapper import GlobalStiffnessTimeStepper  # noqa: E402

O.engines = O.engines[:-1] + [GlobalStiffnessTimeStepper(timestepSafetyCoefficient=0.1, defaultDt=O.dt), O.engines[-1]]
handed = integrator.nHandedOver
O.step()
ck.true(integrator.handedOverBecause.endswith("(GlobalStiffnessTimeStepper)") and integrator.nHandedOver == handed + 1,
        "GlobalStiffnessTimeStepper added to a running scene: the step handed to NewtonIntegrator (%r)" % integrator.handedOverBecause)

# Engine lists that would move every body twice, or never.
stress.box_packing(20, "willett_full", rmin=RMIN, ratio=2.0, box="walls", porosity=0.9)
O.engines = scene.engines(gravity=(0, 0, -9.81))
newton = next(e for e in O.engines if isinstance(e, NewtonIntegrator))
newton.dead = False
ck.raises(ValueError, O.step, ["PendularIntegrator", "dead=False", "twice"], "NewtonIntegrator alive before PendularIntegrator")
O.engines = [e for e in O.engines if not isinstance(e, NewtonIntegrator)]
ck.raises(ValueError, O.step, ["PendularIntegrator", "no NewtonIntegrator", 'integrator="newton"'],
          "no NewtonIntegrator before PendularIntegrator: the message names the yade.mpy fix")
ck.raises(ValueError, lambda: scene.engines(integrator="verlet"), ["integrator", "verlet", "auto", "pendular", "newton"], "unknown integrator")

# integrator="auto" (the default): NewtonIntegrator alone under mpiexec with several processes.
has_pendular = lambda engines: any(e.__class__.__name__ == "PendularIntegrator" for e in engines)  # noqa: E731
ck.true(has_pendular(scene.engines()), "engines() outside MPI: PendularIntegrator")
os.environ["OMPI_COMM_WORLD_SIZE"] = "2"
ck.true(not has_pendular(scene.engines()) and all(not e.dead for e in scene.engines() if isinstance(e, NewtonIntegrator)),
        "engines() with OMPI_COMM_WORLD_SIZE = 2: NewtonIntegrator alone, alive")
os.environ["OMPI_COMM_WORLD_SIZE"] = "many"
ck.true(has_pendular(scene.engines()), "engines() with a size that is not a count: PendularIntegrator")
del os.environ["OMPI_COMM_WORLD_SIZE"]
ck.finish()
