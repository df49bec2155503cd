# PendularRotationEngine against YADE's RotationEngine, whose velocities it sets (expected values: the same
# scene run with RotationEngine).
# - A wet packing of 300 spheres in a box of walls under gravity, 500 steps, with ten spheres fixed and
#   turned by the engine (one of them erased before the run: skipped), with and without rotateAroundZero
#   and with an axis given unnormalized (both engines normalize it): the same operations on the same numbers,
#   so positions, velocities, angular velocities and orientations are bit-identical on one thread.
#   On two threads (yade -j2) two runs differ by round-off even with the same engines (the collider's parallel
#   insertion): bound 1e-9 of the scale as in test_loop.py.
# - The same without the walls (erased before the run, no gravity): no entry of the PendularLoop's pass then
#   goes through YADE's dispatchers, so on two threads the loop sets the engine's velocities ahead of its
#   turn (nAhead counts those steps; none on one thread). The bounds are the same: the values must not
#   change with who computes them.
# - Bad input: an id that is not a body's raises ValueError naming the index and the id when the step runs;
#   a zero or NaN axis raises ValueError naming the attribute when it is set.
import math

from yade import O
from yade.wrapper import PendularRotationEngine, RotationEngine

from yade_capillary import scene, stress
from yade_capillary.testing import Checker

ck = Checker("test_rotation_engine")
STEPS = 500
BOUND = 1e-9
RMIN = 0.5e-3
parallel = O.numThreads > 1


def packing(walls, **kw):
    """300 wet spheres in a box of walls, the walls erased if not `walls` (no entry through the dispatchers)."""
    stress.box_packing(300, "willett_full", rmin=RMIN, ratio=2.0, box="walls", porosity=0.85, speed=1.0, friction=0.3, **kw)
    if not walls:
        for b in [b for b in O.bodies if b.shape.__class__.__name__ == "Wall"]:
            O.bodies.erase(b.id)


def build(kind, around_zero, walls):
    packing(walls)
    spheres = [b.id for b in O.bodies if b.shape.__class__.__name__ == "Sphere"]
    turned = spheres[:10]
    for i in turned:
        O.bodies[i].state.blockedDOFs = "xyzXYZ"
    O.bodies.erase(turned[4])
    engine = (PendularRotationEngine if kind == "ours" else RotationEngine)(ids=turned, rotationAxis=(0.3, -1.0, 2.0), angularVelocity=40.0,
                                                                            rotateAroundZero=around_zero, zeroPoint=(1e-3, 2e-3, 0))
    O.engines = scene.engines(gravity=(0, 0, -9.81) if walls else (0, 0, 0), extra=[engine])
    for e in O.engines:
        if parallel and hasattr(e, "parallelBodies"):
            e.parallelBodies = 0
        if hasattr(e, "sortDisorder"):
            e.sortDisorder = 0
    O.dt = scene.stable_dt(0.1)
    O.run(STEPS, True)
    build.ahead = engine.nAhead if kind == "ours" else 0
    return [(tuple(b.state.pos), tuple(b.state.vel), tuple(b.state.angVel), tuple(b.state.ori)) for b in O.bodies if b is not None]


def worst(a, b):
    """Largest difference [in RMIN for positions, in the largest speed for velocities, in that speed over
    RMIN for angular velocities, absolute for the orientations' unit quaternions]."""
    vmax = max(max(abs(x) for x in s[1]) for s in a) or 1.0
    scales = (RMIN, vmax, vmax / RMIN, 1.0)
    return max(max(abs(x - y) for x, y in zip(sa[k], sb[k])) / scales[k] for sa, sb in zip(a, b) for k in range(4))


for around_zero, walls in ((True, True), (False, True), (True, False), (False, False)):
    ref = build("yade", around_zero, walls)
    got = build("ours", around_zero, walls)
    tag = "rotateAroundZero %s, %s, %d thread(s)" % (around_zero, "walls" if walls else "no walls", O.numThreads)
    if not walls:
        ck.true(build.ahead > 0 if parallel else build.ahead == 0,
                "%s: the PendularLoop set the velocities ahead in %d of %d steps (expected: some on two threads, none on one)"
                % (tag, build.ahead, STEPS))
    if parallel:
        ck.true(worst(ref, got) <= BOUND, "%s: within %g of RotationEngine (worst %.3g of the scale)" % (tag, BOUND, worst(ref, got)))
    else:
        ck.true(got == ref, "%s: positions, velocities, angular velocities and orientations bit-identical to RotationEngine's "
                "(worst difference %.3g of the scale)" % (tag, worst(ref, got)))
    moved = [b for b in O.bodies if b is not None and b.shape.__class__.__name__ == "Sphere" and b.state.blockedDOFs == "xyzXYZ"]
    ck.true(len(moved) == 9 and all(abs(b.state.angVel.norm() - 40.0) < 1e-12 for b in moved),
            "%s: the nine turned spheres spin at 40 rad/s (%s)" % (tag, [b.state.angVel.norm() for b in moved]))

stress.box_packing(50, "willett_full", rmin=RMIN, ratio=2.0, box="walls", porosity=0.85, speed=1.0, friction=0.3)
O.engines = scene.engines(extra=[PendularRotationEngine(ids=[3, 10 ** 6], angularVelocity=1.0)])
O.dt = scene.stable_dt(0.1)
ck.raises(ValueError, lambda: O.run(1, True), ["PendularRotationEngine", "ids[1] = 1000000", "not a body id"], "an id beyond the bodies")
# The same error where the loop sets the velocities ahead (no walls; on two threads): it leaves the step to the
# engine, which raises it.
packing(False, gravity=(0, 0, 0))
turner = PendularRotationEngine(ids=[3], angularVelocity=1.0)
O.engines = scene.engines(extra=[turner])
for e in O.engines:
    if hasattr(e, "parallelBodies"):
        e.parallelBodies = 0
O.dt = scene.stable_dt(0.1)
O.run(50, True)
before = turner.nAhead
ck.true(before > 0 if parallel else before == 0, "the loop set the velocities ahead in %d of the 50 steps before the error "
        "(expected: some on two threads, none on one)" % before)
turner.ids = [3, 10 ** 6]
ck.raises(ValueError, lambda: O.run(1, True), ["PendularRotationEngine", "ids[1] = 1000000", "not a body id"],
          "an id beyond the bodies, after %d steps set ahead" % before)
ck.true(turner.nAhead == before, "the failed step was not counted as set ahead (%d, then %d)" % (before, turner.nAhead))
for axis in ((0, 0, 0), (math.nan, 1, 0)):
    ck.raises(ValueError, lambda: PendularRotationEngine(rotationAxis=axis), ["PendularRotationEngine.rotationAxis", "nonzero finite"],
              "rotationAxis = %s" % (axis,))
ck.finish()
