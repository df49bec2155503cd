# The simple compression test of yade_capillary.compression (Richefeu2008 section 4.2) in its CI size: the number
# fractions of Table II, the sample sealed near the printed solid fraction, the liquid of the water content counted
# on the physical solid mass (the masses are scaled by mass_scale), a wet sample standing after the mould is
# removed (the paper: a settlement of about 0.1 mm), the plate's speed, a finite axial stress with a peak, and the
# liquid conserved to 1e-12 from the sharing to the end of the loading.
import math

from yade import O

from yade_capillary import bonds, compression as cp
from testing import Checker

ck = Checker("test_compression_setup")
cfg = cp.CONFIGS["ci"]
info = cp.build("ci")
d = [2 * O.bodies[i].shape.radius for i in info["spheres"]]
for size, frac in zip(cfg["diameters"], cfg["fractions"]):
    ck.close(sum(1 for x in d if abs(x - size) < 1e-12) / len(d), frac, 2e-3, "number fraction of %g mm" % (size * 1e3), "Richefeu2008 Table II")
cp.settle_and_seal(info)
# The height is the highest sphere's top: in a mould of 10 diameters and a sample of 7, the rough top and the walls
# leave phi some 0.06 below the paper's 0.62 for 25 diameters, and one sphere resting on the top layer lowers it by
# up to 0.03 more (0.31 mm above the next highest: 0.525 against 0.553); the loose fill starts at about 0.3.
ck.true(0.50 < info["phi_sealed"] < 0.66, "settled and sealed at phi = %.3f (the paper: 0.62)" % info["phi_sealed"])
w = 0.02
cp.wet(info, w)
law = O.engines[2].lawDispatcher.functors[0]
solid = sum(O.bodies[i].state.mass for i in info["spheres"]) / cfg["mass_scale"]
ck.close(law.liquidTotals()["total"], w * solid / 1000.0, 1e-12, "the liquid of w = 2 % of the physical solid mass",
         "w = m_w / m_s (Richefeu2008 section 3.1.2)")
total0 = law.liquidTotals()["total"]
ck.true(bonds.coordination() > 3, "bonds on the close pairs (z = %.2f)" % bonds.coordination())
settlement = cp.unmould(info)
ck.true(all(O.bodies[i] is None for i in info["mould"]), "the mould removed")
ck.true(-1e-6 < settlement < 0.5e-3, "the wet sample stands without its mould: settled by %.3f mm (Richefeu2008: about 0.1 mm)" % (1e3 * settlement))
# It keeps the mould's shape (Richefeu2008 section 4.2.1: it relaxes "with only a slight settlement"): 99 % of the
# spheres within a quarter of the smallest diameter outside the mould's wall. With the overlaps of the settling's
# mass_scale times heavier weights locked in, the sample burst outwards (0.6 mm here, 15 mm in the paper's sample).
reach = sorted(math.hypot(O.bodies[i].state.pos[0], O.bodies[i].state.pos[1]) + O.bodies[i].shape.radius for i in info["spheres"])
beyond = reach[int(0.99 * len(reach))] - cfg["D"] / 2
ck.true(beyond < min(cfg["diameters"]) / 4, "the sample keeps the mould's shape: 99 %% of the spheres within %.3f mm of its wall (< %.2f mm)"
        % (1e3 * beyond, 1e3 * min(cfg["diameters"]) / 4))
rows = cp.compress(info, "/tmp/test_compression_setup")
ck.close(rows[-1]["shortening_m"], cfg["shortening"], 0.03, "the plate moved by the shortening", "speed x time")
ck.true(all(math.isfinite(r["axial_stress_Pa"]) for r in rows), "finite axial stress")
peak = max(r["axial_stress_Pa"] for r in rows)
ck.true(peak > 0, "the plate meets the sample (peak %.1f Pa)" % peak)
ck.close(law.liquidTotals()["total"], total0, 1e-12, "liquid conserved through unmoulding and compression", "the liquid after the sharing")
ck.finish()
