# Class-layout check: the plugin is compiled against YADE 2025.2.0 headers and runs in Debian's
# YADE 2023.02a. C++ must read exactly what Python set. After one step of two touching spheres,
# the contact force, torques and stiffnesses are recomputed here from the values set in Python
# (positions, velocities, angular velocities, masses from density, material parameters, O.dt)
# with the formulas of Gladkyy 2014 eq. (3); any layout drift would change them. Tolerance 1e-9:
# the overlap (2 um) is the difference of positions of order 0.3 m, which costs ~1e-10 relative.
import math

import numpy as np
from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_layout")
R1, R2 = 1.1e-3, 0.7e-3
p1 = np.array([0.1, -0.2, 0.3])
n = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
delta = 2e-6
p2 = p1 + (R1 + R2 - delta) * n
v1, v2 = np.array([0.02, 0.01, -0.03]), np.array([-0.01, 0.04, 0.02])
w1, w2 = np.array([3.0, -1.0, 2.0]), np.array([-2.0, 0.5, 1.0])
dt = 3.7e-7


def setup(mat1, mat2):
    O.reset()
    O.dt = dt
    m1 = O.materials.append(mat1)
    m2 = m1 if mat2 is mat1 else O.materials.append(mat2)
    a = O.bodies.append(sphere(tuple(p1), R1, material=m1))
    b = O.bodies.append(sphere(tuple(p2), R2, material=m2))
    for bid, v, w in ((a, v1, w1), (b, v2, w2)):
        O.bodies[bid].state.vel, O.bodies[bid].state.angVel = tuple(v), tuple(w)
    O.engines = engines()
    O.step()
    return a, b


def expected_force(kn, cn, ks, cs):
    """Force on body 2: kn delta + cn vn along n, ks dt vs + cs vs tangentially (first step, no slip)."""
    cp = p1 + (R1 - delta / 2) * n  # ScGeom contact point: middle of the overlap
    rel = (v1 + np.cross(w1, cp - p1)) - (v2 + np.cross(w2, cp - p2))
    vn = rel.dot(n)
    vs = rel - vn * n
    f = (kn * delta + cn * vn) * n + (ks * dt + cs) * vs
    return f, cp


# Explicit stiffnesses: combined in series (documented mixing rule of the Ip2).
mA = PendularMat(kn=2.0e4, cn=0.3, ks=0.8e4, cs=0.1, frictionAngle=1.5, density=2600)
mB = PendularMat(kn=3.0e4, cn=0.5, ks=1.2e4, cs=0.2, frictionAngle=1.4, density=2400)
a, b = setup(mA, mB)
ser = lambda x, y: x * y / (x + y)
kn, cn, ks, cs = ser(2.0e4, 3.0e4), ser(0.3, 0.5), ser(0.8e4, 1.2e4), ser(0.1, 0.2)
ph = O.interactions[a, b].phys
for name, val in (("kn", kn), ("cn", cn), ("ks", ks), ("cs", cs)):
    ck.close(getattr(ph, name), val, 1e-14, "phys." + name, "series combination of the material values")
ck.close(ph.tangensOfFrictionAngle, math.tan(1.4), 1e-14, "tan(friction angle)", "smaller material friction angle")
f, cp = expected_force(kn, cn, ks, cs)
F2 = np.array(O.forces.f(b))
ck.close(np.linalg.norm(F2 - f), 0.0, 0, "force on body 2 from positions, velocities, dt", "Gladkyy eq. (3)", atol=1e-9 * np.linalg.norm(f))
ck.close(np.linalg.norm(np.array(O.forces.f(a)) + f), 0.0, 0, "force on body 1", "Newton's third law", atol=1e-9 * np.linalg.norm(f))
ck.close(np.linalg.norm(np.array(O.forces.t(a)) - np.cross(cp - p1, -f)), 0.0, 0, "torque on body 1", "(c - x1) x (-F)",
         atol=1e-9 * np.linalg.norm(f) * R1)
ck.close(np.linalg.norm(np.array(O.forces.t(b)) - np.cross(cp - p2, f)), 0.0, 0, "torque on body 2", "(c - x2) x F",
         atol=1e-9 * np.linalg.norm(f) * R2)

# tc, en, et: masses from density, kn = m (pi/tc)^2 (1 + x^2), cn = 2 m (pi/tc) x, where x solves
# en = exp(-x (pi - 2 atan x)) (Schwager & Poeschel 2007), solved here by bisection.
tc, en, et = 2e-4, 0.7, 0.6
mat = PendularMat(tc=tc, en=en, et=et, frictionAngle=1.5, density=2500)
a, b = setup(mat, mat)
m1, m2 = 2500 * 4 / 3 * math.pi * R1 ** 3, 2500 * 4 / 3 * math.pi * R2 ** 3
ck.close(O.bodies[a].state.mass, m1, 1e-14, "mass of body 1", "rho 4/3 pi R^3")
mr = m1 * m2 / (m1 + m2)
lo, hi = 0.0, 100.0
for _ in range(200):
    mid = (lo + hi) / 2
    lo, hi = (mid, hi) if mid * (math.pi - 2 * math.atan(mid)) < -math.log(en) else (lo, mid)
x, w, xt = lo, math.pi / tc, -math.log(et) / math.pi
kn, cn = mr * w * w * (1 + x * x), 2 * mr * w * x
ks, cs = 2 / 7 * mr * w * w * (1 + xt * xt), 2 / 7 * 2 * mr * w * xt
ph = O.interactions[a, b].phys
for name, val in (("kn", kn), ("cn", cn), ("ks", ks), ("cs", cs)):
    ck.close(getattr(ph, name), val, 1e-12, "phys.%s from tc, en, et" % name, "Schwager & Poeschel 2007 / YADE ViscElMat tangential rule")
f, cp = expected_force(kn, cn, ks, cs)
ck.close(np.linalg.norm(np.array(O.forces.f(b)) - f), 0.0, 0, "force from tc, en, et", "Gladkyy eq. (3)", atol=1e-9 * np.linalg.norm(f))
ck.finish()
