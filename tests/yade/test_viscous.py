# In-YADE tests of the viscous bridge forces and the dynamic rupture distance (Elskamp 2018
# section 2.2.3-2.2.4): the Law2 gives the kernels' forces and moments for sphere-sphere and
# sphere-wall bridges in both loops, a pull-off at constant speed gives F_cap + c_n v, the bridge
# breaks at S_rup (1 + sqrt(v eta / gamma)) (eq. 33), eta = 0 evaluates nothing, the critical time
# step accounts for the viscous dashpots, a free pair loses kinetic energy, and bad input is refused.
import math

from yade import O
from yade.utils import facet, sphere, wall
from yade.wrapper import PendularMat

from yade_capillary import kernels
from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_viscous")
# Pitois' experiment as simulated by Elskamp 2018 section 3.1 (Fig. 5b): r = 4 mm, V = 5e-10 m^3,
# theta = 10 deg, sigma = 21 mN/m, eta = 0.1 Pa s; unequal radii for the sphere-sphere checks.
V, GAMMA, THETA, ETA = 5e-10, 0.021, math.radians(10), 0.1


def material(eta=ETA, rupture="willett", model="rabinovich", viscous="pitois", friction=0.0):
    return PendularMat(tc=1e-4, en=0.8, et=0.8, density=2500, frictionAngle=friction, wet=True, Vb=V, gamma=GAMMA, theta=THETA,
                       model=model, rupture=rupture, eta=eta, viscousNormal=viscous)


def pair(R1, R2, mat, loop="fused", wall_x=None):
    """Two fixed (kinematic) bodies touching: sphere 0 at the origin and sphere 1 along +x, or a
    wall at x = 0 (body 0) and a sphere (body 1). One step forms the bridge."""
    O.reset()
    O.dt = 1e-7
    m = O.materials.append(mat)
    if wall_x is None:
        O.bodies.append(sphere((0, 0, 0), R1, material=m, fixed=True))
        O.bodies.append(sphere((R1 + R2, 0, 0), R2, material=m, fixed=True))
    else:
        O.bodies.append(wall(0, axis=0, material=m))
        O.bodies.append(sphere((R1, 0, 0), R1, material=m, fixed=True))
    O.engines = engines(loop=loop)
    O.step()


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def cross(a, b):
    return [a[(k + 1) % 3] * b[(k + 2) % 3] - a[(k + 2) % 3] * b[(k + 1) % 3] for k in range(3)]


def on_sphere_at_wall(S, R, vrel, ws):
    """Kernels' force on a sphere R at gap S from a wall along -x (n from the sphere to the wall),
    relative velocity vrel of the sphere against the wall at the contact point, spin ws: (force,
    kernels' tangential dict, force scale)."""
    nn, inf = [-1.0, 0.0, 0.0], float("inf")
    vn = sum(a * b for a, b in zip(vrel, nn))
    fcap = kernels.force("rabinovich", S, R, inf, V, GAMMA, THETA)
    fn = kernels.viscous_normal_force("pitois", S, vn, R, inf, ETA, V)
    t = kernels.viscous_tangential(S, nn, vrel, R, inf, ETA, ws, (0, 0, 0))
    return [(fcap + fn) * nn[k] + t["force"][k] for k in range(3)], t, abs(fcap) + abs(fn)


def close_vec(actual, expected, scale, what, source, rtol=1e-9):
    for k in range(3):
        ck.close(actual[k], expected[k], 0, "%s[%d]" % (what, k), source, atol=rtol * scale)


