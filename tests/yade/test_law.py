# In-YADE tests of Law2_ScGeom_PendularPhys_Bridge: forces equal the kernels at the same gaps,
# the bridge state machine (forms at contact only, breaks beyond sCrit, liquid totals balance),
# sphere-wall bridges, and O.save/O.load of a live bridge.
import math
import os
import tempfile

from yade import O
from yade.utils import facet, sphere, wall
from yade.wrapper import PendularMat

from yade_capillary import cases, kernels
from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_law")


def two_spheres(case, model, forceInContact=False, detection_factor=1.0, start_gap=0.0):
    O.reset()
    O.dt = 1e-6
    mat = O.materials.append(PendularMat(tc=2e-5, en=0.83, et=0.83, density=2500, frictionAngle=0.3, wet=True, Vb=case.volume_m3,
                                         gamma=case.gamma_N_m, theta=case.theta_rad, model=model, forceInContact=forceInContact))
    b1 = O.bodies.append(sphere((0, 0, 0), case.R1_m, material=mat, fixed=True))
    b2 = O.bodies.append(sphere((case.R1_m + case.R2_m + start_gap, 0, 0), case.R2_m, material=mat, fixed=True))
    O.engines = engines(detection_factor=detection_factor)
    return b1, b2


def place(case, b2, gap):
    O.bodies[b2].state.pos = (case.R1_m + case.R2_m + gap, 0, 0)
    O.step()
    return O.forces.f(0)[0]  # attraction pulls body 0 towards +x


# 1. Law2 forces equal the kernel values at the same gaps (the same kernel, through the YADE layer).
for code in ("W11", "W24", "W33", "R2"):
    c = cases.case(code)
    for model in kernels.MODEL_NAMES:
        for fic in (False, True):
            b1, b2 = two_spheres(c, model, forceInContact=fic)
            O.step()  # touching: the bridge forms
            info = kernels.bridge(model, c.R1_m, c.R2_m, c.volume_m3, c.gamma_N_m, c.theta_rad)
            I = O.interactions[b1, b2]
            ck.close(I.phys.sCrit, info["rupture"], 1e-14, "%s %s sCrit" % (code, model), "kernels.bridge")
            ck.close(O.forces.f(0)[0], info["force0"] if fic else 0.0, 1e-12, "%s %s force in contact (forceInContact=%s)" % (code, model, fic),
                     "F(0) from kernels.bridge, or 0 (Gladkyy eq. 4)", atol=1e-12 * info["force0"])
            for frac in (0.01, 0.3, 0.7, 0.99):
                gap = frac * info["rupture"]
                F = place(c, b2, gap)
                gap_geom = -O.interactions[b1, b2].geom.penetrationDepth
                expected = kernels.force(model, gap_geom, c.R1_m, c.R2_m, c.volume_m3, c.gamma_N_m, c.theta_rad)
                ck.close(F, expected, 1e-12, "%s %s F at a=%.2f a_crit" % (code, model, frac), "kernels.force")
                ck.close(O.interactions[b1, b2].phys.Fcap, expected, 1e-12, "%s %s phys.Fcap" % (code, model), "kernels.force")
                ck.close(O.forces.f(1)[0], -expected, 1e-12, "%s %s reaction on body 2" % (code, model), "Newton's third law")

# 2. State machine: no bridge (and no real interaction) before the first contact; bridge at contact; broken beyond sCrit.
c = cases.case("W11")
info = kernels.bridge("willett_full", c.R1_m, c.R2_m, c.volume_m3, c.gamma_N_m, c.theta_rad)
b1, b2 = two_spheres(c, "willett_full", detection_factor=1.2, start_gap=0.5 * info["rupture"])
O.step()
ck.true(not (O.interactions.has(b1, b2) and O.interactions[b1, b2].isReal),
        "no bridge before the first contact: the law resets the pre-contact interaction (detection factor 1.2)")
