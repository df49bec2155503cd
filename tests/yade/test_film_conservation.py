# Exact conservation of the liquid in film mode (PendularMat.liquid = 'film') over whole runs: a gas of
# wet and dry spheres in a box whose walls hold films, with bridges forming and breaking all the time,
# bodies erased and the scene saved and loaded mid-run. films + bridges + liquidRemoved must stay
# constant to 1e-12 relative (rounding only), every film non-negative, every force finite; the dry
# spheres must gain liquid. Run by ctest with -j1 and with -j2 (no races on a particle's film: the
# films are written only at the end of the step, serially).
#   yade-capillary -jN -n -x test_film_conservation.py [fused|standard] [contact|films]
import math
import random
import sys

from yade import O
from yade.utils import sphere, wall
from yade.wrapper import PendularMat

from yade_capillary.scene import engines, stable_dt
from liquid_checks import conserved
from testing import Checker

loop = sys.argv[1] if len(sys.argv) > 1 else "fused"
formation = sys.argv[2] if len(sys.argv) > 2 else "contact"
ck = Checker("test_film_conservation (%s loop, formation %s, %d threads)" % (loop, formation, O.numThreads))
rng = random.Random(7)  # private: utils.sphere draws random colours from the shared generator
BOX, N = 0.02, 240
mat = PendularMat(tc=2e-4, en=0.7, et=0.7, density=2500, frictionAngle=0.3, wet=True, Vb=1e-6, gamma=0.072,
                  theta=math.radians(15), model="willett_full", liquid="film", formation=formation, transfer="exact")
O.materials.append(mat)
for axis in range(3):
    for side in (0, BOX):
        w = O.bodies.append(wall(side, axis=axis, sense=1 if side == 0 else -1, material=mat))
        if axis == 2 and side == 0:  # the floor is wettable and wet; the other walls hold no film
            O.bodies[w].state.filmArea = BOX * BOX
            O.bodies[w].state.film = 1e-9
wet, dry = [], []
for i in range(N):
    r = rng.uniform(0.6e-3, 1.0e-3)
    c = tuple(rng.uniform(r, BOX - r) for _ in range(3))
    b = O.bodies.append(sphere(c, r, material=mat))
    O.bodies[b].state.vel = tuple(rng.gauss(0, 0.3) for _ in range(3))
    if i % 2 == 0:
        O.bodies[b].state.film = 0.01 * 4 / 3 * math.pi * r ** 3  # 1 % of the particle volume
        wet.append(b)
    else:
        dry.append(b)
O.engines = engines(loop=loop, detection_factor=1.05 if formation == "films" else 1.0)
O.dt = stable_dt()
law = O.engines[2].lawDispatcher.functors[0]
total0 = law.liquidTotals()["total"]
ck.true(total0 > 0, "some liquid to conserve")


def check(where):
    return conserved(ck, law, total0, where)


formed = 0
for block in range(12):
    O.run(250, True)
    t = check("step %d" % O.iter)
    if block == 4:  # erase a wet and a dry sphere with their bridges
        for b in (wet.pop(), dry.pop()):
            O.bodies.erase(b)
        check("after erase")
    if block == 7:
        O.save("/tmp/test_film_conservation.yade.gz")
        O.load("/tmp/test_film_conservation.yade.gz")
        law = O.engines[2].lawDispatcher.functors[0]
        check("after save/load")
print("liquid: films %.4g, bridges %.4g, removed %.4g m^3; bridges formed %.4g m^3, %d bridges now" %
      (t["films"], t["bridges"], t["removed"], law.liquidFormed, law.nBridges))
ck.true(law.liquidFormed > 0 and law.liquidReleased > 0, "bridges formed and broke during the run")
ck.true(t["removed"] > 0, "the erased bodies took liquid with them")
ck.true(sum(O.bodies[b].state.film for b in dry) > 0, "the dry population gained liquid")
ck.finish()
