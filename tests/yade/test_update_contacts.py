# Ip2_PendularMat_PendularMat_PendularPhys.updateContacts(): existing interactions take the contact parameters
# of their materials again (Richefeu2008 section 3.2.1: consolidated without friction, then mu = 0.4). Two
# spheres slide over each other: frictionless, no tangential force; after frictionAngle = 0.4 and
# updateContacts, the Coulomb force mu f_n. In the fused loop (whose records keep the old parameters until
# they are dropped) and in YADE's InteractionLoop. A refused pair changes nothing.
import math

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_update_contacts")
R = 1e-3
for loop in ("fused", "standard"):
    O.reset()
    m = O.materials.append(PendularMat(kn=2000.0, cn=0.0, ks=600.0, cs=0.0, density=2500, frictionAngle=0.0))
    a = O.bodies.append(sphere((0, 0, 0), R, material=m, fixed=True))
    b = O.bodies.append(sphere((2 * R - 2e-6, 0, 0), R, material=m, fixed=True))
    O.bodies[b].state.vel = (0, 0.05, 0)  # sliding along y, the overlap held (to second order)
    O.engines = engines(loop=loop)
    O.dt = 1e-6
    O.run(20, True)
    ck.true(O.interactions[a, b].phys.shearForce.norm() == 0, "%s: frictionless: no tangential force" % loop)
    O.materials[m].frictionAngle = 0.4
    ip2 = [f for e in O.engines if hasattr(e, "physDispatcher") for f in e.physDispatcher.functors][0]
    ck.true(ip2.updateContacts() == 1, "%s: one interaction updated" % loop)
    p = O.interactions[a, b].phys
    ck.close(p.tangensOfFrictionAngle, math.tan(0.4), 1e-15, "%s: the new friction coefficient" % loop, "tan(frictionAngle)")
    O.run(200, True)  # the spring loads by ks v dt = 1.5e-5 N per step to the cap mu f_n = 8.5e-4 N in about 60 steps
    p = O.interactions[a, b].phys
    ck.close(p.shearForce.norm(), math.tan(0.4) * p.normalForce.norm(), 1e-9, "%s: sliding at the Coulomb force mu f_n" % loop,
             "Gladkyy2014 eq. (4), Coulomb cap")
    # Refused: a change that the pair cannot take leaves every parameter as it was.
    O.materials[m].frictionAngle = 0.2
    O.materials[m].kn = float("nan")  # neither (tc, en, et) nor (kn, cn, ks, cs) complete
    ck.raises(ValueError, ip2.updateContacts, "give either", "%s: refused parameters" % loop)
    ck.close(O.interactions[a, b].phys.tangensOfFrictionAngle, math.tan(0.4), 1e-15, "%s: nothing changed after a refusal" % loop, "the last update")
ck.finish()