ck.close(O.forces.f(0)[0], 0.0, 0, "no capillary force before contact", "bridges form at contact (Gladkyy 2014, sec. 2)")
ck.true(capillaryLaw.nBridges == 0, "nBridges = 0 before contact")
place(c, b2, -1e-9)
ck.true(O.interactions[b1, b2].phys.active, "bridge formed at contact")
ck.true(capillaryLaw.nBridges == 1, "nBridges = 1 after contact")
ck.close(capillaryLaw.liquidVolume, c.volume_m3, 1e-15, "liquid in bridges", "Vb of the material")
ck.true(place(c, b2, info["rupture"] * (1 - 1e-9)) > 0, "bridge alive just below sCrit")
ck.close(place(c, b2, info["rupture"] * (1 + 1e-9)), 0.0, 0, "force beyond sCrit", "rupture distance (Gladkyy eq. 2)")
ck.true(not (O.interactions.has(b1, b2) and O.interactions[b1, b2].isReal and O.interactions[b1, b2].phys.active), "bridge removed at rupture")
ck.true(capillaryLaw.nBridges == 0, "nBridges back to 0")
ck.close(capillaryLaw.liquidVolume, 0.0, 0, "no liquid in bridges after rupture", "liquidFormed - liquidReleased", atol=1e-30)
ck.close(capillaryLaw.liquidReleased, capillaryLaw.liquidFormed, 1e-15, "liquid released = liquid formed", "liquid balance")
place(c, b2, 0.5 * info["rupture"])
ck.close(O.forces.f(0)[0], 0.0, 0, "no bridge again without a new contact", "bridge hysteresis (Gladkyy 2014, sec. 2)")

# 3. Sphere-wall bridge: effective radius 2R (Derjaguin sphere-plane limit, capillary-models.md).
R, V, g, t = 1e-3, 1e-11, 0.05, math.radians(20)
for model in kernels.MODEL_NAMES:
    O.reset()
    O.dt = 1e-6
    mat = O.materials.append(PendularMat(tc=2e-5, en=0.8, et=0.8, density=2500, wet=True, Vb=V, gamma=g, theta=t, model=model, forceInContact=True))
    w = O.bodies.append(wall((0, 0, 0), axis=0, material=mat))
    s = O.bodies.append(sphere((R, 0, 0), R, material=mat, fixed=True))
    O.engines = engines()
    O.step()
    info = kernels.bridge(model, R, float("inf"), V, g, t)
    ck.close(O.interactions[w, s].phys.R, 2 * R, 1e-14, "%s wall effective radius" % model, "harmonic mean with R2 -> inf")
    if model == "willett_reduced":
        ck.close(O.forces.f(s)[0], -4 * math.pi * R * g * math.cos(t), 1e-12, "wall F(0)", "4 pi R gamma cos(theta)")
    for frac in (0.2, 0.8):
        O.bodies[s].state.pos = (R + frac * info["rupture"], 0, 0)
        O.step()
        gap = -O.interactions[w, s].geom.penetrationDepth
        ck.close(-O.forces.f(s)[0], kernels.force(model, gap, R, float("inf"), V, g, t), 1e-12, "%s sphere-wall force" % model,
                 "kernels.force with R2 = inf")

# A facet is a wall for the bridge as well (Ig2_Facet_Sphere_ScGeom).
O.reset()
O.dt = 1e-6
mat = O.materials.append(PendularMat(tc=2e-5, en=0.8, et=0.8, density=2500, wet=True, Vb=V, gamma=g, theta=t, model="willett_full", forceInContact=True))
f = O.bodies.append(facet([(0, -5 * R, -5 * R), (0, 5 * R, -5 * R), (0, 0, 5 * R)], material=mat))
s = O.bodies.append(sphere((R - 1e-9, 0, 0), R, material=mat, fixed=True))
O.engines = engines()
O.step()
O.bodies[s].state.pos = (R + 0.5 * kernels.bridge("willett_full", R, float("inf"), V, g, t)["rupture"], 0, 0)
O.step()
gap = -O.interactions[f, s].geom.penetrationDepth
ck.close(-O.forces.f(s)[0], kernels.force("willett_full", gap, R, float("inf"), V, g, t), 1e-12, "sphere-facet force", "kernels.force with R2 = inf")

