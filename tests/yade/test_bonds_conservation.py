# Exact conservation of the liquid shared over bonds (PendularMat.liquid = 'bonds') over whole runs, under
# each protocol: a gas of spheres in a box, bonds sharing, breaking and forming all the time, bodies erased
# and the scene saved and loaded mid-run. films + bonds + liquidRemoved must stay constant to 1e-12
# relative (rounding only), every free volume non-negative, every bond within its debonding distance after
# a sharing, every force finite. Run by ctest with -j1 and, for two protocols, with -j2.
#   yade-capillary -jN -n -x test_bonds_conservation.py [update|particles|lowest|neighbours] [fused|standard]
import random
import sys

from yade import O
from yade.utils import sphere, wall
from yade.wrapper import PendularBonds, PendularMat

from yade_capillary import bonds as wetting
from yade_capillary.scene import engines, stable_dt
from liquid_checks import conserved
from testing import Checker

protocol = sys.argv[1] if len(sys.argv) > 1 else "update"
loop = sys.argv[2] if len(sys.argv) > 2 else "fused"
ck = Checker("test_bonds_conservation (%s, %s loop, %d threads)" % (protocol, loop, O.numThreads))
rng = random.Random(5)  # private: utils.sphere draws random colours from the shared generator
BOX, N = 0.02, 240
mat = PendularMat(tc=2e-4, en=0.7, et=0.7, density=2500, frictionAngle=0.3, Vb=1e-6, gamma=0.073, theta=0.0, model="richefeu",
                  rupture="lian", liquid="bonds")
mat.wet = True
O.materials.append(mat)
for axis in range(3):
    for side in (0, BOX):
        O.bodies.append(wall(side, axis=axis, sense=1 if side == 0 else -1, material=mat))
spheres = []
for i in range(N):
    r = rng.uniform(0.6e-3, 1.0e-3)
    c = tuple(rng.uniform(r, BOX - r) for _ in range(3))
    b = O.bodies.append(sphere(c, r, material=mat))
    O.bodies[b].state.vel = tuple(rng.gauss(0, 0.3) for _ in range(3))
    spheres.append(b)
bonds = PendularBonds(protocol=protocol, dryFraction=0.2, seed=3)
O.engines = engines(loop=loop, gravity=(0, 0, -9.81), extra=[bonds])
collider = [e for e in O.engines if e.label == "collider"][0]
collider.verletDist = 0.5e-3  # lists every pair within the longest debonding distance
O.dt = stable_dt()
O.step()
wetting.share_water(0.0002)  # 0.02 % water content over the few close pairs of a gas
law = O.engines[2].lawDispatcher.functors[0]
total0 = law.liquidTotals()["total"]
ck.true(total0 > 0 and bonds.nShared > 0, "some liquid on some bonds (%d bonds, alpha %.3g)" % (bonds.nShared, bonds.alpha))
within = [-I.geom.penetrationDepth <= I.phys.sCrit * (1 + 1e-12) for I in O.interactions if I.isReal and I.phys.active]
ck.true(len(within) == bonds.nShared and all(within), "every bond of the sharing within its debonding distance (rule iii)")


def check(where):
    return conserved(ck, law, total0, where)


sharings0 = bonds.nSharings
for block in range(12):
    O.run(250, True)
    t = check("step %d" % O.iter)
    if block == 4:
        held = {i for I in O.interactions if I.isReal and I.phys.active for i in (I.id1, I.id2)}
        wet = [b for b in spheres if O.bodies[b].state.film > 0 or b in held][:2]  # two spheres that hold liquid
        for b in wet:
            spheres.remove(b)
            O.bodies.erase(b)
        check("after erase")
    if block == 7:
        O.save("/tmp/test_bonds_conservation.yade.gz")
        O.load("/tmp/test_bonds_conservation.yade.gz")
        law = O.engines[2].lawDispatcher.functors[0]
        bonds = [e for e in O.engines if isinstance(e, PendularBonds)][0]
        check("after save/load")
print("liquid: free %.4g, bonds %.4g, removed %.4g m^3; %d bonds now; sharings %d, placed %d, free %d" %
      (t["films"], t["bridges"], t["removed"], law.nBridges, bonds.nSharings, bonds.nPlaced, bonds.nFree))
ck.true(law.liquidReleased > 0, "bonds broke during the run")
ck.true(t["removed"] > 0, "the erased bodies took liquid with them")
if protocol == "update":
    ck.true(bonds.nSharings > sharings0 + 3, "protocol 1: sharings at the collider's runs (%d)" % bonds.nSharings)
if protocol in ("lowest", "neighbours"):
    ck.true(bonds.nPlaced > 0, "%s: shares placed into other bonds (%d)" % (protocol, bonds.nPlaced))
ck.finish()
