# Rolling friction (PendularMat.rollingFriction = mu_roll [m], Elskamp2018 Table 3): a moment of constant
# magnitude mu_roll f_n against the relative rolling.
# 1. One step of two touching fixed spheres, in the fused loop and in YADE's InteractionLoop: the moments
#    are -/+ mu_roll f_n along the relative rolling, and the spin about the normal is not resisted.
# 2. A sphere rolling on a plane decelerates at mu_roll g / (r (1 + I/(m r^2))), the closed form for a
#    constant resisting moment, at two initial speeds: a torque growing with the rolling speed (YADE's
#    ViscEl mRtype=1, which discards relAngVel.normalized()) would decelerate twice as fast at twice the speed.
import math

from yade import O
from yade.utils import sphere, wall
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_rolling_friction")
R, rho, mu_roll = 2.5e-3, 1400.0, 1e-4

for loop in ("fused", "standard"):
    for omega, what in (((0, 0, 30.0), "rolling"), ((30.0, 0, 0), "spin about the normal")):
        O.reset()
        O.dt = 1e-6
        m = O.materials.append(PendularMat(kn=500.0, cn=0.0, ks=100.0, cs=0.0, density=rho, frictionAngle=0.0, rollingFriction=mu_roll))
        a = O.bodies.append(sphere((0, 0, 0), R, material=m, fixed=True))
        b = O.bodies.append(sphere((2 * R - 1e-6, 0, 0), R, material=m, fixed=True))
        O.bodies[a].state.angVel = omega
        O.engines = engines(loop=loop)
        O.step()
        p = O.interactions[a, b].phys
        ck.close(p.rollingFriction, mu_roll, 1e-15, "%s: the pair's mu_roll" % loop, "PendularMat.rollingFriction (equal materials)")
        fn = p.kn * 1e-6
        expected = -mu_roll * fn if what == "rolling" else 0.0
        # Body 1 spins about z (rolling: the normal is x) or x (spin); without sliding friction the torques
        # are the rolling moments alone.
        axis = 2 if what == "rolling" else 0
        ck.close(O.forces.t(a)[axis], expected, 1e-9, "%s, %s: moment on body 1" % (loop, what), "-mu_roll f_n along the relative rolling",
                 atol=1e-20)
        ck.close(O.forces.t(b)[axis], -expected, 1e-9, "%s, %s: moment on body 2" % (loop, what), "the opposite moment", atol=1e-20)

# 2. Rolling on a plane under gravity, started in rolling without slip (omega = v/r about y for motion along +x).
g = 9.81
mass = rho * 4 / 3 * math.pi * R ** 3
decel = mu_roll * g / (R * (1 + 0.4))  # I = 2/5 m r^2
measured = {}
for v0 in (0.02, 0.04):
    O.reset()
    tc = 1e-4
    O.dt = tc / 40
    m = O.materials.append(PendularMat(tc=tc, en=0.5, et=0.5, density=rho, frictionAngle=0.5, rollingFriction=mu_roll))
    O.bodies.append(wall((0, 0, 0), axis=2, material=m))
    s = O.bodies.append(sphere((0, 0, R), R, material=m))
    O.engines = engines(gravity=(0, 0, -g))
    O.run(4000, True)  # settle on the plane (the normal oscillation decays in a few tc)
    O.bodies[s].state.vel = (v0, 0, 0)
    O.bodies[s].state.angVel = (0, v0 / R, 0)
    O.run(200, True)  # the tangential spring takes up the rolling moment
    t0, x0 = O.time, O.bodies[s].state.vel[0]
    span = 0.5 * v0 / decel  # half of the stopping time
    O.run(int(span / O.dt), True)
    measured[v0] = (x0 - O.bodies[s].state.vel[0]) / (O.time - t0)
    ck.close(measured[v0], decel, 1e-3, "deceleration from v0 = %g m/s" % v0, "mu_roll g / (r (1 + I/(m r^2)))")
    ck.close(O.bodies[s].state.angVel[1] * R, O.bodies[s].state.vel[0], 1e-3, "still rolling without slip at v0 = %g m/s" % v0,
             "the contact point at rest")
    print("v0 = %.2f m/s: deceleration %.5f m/s^2, closed form %.5f" % (v0, measured[v0], decel))
ck.close(measured[0.04], measured[0.02], 1e-3, "deceleration independent of the speed", "a moment of constant magnitude")
ck.finish()