# 1. Sphere-sphere: forces and moments equal the kernels at a general state (normal and tangential
#    relative velocity, both spheres spinning), separated and in contact, in both loops.
R1, R2 = 4e-3, 3e-3
n = [c / math.sqrt(1.13) for c in (1, 0.3, -0.2)]  # from sphere 0 to sphere 1
v1, v2 = (0.002, -0.001, 0.0005), (-0.001, 0.003, 0.001)
w1, w2 = (1.0, -2.0, 0.5), (-0.5, 0.7, 3.0)
for loop in ("fused", "standard"):
    for S in (2e-5, 1e-4, 4e-4):
        pair(R1, R2, material(), loop)
        O.bodies[1].state.pos = [(R1 + R2 + S) * c for c in n]
        for b, v, w in ((0, v1, w1), (1, v2, w2)):
            O.bodies[b].state.vel, O.bodies[b].state.angVel = v, w
        O.step()
        vrel = sub(v1, v2)
        vn = sum(a * b for a, b in zip(vrel, n))
        fcap = kernels.force("rabinovich", S, R1, R2, V, GAMMA, THETA)
        fn = kernels.viscous_normal_force("pitois", S, vn, R1, R2, ETA, V)
        t = kernels.viscous_tangential(S, n, vrel, R1, R2, ETA, w1, w2)
        expect = [(fcap + fn) * n[k] + t["force"][k] for k in range(3)]  # on sphere 0 (kernel particle 1)
        scale = abs(fcap) + abs(fn)
        what = "%s S=%g" % (loop, S)
        close_vec(O.forces.f(0), expect, scale, what + " force on sphere 0", "F_cap n + eq. (26) + eq. (28)/(29) (kernels)")
        close_vec(O.forces.f(1), [-x for x in expect], scale, what + " force on sphere 1", "the opposite force")
        mscale = R1 * scale
        close_vec(O.forces.t(0), t["moment1"], mscale, what + " moment on sphere 0", "R1 n x F1 (Elskamp after eq. 6)")
        close_vec(O.forces.t(1), t["moment2"], mscale, what + " moment on sphere 1", "R2 n x F1")
        I = O.interactions[0, 1]
        ck.close(I.phys.Fvisc, fn, 1e-9, what + " phys.Fvisc", "eq. (26) (attraction > 0)")
        ck.true(I.phys.viscousNormal == "pitois" and I.phys.eta == ETA, what + " phys records the viscous law and eta")

    # In contact (overlap 1e-6 m): the bridge's viscous forces act at S_eff = S_min, besides the
    # contact's spring-dashpot (frictionless: no tangential spring).
    pair(R1, R2, material(), loop)
    O.bodies[1].state.pos = [(R1 + R2 - 1e-6) * c for c in n]
    for b, v, w in ((0, v1, w1), (1, v2, w2)):
        O.bodies[b].state.vel, O.bodies[b].state.angVel = v, w
    O.step()
    I = O.interactions[0, 1]
    vrel = sub(v1, v2)
    vn = sum(a * b for a, b in zip(vrel, n))
    ck.close(I.phys.Fvisc, kernels.viscous_normal_force("pitois", -1e-6, vn, R1, R2, ETA, V), 1e-9, loop + " in contact: Fvisc",
             "eq. (26) at S_eff = S_min = 0.001 r* (Elskamp after eq. 29)")
    t = kernels.viscous_tangential(-1e-6, n, vrel, R1, R2, ETA, w1, w2)
    close_vec([-x for x in I.phys.viscousShear], t["force"], abs(t["c_t"]) * 1e-2, loop + " in contact: viscous shear",
              "eq. (28) at S_min (kernels)")

# 2. Sphere-wall: the sphere's force and moment equal the kernels with R2 = inf (the wall's
#    velocity at the contact point is 0; its arm is 0).
for loop in ("fused", "standard"):
    R = 4e-3
    pair(R, None, material(), loop, wall_x=0)
    S = 1e-4
    vs, ws = (0.003, 0.002, -0.001), (0.5, 2.0, -1.0)
    O.bodies[1].state.pos = (R + S, 0, 0)
    O.bodies[1].state.vel, O.bodies[1].state.angVel = vs, ws
    O.step()
    expect, t, scale = on_sphere_at_wall(S, R, vs, ws)  # the wall is at rest
    close_vec(O.forces.f(1), expect, scale, loop + " wall: force on the sphere", "kernels with R2 = inf")
    close_vec(O.forces.t(1), t["moment1"], R * scale, loop + " wall: moment on the sphere", "R1 n x F1, kernels with R2 = inf")
    ck.true(O.interactions[0, 1].phys.swapped, loop + " wall: body 0 is the wall, so the phys is marked swapped")

