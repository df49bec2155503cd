# Time step: yade_capillary.scene.stable_dt against the analytic stability limit of YADE's
# leapfrog for a linear spring-dashpot, dt_c = (2/w0)(sqrt(1 + z^2) - z) with w0^2 = k/m and
# z = c/(2 sqrt(k m)) (Belytschko, Liu & Moran 2000, Nonlinear Finite Elements, sec. 6.3), normal
# and tangential (m_t = 2/7 m for solid spheres), and PendularCheck's warning when O.dt is too large.
import math

from yade import O
from yade.utils import sphere, wall
from yade.wrapper import PendularMat

from yade_capillary.scene import engines, stable_dt
from collisions import damping_ratio, through_contact
from stress import oscillator_limit as limit
from testing import Checker

ck = Checker("test_timestep")
R, rho = 1e-3, 2500.0
mass = rho * 4 / 3 * math.pi * R ** 3


def expected_tc(tc, en, et, m):
    """Two-body limit of a pair with effective mass m given by tc, en, et (mixing as in the Ip2)."""
    w, x, xt = math.pi / tc, damping_ratio(en), -math.log(et) / math.pi
    kn, cn = m * w * w * (1 + x * x), 2 * m * w * x
    ks, cs = 2 / 7 * m * w * w * (1 + xt * xt), 2 / 7 * 2 * m * w * xt
    return min(limit(kn, cn, m), limit(ks, cs, 2 / 7 * m))


def scene(mat, partner, dt=1e-7):
    O.reset()
    O.dt = dt
    m = O.materials.append(mat)
    if partner == "wall":
        O.bodies.append(wall((-R, 0, 0), axis=0, material=m))
    else:
        O.bodies.append(sphere((0, 0, 0), R, material=m, fixed=(partner == "fixed sphere")))
    O.bodies.append(sphere((2 * R + 1e-6, 0, 0), R, material=m))
    O.engines = engines()


tc, en, et = 1e-4, 0.83, 0.6
for partner, m_eff in (("free sphere", mass / 2), ("fixed sphere", mass), ("wall", mass)):
    scene(PendularMat(tc=tc, en=en, et=et, density=rho), partner)
    ck.close(stable_dt(safety=1.0), expected_tc(tc, en, et, m_eff), 1e-12, "two-body limit, tc given, %s" % partner,
             "(2/w0)(sqrt(1+z^2)-z), normal and tangential")
    ck.close(stable_dt(safety=0.1), 0.1 * expected_tc(tc, en, et, m_eff), 1e-12, "stable_dt(0.1), %s" % partner, "0.1 x limit")
kn, cn, ks, cs = 50.0, 2e-3, 20.0, 1e-3
for partner, m_eff in (("free sphere", mass / 2), ("wall", mass)):
    scene(PendularMat(kn=2 * kn, cn=2 * cn, ks=2 * ks, cs=2 * cs, density=rho), partner)  # in series: kn, cn, ks, cs
    ck.close(stable_dt(safety=1.0), min(limit(kn, cn, m_eff), limit(ks, cs, 2 / 7 * m_eff)), 1e-12,
             "two-body limit, kn given, %s" % partner, "(2/w0)(sqrt(1+z^2)-z) with the effective masses")
# Two materials and spheres of two sizes: the lightest pair sets the limit.
O.reset()
a = O.materials.append(PendularMat(kn=100.0, cn=0.0, ks=0.0, cs=0.0, density=rho))
b = O.materials.append(PendularMat(kn=300.0, cn=0.0, ks=0.0, cs=0.0, density=rho))
O.bodies.append([sphere((0, 0, 0), R, material=a), sphere((1, 0, 0), 2 * R, material=a), sphere((2, 0, 0), 0.5 * R, material=b),
                 sphere((3, 0, 0), R, material=b, fixed=True)])
m_small = mass / 8
cands = {"a-a": (100.0 / 2, mass * 8 * mass / (9 * mass)), "a-b": (75.0, mass * m_small / (mass + m_small)),
         "a-b (fixed partner)": (75.0, mass), "b-b (fixed partner)": (150.0, m_small)}
ck.close(stable_dt(safety=1.0), min(limit(k, 0.0, m) for k, m in cands.values()), 1e-12, "two materials, three sizes",
         "smallest limit over material pairs and lightest bodies")


def collide(dt, en=0.83, steps_max=100000):
    """Two free spheres, head-on at 0.05 m/s each; returns (measured restitution, PendularCheck)."""
    scene(PendularMat(tc=tc, en=en, et=0.9, density=rho, frictionAngle=0.0), "free sphere", dt=dt)
    O.bodies[0].state.vel = (0.05, 0, 0)
    O.bodies[1].state.vel = (-0.05, 0, 0)
    through_contact(steps_max)
    check = [e for e in O.engines if e.__class__.__name__ == "PendularCheck"][0]
    return (O.bodies[1].state.vel[0] - O.bodies[0].state.vel[0]) / 0.1, check


e_meas, check = collide(tc / 2)
ck.true(check.dtWarnings == 1, "dt = tc/2: PendularCheck warned once (dtWarnings = %d)" % check.dtWarnings)
ck.close(check.criticalDt, expected_tc(tc, en, 0.9, mass / 2), 1e-12, "PendularCheck.criticalDt", "two-body limit")
scene(PendularMat(tc=tc, en=en, et=0.9, density=rho, frictionAngle=0.0), "free sphere")
dt = stable_dt()
e_meas, check = collide(dt)
ck.true(check.dtWarnings == 0, "dt = stable_dt() = tc/%.1f: no warning (dtWarnings = %d)" % (tc / dt, check.dtWarnings))
ck.close(e_meas, en, 0.01, "restitution at dt = stable_dt()", "PendularMat.en (energy after/before = en^2)")
print("dt = stable_dt() = tc/%.2f: restitution %.5f for en = %g" % (tc / dt, e_meas, en))
ck.finish()