# 4. A live bridge survives O.save / O.load (cached invariants are rebuilt by postLoad).
c = cases.case("W22")
b1, b2 = two_spheres(c, "willett_full")
O.step()
F_before = place(c, b2, 0.4 * O.interactions[b1, b2].phys.sCrit)
totals = (capillaryLaw.nBridges, capillaryLaw.liquidVolume, capillaryLaw.liquidFormed, capillaryLaw.liquidReleased)
path = os.path.join(tempfile.mkdtemp(), "bridge.yade.gz")
O.save(path)
O.load(path)
ck.true((capillaryLaw.nBridges, capillaryLaw.liquidVolume, capillaryLaw.liquidFormed, capillaryLaw.liquidReleased) == totals,
        "Law2 totals saved and restored by O.save/O.load")
O.step()
ck.true(O.interactions[b1, b2].phys.active, "bridge active after O.load")
ck.close(O.forces.f(0)[0], F_before, 1e-14, "force after O.load", "force before O.save")
place(c, b2, 1.01 * O.interactions[b1, b2].phys.sCrit)
ck.true(capillaryLaw.nBridges == 0 and capillaryLaw.liquidVolume == 0, "rupture after O.load: no bridge, no liquid in bridges")
ck.close(capillaryLaw.liquidReleased, capillaryLaw.liquidFormed, 1e-15, "liquid released = formed after O.load", "liquid balance")

# 5. Frictionless contacts between spheres exert a central force: no moment about either centre, in both
#    loops (the arms lie along the normal; computed, their cross products with the force gave round-off
#    moments that spun frictionless spheres). A facet keeps the moment of the force at the contact point
#    about its own position, (contactPoint - position) x force.
from yade_capillary import scene  # noqa: E402

for loop in ("standard", "fused"):
    O.reset()
    O.dt = 1e-6
    mat = O.materials.append(PendularMat(tc=2e-5, en=0.8, et=0.8, density=2500, frictionAngle=0, wet=True, Vb=V, gamma=g, theta=t, model="willett_full"))
    direction = (0.3713, -0.5521, 0.7466)
    norm = math.sqrt(sum(x * x for x in direction))
    b1 = O.bodies.append(sphere((0.1 * R, 0.2 * R, -0.3 * R), R, material=mat, fixed=True))
    b2 = O.bodies.append(sphere(tuple(p + (1.93 * R) * x / norm for p, x in zip((0.1 * R, 0.2 * R, -0.3 * R), direction)), 0.95 * R, material=mat,
                                fixed=True))
    f = O.bodies.append(facet([(3 * R, -5 * R, -5 * R), (3 * R, 5 * R, -5 * R), (3 * R, 0, 5 * R)], material=mat))
    s3 = O.bodies.append(sphere((3 * R + 0.999 * R, 1.7 * R, -0.9 * R), R, material=mat, fixed=True))
    O.engines = scene.engines(loop=scene.interaction_loop(loop))
    O.step()
    O.step()
    F = O.forces.f(b2)
    ck.true(F.norm() > 0 and O.forces.t(b1).norm() == 0 and O.forces.t(b2).norm() == 0,
            "%s loop: frictionless sphere-sphere contact, force %.3g N, moments on both spheres exactly 0 (central force)" % (loop, F.norm()))
    I = O.interactions[f, s3]
    arm = I.geom.contactPoint - O.bodies[f].state.pos
    expected = arm.cross(O.forces.f(f))
    ck.true(O.forces.f(f).norm() > 0 and O.forces.t(s3).norm() == 0, "%s loop: sphere on a facet, moment on the sphere exactly 0" % loop)
    ck.close((O.forces.t(f) - expected).norm(), 0.0, 0, "%s loop: moment on the facet" % loop, "(contactPoint - position) x force",
             atol=1e-12 * expected.norm())

ck.finish()