# 2b. Sphere-facet, the facet moving and spinning (a wall's motion at the contact point drives the
#     bridge): the kernels with v_rel = v_sphere - (v_facet + omega_facet x (contact point - facet centre)).
for loop in ("fused", "standard"):
    R = 4e-3
    O.reset()
    O.dt = 1e-7
    m = O.materials.append(material())
    O.bodies.append(facet(((0, -0.02, -0.02), (0, 0.02, -0.02), (0, 0, 0.03)), material=m, fixed=True))
    O.bodies.append(sphere((R - 1e-7, 0, 0), R, material=m, fixed=True))  # overlapping: the bridge forms
    O.engines = engines(loop=loop)
    O.step()
    S = 1e-4
    vs, ws, vf, wf = (0.003, 0.002, -0.001), (0.5, 2.0, -1.0), (0.001, -0.002, 0.004), (3.0, 1.0, -2.0)
    O.bodies[1].state.pos = (R + S, 0, 0)
    O.bodies[1].state.vel, O.bodies[1].state.angVel = vs, ws
    O.bodies[0].state.vel, O.bodies[0].state.angVel = vf, wf
    O.step()
    I = O.interactions[0, 1]
    # YADE's contact point of the step, and the facet centre at the start of the step (NewtonIntegrator
    # moved it after the law).
    cp, fc = I.geom.contactPoint, O.bodies[0].state.pos
    arm = sub(cp, [fc[k] - vf[k] * O.dt for k in range(3)])
    vwall = [vf[k] + c for k, c in enumerate(cross(wf, arm))]
    expect, t, scale = on_sphere_at_wall(S, R, sub(vs, vwall), ws)
    close_vec(O.forces.f(1), expect, scale, loop + " moving facet: force on the sphere", "kernels, v_rel at the contact point")
    close_vec(O.forces.t(1), t["moment1"], R * scale, loop + " moving facet: moment on the sphere", "R1 n x F1")
    # The facet gets the moment of its viscous force at the contact point (the capillary and normal
    # viscous forces of a separated bridge give a body no moment, as without viscosity).
    close_vec(O.forces.t(0), cross(arm, [-x for x in t["force"]]), 0.05 * scale, loop + " moving facet: moment on the facet", "(contact point - centre) x its viscous force")

# 3. Pull-off at constant speed (Elskamp Fig. 5b setup): F = F_cap(S) + c_n(S) v at every step,
#    and the bridge breaks at the dynamic rupture distance (eq. 33), beyond which the force is 0.
R = 4e-3
static = kernels.rupture_distance("willett", R, R, V, THETA)
for speed in (1e-3, 1e-2):
    pair(R, R, material(rupture="willett+pitois"))
    dyn = kernels.dynamic_rupture_distance(static, speed, ETA, GAMMA)
    O.dt = dyn / speed / 400  # 400 steps to rupture
    O.bodies[1].state.vel = (speed, 0, 0)
    worst, last_gap, broke_at = 0.0, None, None
    for _ in range(460):
        gap = O.bodies[1].state.pos[0] - 2 * R
        O.step()
        F = O.forces.f(0)[0]
        expected = kernels.force("rabinovich", gap, R, R, V, GAMMA, THETA, range=dyn) + kernels.viscous_normal_force(
            "pitois", gap, -speed, R, R, ETA, V)
        if gap <= 0:  # at gap 0 the contact law acts (and F(0) only with forceInContact)
            continue
        if gap <= dyn:
            worst = max(worst, abs(F - expected) / abs(expected))
            last_gap = gap
        elif broke_at is None:
            broke_at = gap
            ck.true(F == 0, "v=%g: no force beyond S_rup,dyn" % speed)
    ck.true(worst <= 1e-10, "v=%g: pull-off force = F_cap + c_n v at every step before rupture, worst relative error %.2e <= 1e-10 "
            "(kernels: rabinovich, eq. 26)" % (speed, worst))
    step = speed * O.dt
    ck.true(broke_at is not None and last_gap <= dyn < broke_at and broke_at - last_gap <= step * 1.0001,
            "v=%g: rupture between the steps around S_rup,dyn = %.6g m (eq. 33; static %.6g m)" % (speed, dyn, static))
    ck.true(dyn > static * (1 + math.sqrt(speed * ETA / GAMMA)) * (1 - 1e-12) and last_gap > static,
            "v=%g: the bridge outlives its static rupture distance" % speed)

