# Richefeu et al. 2008's contact law as options of PendularMat, against its printed equations:
# normalDamping='approach' (eq. 3: the normal dashpot acts only while the particles approach) and
# friction='viscous' (eq. 12: f_t = -min(gamma_t |v_t|, mu (f_n - f_n^c)) v_t/|v_t|, no tangential spring),
# in the fused loop and in YADE's InteractionLoop; and the restitution of the approach-only law
# in a free binary collision against its closed form en = exp(-x atan(1/x)), x = beta/omega.
import math

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from collisions import damping_ratio, head_on
from testing import Checker

ck = Checker("test_richefeu_contact")
R, rho, tc = 1e-3, 2500.0, 1e-4
mass = rho * 4 / 3 * math.pi * R ** 3


def pair(loop, overlap, vel2, **mat):
    """Two fixed spheres along x, body 2 overlapping by `overlap` and moving at vel2: one step."""
    O.reset()
    O.dt = tc / 200
    m = O.materials.append(PendularMat(density=rho, **mat))
    a = O.bodies.append(sphere((0, 0, 0), R, material=m, fixed=True))
    b = O.bodies.append(sphere((2 * R - overlap, 0, 0), R, material=m, fixed=True))
    O.bodies[b].state.vel = vel2
    O.engines = engines(loop=loop)
    O.step()
    return a, b


for loop in ("fused", "standard"):
    # 1. Eq. (3): approaching, the spring and the dashpot; separating, the spring alone. Body 2 moves
    # along -x (approach, overlap rate v > 0) or +x; the force on it is repulsive along +x.
    en, v, overlap = 0.6, 0.02, 2e-6
    for sign, phase in ((-1, "approaching"), (1, "separating")):
        for damping in ("approach", "always"):
            a, b = pair(loop, overlap, (sign * v, 0, 0), tc=tc, en=en, et=0.9, frictionAngle=0.0, normalDamping=damping)
            p = O.interactions[a, b].phys
            rate = -sign * v  # d(overlap)/dt
            dash = p.cn * (max(rate, 0.0) if damping == "approach" else rate)
            expected = max(0.0, p.kn * overlap + dash)
            ck.close(O.forces.f(b)[0], expected, 1e-9, "%s: normal force %s, normalDamping=%s" % (loop, phase, damping),
                     "Richefeu2008 eq. (2)-(3)" if damping == "approach" else "Gladkyy2014 eq. (3) with Schwager2007")
    # The Ip2's stiffness and damping for (tc, en) with the approach-only dashpot: omega = pi/tc is the
    # damped frequency, x = beta/omega from en by the approach-only restitution (closed form above).
    a, b = pair(loop, overlap, (0, 0, 0), tc=tc, en=en, et=0.9, frictionAngle=0.0, normalDamping="approach")
    p = O.interactions[a, b].phys
    m_red, omega, x = mass / 2, math.pi / tc, damping_ratio(en, approach_only=True)
    ck.close(p.kn, m_red * omega ** 2 * (1 + x * x), 1e-9, "%s: kn from tc, en (approach)" % loop, "k = m (omega^2 + beta^2)")
    ck.close(p.cn, 2 * m_red * omega * x, 1e-9, "%s: cn from tc, en (approach)" % loop, "c = 2 m beta, x from en = exp(-x atan(1/x))")
    ck.true(p.approachDamping and not p.viscousFriction, "%s: the phys flags follow the material" % loop)

    # 2. Eq. (12): viscous-regularised Coulomb friction. Body 2 slides along +y at speed v over body 1
    # (overlap fixed, no normal motion): the tangential force on body 2 is -min(cs v, mu fn) along y,
    # in the viscous regime (small v) and at the Coulomb cap (large v), and has no memory: it stays so
    # over many steps, where a tangential spring would grow.
    kn, cs, mu = 200.0, 0.05, 0.4
    fn = kn * overlap
    for v_t, regime in ((0.2 * mu * fn / cs, "viscous"), (5 * mu * fn / cs, "Coulomb")):
        a, b = pair(loop, overlap, (0, v_t, 0), kn=kn, cn=0.0, ks=1e3, cs=cs, frictionAngle=math.atan(mu), friction="viscous")
        for step in range(40):
            if step:
                O.step()
            # The force of a step follows from the positions before it (body 2 has moved by v_t dt since).
            pos = O.bodies[b].state.pos - O.dt * O.bodies[b].state.vel
            n = pos / pos.norm()
            f = O.forces.f(b)
            f_n = f.dot(n)
            f_t = f - f_n * n
            p = O.interactions[a, b].phys  # kn, cs of the pair: the two materials' in series
            # The sliding speed is v_t n_x (the normal turns by v_t t / 2R).
            expected = min(p.cs * v_t * abs(n[0]), p.tangensOfFrictionAngle * f_n)
            ck.close(f_n, p.kn * (2 * R - pos.norm()), 1e-9, "%s: %s friction, step %d: normal force" % (loop, regime, step), "Richefeu2008 eq. (2)")
            ck.close(f_t.norm(), expected, 1e-9, "%s: %s friction, step %d: tangential force" % (loop, regime, step), "Richefeu2008 eq. (12)")
            ck.true(f_t[1] < 0, "%s: %s friction, step %d: the tangential force opposes the sliding" % (loop, regime, step))
        # At the contact point, midway through the overlap: arm -(d/2) n from body 2's centre.
        ck.close(O.forces.t(b)[2], -0.5 * pos.norm() * (n[0] * f[1] - n[1] * f[0]), 1e-9, "%s: %s friction torque on body 2" % (loop, regime),
                 "the tangential force at the contact point")
    # The spring law at the same speed grows with the sliding distance (ks v dt per step), where the
    # viscous law stays at cs v.
    v_t = 0.2 * mu * fn / cs
    a, b = pair(loop, overlap, (0, v_t, 0), kn=kn, cn=0.0, ks=1e3, cs=cs, frictionAngle=math.atan(mu), friction="spring")
    for _ in range(39):
        O.step()
    p = O.interactions[a, b].phys
    ck.true(abs(O.forces.f(b)[1]) > 1.1 * p.cs * v_t,
            "%s: the spring law's force (%.3g N) exceeds the viscous one (%.3g N) after 40 steps" % (loop, abs(O.forces.f(b)[1]), p.cs * v_t))

# 3. A free head-on collision with the approach-only dashpot returns en (1 %, the integration error
# at dt = tc/200 as in test_restitution): the closed form of the restitution is that of eq. (3).
for en in (0.4, 0.6, 0.9):
    O.reset()
    O.dt = tc / 200
    m = O.materials.append(PendularMat(tc=tc, en=en, et=0.9, density=rho, frictionAngle=0.0, normalDamping="approach"))
    touched, measured = head_on(m, R)
    ck.true(touched, "en=%g: the spheres collided" % en)
    ck.close(measured, en, 0.01, "restitution with normalDamping='approach', en=%g" % en, "en = exp(-x atan(1/x)) of Richefeu2008 eq. (3)")
    print("approach-only dashpot: en = %.2f, measured %.5f" % (en, measured))
ck.finish()
