# Findings of a stress campaign, one block each: liquid totals across O.save/O.load, input
# errors scoped to their scene, pre-contact interactions that are never erased, nearly equal
# linear parameters, the interaction after a caught error, and the exception type of O.run.
import math
import os
import tempfile

from yade import O
from yade.utils import sphere
from yade.wrapper import InteractionLoop, PendularCheck, PendularMat

from yade_capillary import cases, kernels
from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_hardening")
good = dict(tc=1e-4, en=0.8, et=0.8, density=2500, wet=True, Vb=1e-11, gamma=0.05, theta=0.2)
R = 1e-3


def pair(mat_a, mat_b, gap=-1e-9, fixed=True, eng=None):
    """Two spheres of radius R, surface gap `gap` [m]; returns their ids."""
    O.reset()
    O.dt = 1e-6
    a = O.materials.append(mat_a)
    b = O.materials.append(mat_b)
    i = O.bodies.append(sphere((0, 0, 0), R, material=a, fixed=fixed))
    j = O.bodies.append(sphere((2 * R + gap, 0, 0), R, material=b, fixed=fixed))
    O.engines = eng if eng is not None else engines()
    return i, j


def law():
    return [f for e in O.engines if isinstance(e, InteractionLoop) for f in e.lawDispatcher.functors][0]


# 1. The Law2 totals survive O.save/O.load; the rupture after the load keeps them consistent.
c = cases.case("W22")
info = kernels.bridge("willett_full", c.R1_m, c.R2_m, c.volume_m3, c.gamma_N_m, c.theta_rad)
O.reset()
O.dt = 1e-6
mat = O.materials.append(PendularMat(tc=2e-5, en=0.83, et=0.83, density=2500, wet=True, Vb=c.volume_m3, gamma=c.gamma_N_m,
                                     theta=c.theta_rad))
ids = [O.bodies.append(sphere((3 * k * c.R1_m, 0, 0), c.R1_m, material=mat, fixed=True)) for k in range(4)]
for k in (1, 3):  # two touching pairs: 0-1 and 2-3
    O.bodies[ids[k]].state.pos = (O.bodies[ids[k - 1]].state.pos[0] + 2 * c.R1_m - 1e-9, 0, 0)
O.engines = engines()
O.step()
before = (law().nBridges, law().liquidVolume, law().liquidFormed, law().liquidReleased)
ck.true(before[0] == 2, "two live bridges before O.save (nBridges = %d)" % before[0])
path = os.path.join(tempfile.mkdtemp(), "totals.yade.gz")
O.save(path)
O.load(path)
after = (law().nBridges, law().liquidVolume, law().liquidFormed, law().liquidReleased)
ck.true(after == before, "Law2 totals after O.load equal those before O.save: %s -> %s" % (before, after))
O.step()
O.bodies[ids[1]].state.pos = (O.bodies[ids[0]].state.pos[0] + 2 * c.R1_m + 1.01 * info["rupture"], 0, 0)
O.step()
L = law()
ck.true(L.nBridges == 1, "one bridge left after one rupture following O.load (nBridges = %d)" % L.nBridges)
ck.true(L.liquidVolume > 0, "liquid volume stays positive after the rupture (%g m^3)" % L.liquidVolume)
ck.close(L.liquidFormed - L.liquidReleased, L.liquidVolume, 1e-12, "liquidFormed - liquidReleased after O.load and rupture", "liquidVolume")

# 2. An input error stays with its scene: a scene without PendularCheck leaves no error behind
#    for the next scene after O.reset().
no_check = [e for e in engines() if not isinstance(e, PendularCheck)]
pair(PendularMat(**good), PendularMat(**dict(good, model="richefeu")), eng=no_check)
O.step()  # the error is printed and the run stops after this step; nothing raises it
pair(PendularMat(**good), PendularMat(**good))
try:
    O.step()
    ck.true(O.iter == 1, "a valid scene after O.reset() steps without the error of the previous scene")
except ValueError as e:
    ck.true(False, "a valid scene after O.reset() raised the previous scene's error: %s" % e)
# The same engine list reused after O.reset(): its stale error is not raised either.
shared = engines()
pair(PendularMat(**good), PendularMat(**dict(good, model="richefeu")), eng=shared)
ck.raises(ValueError, O.step, ["model"], "error raised in its own scene")
pair(PendularMat(**good), PendularMat(**good), eng=shared)
try:
    O.step()
    ck.true(True, "reused engine list on a valid scene")
except ValueError as e:
    ck.true(False, "reused engine list raised a stale error: %s" % e)