# 3a. The dynamic rule stretches a model's own range too: young_laplace_table breaks between the steps
#     around its exact rupture distance times 1 + sqrt(v eta / gamma) (eq. 33).
pair(R, R, material(rupture="willett+pitois", model="young_laplace_table"))
exact = kernels.bridge("young_laplace_table", R, R, V, GAMMA, THETA)["rupture"]
speed = 1e-2
dyn = kernels.dynamic_rupture_distance(exact, speed, ETA, GAMMA)
O.dt = dyn / speed / 400
O.bodies[1].state.vel = (speed, 0, 0)
last_gap, broke_at = None, None
for _ in range(460):
    gap = O.bodies[1].state.pos[0] - 2 * R
    O.step()
    if gap > 0 and O.forces.f(0)[0] != 0:
        last_gap = gap
    elif gap > 0 and broke_at is None:
        broke_at = gap
ck.true(last_gap is not None and broke_at is not None and last_gap <= dyn < broke_at and last_gap > exact,
        "young_laplace_table + pitois: breaks between %.6g and %.6g m, around the stretched exact rupture %.6g m (exact %.6g m)"
        % (last_gap or 0, broke_at or 0, dyn, exact))

# 3b. O.save/O.load of a live viscous bridge with the dynamic rule: the invariants are rebuilt, the
#     reloaded run gives the same forces as the uninterrupted one.
pair(R, R, material(rupture="willett+pitois"))
O.dt = 2e-4
O.bodies[1].state.vel, O.bodies[1].state.angVel = (0.01, 0.002, 0), (0, 0, 3.0)
O.run(100, True)
O.saveTmp("viscous")
O.run(20, True)
ref = (tuple(O.forces.f(0)), tuple(O.forces.t(0)), O.interactions[0, 1].phys.sRupture)
O.loadTmp("viscous")
O.run(20, True)
got = (tuple(O.forces.f(0)), tuple(O.forces.t(0)), O.interactions[0, 1].phys.sRupture)
ck.true(got == ref and ref[2] > static, "O.save/O.load mid-pull: identical force, moment and dynamic rupture distance (%s)" % (got,))

# 4. eta = 0: nothing viscous is evaluated; the forces are those of the capillary bridge alone.
pair(R1, R2, material(eta=0))
O.bodies[1].state.pos = [(R1 + R2 + 1e-4) * c for c in n]
O.bodies[0].state.vel, O.bodies[0].state.angVel = v1, w1
O.step()
I = O.interactions[0, 1]
fcap = kernels.force("rabinovich", 1e-4, R1, R2, V, GAMMA, THETA)
close_vec(O.forces.f(0), [fcap * c for c in n], fcap, "eta = 0: force on sphere 0", "F_cap n alone", rtol=1e-14)
ck.true(I.phys.Fvisc == 0 and tuple(I.phys.viscousShear) == (0, 0, 0) and tuple(O.forces.t(0)) == (0, 0, 0) and I.phys.viscousNormal == "",
        "eta = 0: no viscous force, no moment, no viscous law")

# 5. The critical time step accounts for the viscous dashpot at contact (a damper c alone limits
#    dt to 2 m/c): with a very viscous liquid it is smaller than without.
def critical(eta):
    O.reset()
    m = O.materials.append(material(eta=eta))
    O.bodies.append(sphere((0, 0, 0), 2e-3, material=m))
    O.bodies.append(sphere((5e-3, 0, 0), 2e-3, material=m))
    O.engines = engines()
    loop = [e for e in O.engines if e.label == "interactionLoop"][0]
    return loop.physDispatcher.functors[0].criticalDt(0, 1)


dry, viscid = critical(0), critical(1e3)
ck.true(viscid < 0.5 * dry, "criticalDt with eta = 1e3 Pa s (%.3g s) is below half of that without (%.3g s)" % (viscid, dry))

