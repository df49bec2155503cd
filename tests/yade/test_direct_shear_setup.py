# The direct shear cell of yade_capillary.directshear (Richefeu2008 section 3.2.1) as the paper prescribes it,
# in its CI size: the number fractions of the three sizes, a settled sample without bonds, the liquid of the
# water content shared over bonds (w = m_w / m_s), consolidation without friction to phi = 0.6 (within the
# overshoot of one check interval, or as far as the cohesive sample goes in consolidate_s) and friction mu = 0.4
# after it on every contact, the lid's weight as the normal stress (its contact stress at rest within 10 %),
# the upper part moving at the speed of
# the inertial number, the liquid conserved to 1e-12 through the shear, and no NaN.
import math

from yade import O

from yade_capillary import bonds, directshear as ds
from testing import Checker

ck = Checker("test_direct_shear_setup")
cfg = dict(ds.CONFIGS["ci"], D=0.016, n=884, shear=2e-4, records=20, settle_s=0.25)  # a smaller cell: the machinery only
ds.CONFIGS["test"] = cfg
info = ds.build("test")
d = [2 * O.bodies[i].shape.radius for i in info["spheres"]]
for size, frac in zip(cfg["diameters"], cfg["fractions"]):
    ck.close(sum(1 for x in d if abs(x - size) < 1e-12) / len(d), frac, 2e-3, "number fraction of %g mm" % (size * 1e3), "Richefeu2008 section 3.2.1")
ds.settle(info)
ck.true(int(bonds.engine().nShared) == 0 and O.engines[2].lawDispatcher.functors[0].nBridges == 0, "settled without bonds")
w = 0.01
ds.wet(info, w)
law = O.engines[2].lawDispatcher.functors[0]
solid = sum(O.bodies[i].state.mass for i in info["spheres"])
ck.close(law.liquidTotals()["total"], w * solid / 1000.0, 1e-12, "the liquid of w = 1 %", "w = m_w / m_s (Richefeu2008 section 3.1.2)")
ck.true(bonds.coordination() > 2, "bonds on the close pairs (z = %.2f)" % bonds.coordination())
phi0 = ds.consolidate(info, 300.0)
ck.true(0.58 < phi0 < cfg["phi"] + 0.005, "consolidated without friction to phi = %.4f (0.6)" % phi0)
ck.close(info["sigma_rest_Pa"], 300.0, 0.1, "the lid's contact stress at rest", "its weight over the area")
mu = [I.phys.tangensOfFrictionAngle for I in O.interactions if I.isReal]
ck.true(len(mu) > 0 and all(abs(m - cfg["mu"]) < 1e-12 for m in mu), "friction mu = 0.4 on every contact after consolidation")
total0 = law.liquidTotals()["total"]
rows = ds.shear(info, "/tmp/test_direct_shear_setup")
ck.close(info["v"], cfg["inertial"] * 10 * math.sqrt(300.0 / cfg["rho"]), 1e-12, "shear speed of the inertial number", "I = (v / 10 d) d sqrt(rho / sigma)")
ck.close(rows[-1]["displacement_m"], cfg["shear"], 0.005, "the upper part moved by the shear distance (within one step, 0.2 %)", "v t")
ck.close(law.liquidTotals()["total"], total0, 1e-12, "liquid conserved through the shear", "the liquid after the sharing")
ck.true(all(math.isfinite(r["tau_Pa"]) for r in rows), "finite shear stress")
ck.finish()
