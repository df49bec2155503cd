# PendularForceResetter against YADE's ForceResetter, and the fused loop's forces written straight into
# the force container. Expected values: the same scene run with ForceResetter (the reset it replaces) or
# with YADE's InteractionLoop (the loop PendularLoop reproduces).
# - Wet packings of 300 spheres in a box of walls under gravity, 500 steps, with yade -j1 and -j2 (ctest
#   runs this file both ways; parallelBodies = 0 puts the per-body passes of 300 bodies on both threads).
# - The reset zeroes the same entries as ForceResetter's, so positions, velocities, and the forces and
#   torques left in O.forces after the run are bit-identical on one thread, in each case below. Two runs
#   on two threads differ by round-off even with the same engines (the collider's parallel insertion
#   changes the order of the container: 3.1e-13 of the scale measured between two ForceResetter runs),
#   so there the bound is 1e-9 of the scale as in test_loop.py. The cases:
#   a plain run (reset by the threads' parts from the second step on: nHandedOver = 1), permanent forces
#   (O.forces.setPermF: every step handed to ForceContainer::reset), a force added after the integrator
#   at every step (O.forces.addF from a PyRunner: YADE carries it into the next step's sync; handed over),
#   and spheres appended during the run (the force container grows).
# - A force added before the loop at every step (a PyRunner between the reset and the loop): each thread
#   of the fused pass adds its bodies' forces onto it, in the container, as InteractionLoop's thread adds
#   them onto its per-thread entry. On one thread the sums are InteractionLoop's in the same order:
#   bit-identical (the container unsorted, sortDisorder = 0, as in test_loop.py; before the forces went
#   straight into the container, the force added before the loop came last: 5.2e-17 of the scale). On
#   two threads the sums differ in order: bound 1e-9 of the scale as in test_loop.py.
# - Where only the collider stands between the reset and the loop (scene.engines), the loop's gathering
#   zeroes the forces (nDeferred counts those steps: every step not handed over); with the PyRunner between
#   them, none. With O.subStepping, Python can read the forces between the engines: the reset is then the
#   resetter's own, and every force is zero after its sub-step.
from yade import O
from yade.utils import sphere
from yade.wrapper import ForceResetter, PendularForceResetter, PyRunner

import stress
from testing import Checker
from yade_capillary import scene

ck = Checker("test_force_resetter")
STEPS = 500
BOUND = 1e-9
RMIN = 0.5e-3
parallel = O.numThreads > 1


def grow():
    """One more sphere above the packing (the body and force containers grow during the run)."""
    O.bodies.append(sphere((0.0, 0.0, 0.02 + 1e-3 * len(O.bodies)), RMIN, material=O.materials[0]))


def build(resetter, loop="fused", case="plain"):
    stress.box_packing(300, "willett_full", rmin=RMIN, ratio=2.0, box="walls", porosity=0.85, speed=1.0, friction=0.3)
    engines = scene.engines(gravity=(0, 0, -9.81), loop=loop)
    if resetter == "yade":
        engines[0] = ForceResetter()
    ids = [b.id for b in O.bodies if b.shape.__class__.__name__ == "Sphere"][:5]
    command = "for i in %r: O.forces.addF(i, (1e-5, -2e-5, 3e-5)); O.forces.addT(i, (1e-8, 0, -1e-8))" % ids
    if case == "before":
        engines.insert(1, PyRunner(iterPeriod=1, command=command))
    elif case == "after":
        engines.append(PyRunner(iterPeriod=1, command=command))
    elif case == "grow":
        engines.append(PyRunner(iterPeriod=100, command="grow()"))
    O.engines = engines
    if case == "perm":
        for i in ids:
            O.forces.setPermF(i, (0, 0, 2e-5))
            O.forces.setPermT(i, (1e-8, 0, 0))
    for e in O.engines:
        if parallel and hasattr(e, "parallelBodies"):
            e.parallelBodies = 0
        if hasattr(e, "sortDisorder"):
            e.sortDisorder = 0  # the container in InteractionLoop's order (sorting changes the order of the sums)
    O.dt = scene.stable_dt(0.1)
    O.run(STEPS, True)
    state = [(tuple(b.state.pos), tuple(b.state.vel), tuple(O.forces.f(b.id)), tuple(O.forces.t(b.id))) for b in O.bodies if b is not None]
    return state, O.engines[0]


