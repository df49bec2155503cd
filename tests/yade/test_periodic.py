# Periodic cells: a contact across the boundary of a sheared cell feels the same force as the same
# contact inside the cell. Body 2's periodic image moves with vel2 + shiftVel (ScGeom::getIncidentVel);
# the law used vel2 - shiftVel before (a sign error inherited from the ViscElPhys convention), which
# gave the boundary pair a tangential velocity off by twice the shear rate times the cell size.
from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_periodic")
L, R, rate = 0.01, 1e-3, 5.0  # cell size [m], radius [m], shear rate dvx/dy [1/s]
d = 2 * R - 1e-5  # centre distance: overlap 1e-5 m


def run(loop, wet):
    O.reset()
    O.periodic = True
    O.cell.setBox(L, L, L)
    O.cell.velGrad = ((0, rate, 0), (0, 0, 0), (0, 0, 0))
    O.dt = 1e-7
    m = O.materials.append(PendularMat(tc=1e-4, en=0.8, et=0.8, density=2500, frictionAngle=0.5, wet=wet, Vb=1e-12, gamma=0.05))
    # Pair A across the y boundary (the image of b lies d below a); pair B inside, d apart likewise.
    pos = {"a": (0.003, 0.0005, 0.005), "b": (0.003, 0.0005 - d + L, 0.005), "c": (0.007, 0.006, 0.005), "d": (0.007, 0.006 - d, 0.005)}
    ids = {}
    for k in "abcd":
        # At rest: NewtonIntegrator (homoDeform) gives every body the velocity of the shear flow,
        # vx = rate y, from the first step on.
        ids[k] = O.bodies.append(sphere(pos[k], R, material=m, fixed=True))
    O.engines = engines(loop=loop)
    for _ in range(3):
        O.step()
    return ids


for loop in ("fused", "standard"):
    for wet in (False, True):
        ids = run(loop, wet)
        IA, IB = O.interactions[ids["a"], ids["b"]], O.interactions[ids["c"], ids["d"]]
        fa, fc = O.forces.f(ids["a"]), O.forces.f(ids["c"])
        scale = fc.norm()
        what = "%s wet=%s" % (loop, wet)
        ck.true(IA.isReal and IB.isReal and tuple(IA.cellDist) != (0, 0, 0), what + ": both pairs in contact, pair A across the boundary")
        ck.true(IB.phys.shearForce.norm() > 0, what + ": the shear flow loads the tangential spring")
        for k in range(3):
            ck.close(fa[k], fc[k], 0, "%s: force[%d] across the boundary" % (what, k), "the same pair inside the cell", atol=1e-9 * scale)
            ck.close(IA.phys.shearForce[k], IB.phys.shearForce[k], 0, "%s: shearForce[%d] across the boundary" % (what, k),
                     "the same pair inside the cell", atol=1e-9 * scale)
ck.finish()