# 3. Pre-contact interactions (detection_factor > 1) are erased when the spheres move apart; a
#    pair that touches forms a bridge and keeps it until rupture.
for k in (1.0, 1.3, 2.0, 3.0):
    gap = 0.5 * (k - 1) * 2 * R if k > 1 else 0.0  # inside the detection range, not touching
    i, j = pair(PendularMat(**good), PendularMat(**good), gap=gap, eng=engines(detection_factor=k))
    for _ in range(3):
        O.step()
    for x in (4 * R, 8 * R, 10 * R):  # then apart: centres 6 diameters apart at the end
        O.bodies[j].state.pos = (2 * R + x, 0, 0)
        for _ in range(3):
            O.step()
    left = O.interactions.has(i, j)
    ck.true(not left, "detection_factor %g: no interaction left 5 diameters apart (has=%s, real=%s)"
            % (k, left, left and O.interactions[i, j].isReal))
    # touching pair: bridge forms and lives until rupture
    i, j = pair(PendularMat(**good), PendularMat(**good), gap=-1e-9, eng=engines(detection_factor=k))
    O.step()
    I = O.interactions[i, j]
    ck.true(I.isReal and I.phys.active, "detection_factor %g: touching pair forms a bridge" % k)
    sc = I.phys.sCrit
    O.bodies[j].state.pos = (2 * R + 0.9 * sc, 0, 0)
    O.step()
    ck.true(O.interactions.has(i, j) and O.interactions[i, j].isReal and O.interactions[i, j].phys.active,
            "detection_factor %g: bridge alive at 0.9 sCrit" % k)
    O.bodies[j].state.pos = (2 * R + 1.1 * sc, 0, 0)
    O.step()
    O.step()
    ck.true(not (O.interactions.has(i, j) and O.interactions[i, j].isReal), "detection_factor %g: no real interaction after rupture beyond sCrit" % k)

# 4. linear_irreversible parameters are compared by value: 1e-7 N and 4e-7 N differ.
lin = dict(good, model="linear_irreversible", linearKc=1.0)
pair(PendularMat(**dict(lin, linearFmax=1e-7)), PendularMat(**dict(lin, linearFmax=4e-7)))
ck.raises(ValueError, O.step, ["linearFmax", "1e-07", "4e-07"], "linearFmax 1e-7 vs 4e-7 N")
pair(PendularMat(**dict(lin, linearFmax=1e-7, linearKc=1e-7)), PendularMat(**dict(lin, linearFmax=1e-7, linearKc=3e-7)))
ck.raises(ValueError, O.step, ["linearKc", "1e-07", "3e-07"], "linearKc 1e-7 vs 3e-7 N/m")
pair(PendularMat(**dict(lin, linearFmax=1e-7)), PendularMat(**dict(lin, linearFmax=1e-7)))
O.step()
ck.true(O.interactions[0, 1].phys.active, "equal linear parameters form a bridge")


# 5. After a caught error the pair is not inert: with valid contact parameters the spheres
#    bounce (no bridge); with invalid contact parameters the error is raised again.
def approach(mat_a, mat_b, steps=400):
    """Two free spheres approaching at 0.1 m/s; returns (errors caught, final relative velocity, min distance)."""
    pair(mat_a, mat_b, gap=2e-6, fixed=False)
    O.dt = 1e-6
    O.bodies[0].state.vel = (0.1, 0, 0)
    O.bodies[1].state.vel = (-0.1, 0, 0)
    errors, dmin = 0, float("inf")
    for _ in range(steps):
        try:
            O.step()
        except ValueError:
            errors += 1
        dmin = min(dmin, O.bodies[1].state.pos[0] - O.bodies[0].state.pos[0])
    return errors, O.bodies[1].state.vel[0] - O.bodies[0].state.vel[0], dmin


errors, vrel, dmin = approach(PendularMat(**good), PendularMat(**dict(good, model="richefeu")))
ck.true(errors >= 1, "bridge refused: the error is raised (%d times)" % errors)
ck.true(vrel > 0, "bridge refused, contact parameters valid: the spheres bounce (relative velocity %g m/s)" % vrel)
ck.true(dmin > 2 * R * 0.99, "no pass-through (closest centre distance %g m)" % dmin)
errors, vrel, dmin = approach(PendularMat(**good), PendularMat(wet=True, Vb=1e-11, gamma=0.05, density=2500), steps=60)
ck.true(errors >= 40, "contact parameters invalid: the error is raised at every step after contact (%d of 60, contact at ~10)" % errors)

# 6. O.run(n, True) raises ValueError naming the parameter, like O.step().
pair(PendularMat(**good), PendularMat(**dict(good, model="richefeu")))
ck.raises(ValueError, lambda: O.run(5, True), ["model", "richefeu"], "O.run(5, True) with different models")
pair(PendularMat(**good), PendularMat(**dict(good, rupture="lian")))
O.run(5)
ck.raises(ValueError, O.wait, ["rupture", "lian"], "O.run(5); O.wait() with different rupture rules")
# Other exceptions keep their Python type: the translator only converts PendularCheck's errors.
ck.raises(RuntimeError, lambda: O.load("/nonexistent/scene.yade.gz"), ["doesn't exist"], "O.load of a missing file: RuntimeError")
ck.raises(IndexError, lambda: O.bodies[1000], [], "O.bodies[1000]: IndexError")
# After a caught error, O.run() continues to the stopAtIter the user set (the error does not move it).
pair(PendularMat(**good), PendularMat(**dict(good, model="richefeu")))
O.stopAtIter = 10
O.run()
ck.raises(ValueError, O.wait, ["model"], "O.run() with different models")
O.run()
O.wait()
ck.true(O.iter == 10, "O.run() after a caught error stops at the stopAtIter set before (iter %d, expected 10)" % O.iter)
ck.finish()