def worst(a, b):
    """Largest difference [in RMIN for positions, in the largest speed for velocities, in the largest
    force or torque for those]."""
    scales = [max(max(abs(x) for x in s[k]) for s in a) or 1.0 for k in range(4)]
    scales[0] = RMIN
    return max(max(abs(x - y) for x, y in zip(sa[k], sb[k])) / scales[k] for sa, sb in zip(a, b) for k in range(4))


threads = "%d thread(s)" % O.numThreads
for case, why in (("plain", None), ("perm", "permanent forces"), ("after", "forces added since the last sync"), ("grow", None)):
    ref, _ = build("yade", case=case)
    got, resetter = build("pendular", case=case)
    ck.true(isinstance(resetter, PendularForceResetter) and isinstance(resetter, ForceResetter),
            "%s: scene.engines begins with PendularForceResetter, a ForceResetter (%s)" % (case, type(resetter).__name__))
    diff = worst(ref, got) if len(got) == len(ref) else float("nan")
    if parallel:
        ck.true(diff <= BOUND, "%s, %s: positions, velocities, forces and torques within %g of ForceResetter's (worst %.3g of the scale)"
                % (case, threads, BOUND, diff))
    else:
        ck.true(len(got) == len(ref) and got == ref, "%s, %s: positions, velocities, forces and torques bit-identical to ForceResetter's "
                "(worst difference %.3g of the scale, %d/%d bodies)" % (case, threads, diff, len(got), len(ref)))
    if why is None:
        # The first step has no hand-over of the loop to share by; a grown container is handed over.
        ok = resetter.nHandedOver == 1 if case == "plain" else 1 <= resetter.nHandedOver < STEPS
        ck.true(ok, "%s: steps handed to ForceContainer::reset: %d (%r)" % (case, resetter.nHandedOver, resetter.handedOverBecause))
        ck.true(resetter.nDeferred == STEPS - resetter.nHandedOver, "%s: steps whose forces the loop's gathering zeroed: %d, every step not handed "
                "over (%d of %d)" % (case, resetter.nDeferred, STEPS - resetter.nHandedOver, STEPS))
    else:
        # every step but the first of a PyRunner (which does not run at iteration 0): all STEPS or STEPS - 1
        ck.true(resetter.nHandedOver >= STEPS - 1 and why in resetter.handedOverBecause,
                "%s: every step handed to ForceContainer::reset because of %s: %d, %r" % (case, why, resetter.nHandedOver, resetter.handedOverBecause))

ref, _ = build("yade", loop="standard", case="before")
got, resetter = build("pendular", loop="fused", case="before")
ck.true(resetter.nDeferred == 0, "force added before the loop: a PyRunner between the reset and the loop, no step's reset left to the loop (%d)" % resetter.nDeferred)
if parallel:
    ck.true(worst(ref, got) <= BOUND, "force added before the loop, %s: PendularLoop within %g of InteractionLoop (worst %.3g)" % (threads, BOUND, worst(ref, got)))
else:
    ck.true(got == ref, "force added before the loop, %s: PendularLoop bit-identical to InteractionLoop (worst difference %.3g of the scale)"
            % (threads, worst(ref, got)))

# Sub-steps: the forces of the last step are there before the reset's sub-step, zero after it.
build("pendular")
deferred = O.engines[0].nDeferred
nonzero = lambda: sum(1 for b in O.bodies if O.forces.f(b.id).norm() > 0 or O.forces.t(b.id).norm() > 0)
before = nonzero()
O.subStepping = True
O.step()  # the prologue
O.step()  # the reset
after, engine = nonzero(), O.subStep
O.subStepping = False
O.step()  # the rest of the step
ck.true(before > 0 and after == 0 and engine == 1 and O.engines[0].nDeferred == deferred,
        "sub-steps: %d bodies with a force or torque before the reset, %d after its sub-step (next: %d, the collider), no reset left to the loop (%d more)"
        % (before, after, engine, O.engines[0].nDeferred - deferred))
ck.finish()