# 6. A free sphere sliding along a wall at a constant gap (its normal motion blocked, so that the
#    capillary force does no work), spinning up under the viscous moment: its kinetic energy never
#    increases (the viscous force and moment dissipate here; see the kernels' note on eq. 28).
O.reset()
O.dt = 1e-6
m = O.materials.append(material())
O.bodies.append(wall(0, axis=0, material=m))
O.bodies.append(sphere((R, 0, 0), R, material=m))
O.engines = engines()
O.step()
s1 = O.bodies[1].state
s1.pos, s1.vel, s1.blockedDOFs = (R + 1e-5, 0, 0), (0, 0.01, 0), "x"


def kinetic():
    return 0.5 * s1.mass * s1.vel.squaredNorm() + 0.5 * sum(s1.inertia[k] * s1.angVel[k] ** 2 for k in range(3))


e0, increases, prev = kinetic(), 0, kinetic()
for _ in range(300):
    O.step()
    e = kinetic()
    increases += e > prev * (1 + 1e-12)
    prev = e
ck.true(increases == 0 and prev < 0.999 * e0 and s1.angVel.norm() > 0,
        "sliding sphere: kinetic energy never increases (%d increases), %.4g -> %.4g J, spin %.3g rad/s" % (increases, e0, prev, s1.angVel.norm()))

# 7. Bad input, naming the parameter and its allowed range.
good = dict(tc=1e-4, en=0.8, et=0.8, wet=True, Vb=V, gamma=GAMMA, theta=THETA)
for kw, words in ((dict(eta=-1.0), ["eta", "allowed range"]), (dict(eta=float("nan")), ["eta"]), (dict(eta=1e12), ["eta", "1000000000]"]),
                  (dict(eta=0.1, viscousNormal="stokes"), ["viscousNormal", "pitois", "adams_perchard"]),
                  (dict(eta=0.1, viscousSmin=0.0), ["viscousSmin", "allowed range"]),
                  (dict(rupture="pitois"), ["rupture", "eta > 0"]), (dict(rupture="willett+pitois", eta=0.0), ["rupture", "eta > 0"]),
                  (dict(rupture="pitois+willett", eta=0.1), ["rupture", "+pitois", "lian"])):
    ck.raises(ValueError, lambda: PendularMat(**dict(good, **kw)), words, "PendularMat(%s)" % kw)
ck.true(PendularMat(**dict(good, eta=0.1, rupture="pitois")).rupture == "pitois", "rupture='pitois' with eta > 0 is accepted")


def mixed(ma, mb):
    O.reset()
    O.dt = 1e-7
    a, b = O.materials.append(ma), O.materials.append(mb)
    O.bodies.append(sphere((0, 0, 0), R, material=a, fixed=True))
    O.bodies.append(sphere((2 * R, 0, 0), R, material=b, fixed=True))
    O.engines = engines()
    O.step()


ck.raises(ValueError, lambda: mixed(material(viscous="pitois"), material(viscous="adams_perchard")), ["viscousNormal", "pitois", "adams_perchard"],
          "different normal viscous laws on the two materials")
ck.raises(ValueError, lambda: mixed(material(eta=0.1), material(eta=0.0)), ["eta", "0.1", "both"],
          "a viscous material against one left at eta = 0 (the mean would halve the viscosity)")
mixed(material(rupture="pitois"), material(rupture="willett+pitois"))
ck.true(O.interactions[0, 1].phys.rupture == "willett+pitois", "rupture 'pitois' and 'willett+pitois' are the same rule on two materials")
# A rejected assignment leaves the rule in use as it was: before the fix, the material kept the
# rejected lian+pitois internally while reading back willett.
m_bad = material(eta=0.0)
ck.raises(ValueError, lambda: setattr(m_bad, "rupture", "lian+pitois"), ["rupture", "eta > 0"], "lian+pitois on an inviscid material")
mixed(m_bad, material(eta=0.0))
I = O.interactions[0, 1]
ck.true(m_bad.rupture == "willett" and I.phys.rupture == "willett" and not I.phys.dynamicRupture,
        "after the rejected assignment the bridge uses willett (got %r, dynamic %s)" % (I.phys.rupture, I.phys.dynamicRupture))
mixed(material(eta=0.1), material(eta=0.3))
ck.close(O.interactions[0, 1].phys.eta, 0.2, 1e-15, "eta of two materials", "arithmetic mean, as Vb and gamma")
ck.finish()
