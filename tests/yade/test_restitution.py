# Dry binary collisions reproduce the normal restitution coefficient en within 1 % (en is
# defined with the no-attraction rule of Schwager & Poeschel 2007), for two
# free spheres and for a sphere against a fixed sphere (infinitely heavy partner).
from yade import O
from yade.wrapper import PendularMat

from collisions import head_on
from testing import Checker

ck = Checker("test_restitution")
R, tc = 1e-3, 1e-4
for en in (0.2, 0.5, 0.83, 0.95, 1.0):
    for partner in ("free", "fixed"):
        O.reset()
        O.dt = tc / 200
        mat = O.materials.append(PendularMat(tc=tc, en=en, et=0.9, density=2500, frictionAngle=0.0))
        touched, measured = head_on(mat, R, fixed_partner=(partner == "fixed"))
        ck.true(touched, "en=%g %s: the spheres collided" % (en, partner))
        ck.close(measured, en, 0.01, "restitution en=%g against a %s sphere" % (en, partner), "PendularMat.en")
        print("en = %.3f, %s partner: measured %.5f (rel. error %.2e)" % (en, partner, measured, abs(measured - en) / en))
ck.finish()
