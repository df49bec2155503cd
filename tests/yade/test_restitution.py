# Dry binary collisions reproduce the normal restitution coefficient en within 1 % (en is
# defined with the no-attraction rule of Schwager & Poeschel 2007), for two
# free spheres and for a sphere against a fixed sphere (infinitely heavy partner).
from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_restitution")
R, tc = 1e-3, 1e-4
for en in (0.2, 0.5, 0.83, 0.95, 1.0):
    for partner in ("free", "fixed"):
        O.reset()
        O.dt = tc / 200
        mat = O.materials.append(PendularMat(tc=tc, en=en, et=0.9, density=2500, frictionAngle=0.0))
        a = O.bodies.append(sphere((0, 0, 0), R, material=mat, fixed=(partner == "fixed")))
        b = O.bodies.append(sphere((2 * R + 1e-6, 0, 0), R, material=mat))
        v0 = 0.05
        O.bodies[b].state.vel = (-v0, 0, 0)
        if partner == "free":
            O.bodies[a].state.vel = (v0, 0, 0)
        O.engines = engines()
        touched = False
        for _ in range(20000):
            O.step()
            touched = touched or O.interactions.countReal() > 0
            if touched and O.interactions.countReal() == 0:
                break
        ck.true(touched, "en=%g %s: the spheres collided" % (en, partner))
        before = 2 * v0 if partner == "free" else v0
        after = O.bodies[b].state.vel[0] - O.bodies[a].state.vel[0]
        ck.close(after / before, en, 0.01, "restitution en=%g against a %s sphere" % (en, partner), "PendularMat.en")
        print("en = %.3f, %s partner: measured %.5f (rel. error %.2e)" % (en, partner, after / before, abs(after / before - en) / en))
ck.finish()
