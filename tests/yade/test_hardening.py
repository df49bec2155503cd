# Findings of a stress campaign, one block each: liquid totals across O.save/O.load, input
# errors scoped to their scene, pre-contact interactions that are never erased, nearly equal
# linear parameters, the interaction after a caught error, and the exception type of O.run.
import math
import os
import tempfile

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularCheck, PendularMat

from yade_capillary import cases, kernels
from yade_capillary.scene import engines
from yade_capillary.testing import Checker

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
    return [f for e in O.engines if e.__class__.__name__ == "InteractionLoop" for f in e.lawDispatcher.functors][0]


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

ck.finish()
