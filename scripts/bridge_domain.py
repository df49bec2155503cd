#!/usr/bin/env python3
# Where the pendular bridge exists: the largest volume V* = V/R_small^3 for which the exact Young-Laplace solver
# follows the bridge from contact to its rupture, for contact angles 0..70 deg on either solid, size ratios
# R_small/R_large = 1, 1/2, 1/4 and a wall, both orders of the solids, and why it stops there. Plain python3:
#   PYTHONPATH=build/python /usr/bin/python3 scripts/bridge_domain.py [outdir] [--quick]
# (--quick: angles 0 and 70 deg only). Writes cases.csv, swap.csv, summary.csv, bridge_domain.png (default
# results/bridge_domain) and the tracked per-case table data/bridge_domain/limits.csv (not with --quick).
# See studies/bridgedomain.py.
import os
import sys
import time

from studies import bridgedomain as bd

args = [a for a in sys.argv[1:] if not a.startswith("--")]
quick = "--quick" in sys.argv
outdir = args[0] if args else os.path.join("results", "bridge_domain")
datadir = os.path.join(outdir, "data") if quick else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "bridge_domain")
angles = (0, 70) if quick else bd.ANGLES_DEG


def log(r):
    print("  %-4s theta %2d/%2d small first %d: V* limit %-9.5g %-22s steepest on %-12s (pi/2 - max|phi| = %.1e) %5.2f s" % (
        r["geometry"], r["theta_small_deg"], r["theta_large_deg"], r["small_is_solid1"], r["vstar_limit"], r["cause"],
        r.get("vertical_on", "-"), r.get("vertical_margin_rad", float("nan")), r["seconds"]), flush=True)


t0 = time.perf_counter()
rows, summary = bd.run(outdir, datadir, angles=angles, log=log)
print("\nPer geometry (V* = V/R_small^3; scan %g..%g, bisection to %g in ln V*; the limit of a case: the smaller of both orders):"
      % (bd.SCAN[0], bd.VSTAR_CAP, bd.REL_RESOLUTION))
for s in summary:
    print("  %-4s V* limit %.4g (theta %d/%d) .. %.4g (theta %d/%d), median %.4g" % (
        s["geometry"], s["vstar_limit_min"], s["min_at_theta_small_deg"], s["min_at_theta_large_deg"], s["vstar_limit_max"],
        s["max_at_theta_small_deg"], s["max_at_theta_large_deg"], s["vstar_limit_median"]))
    print("       causes: %s; where no bridge at contact: nearest to vertical %s, vertical at the limit %d, largest volume"
          " before vertical %d (extrapolated pi - theta - beta <= %.3g rad)" % (
              s["causes"], s["margin_on_where_no_bridge_at_contact"], s["vertical_at_limit"], s["fold_before_vertical"],
              s["vertical_margin_extrapolated_max_rad"]))
    print("       holes %d; swap: |ln| limit diff <= %s, rupture-gap rel diff <= %s; meniscus clearance >= %.2g R_small" % (
        s["holes"], s["swap_ln_limit_diff_max"], s["swap_gap_rel_diff_max"], s["clearance_min"]))
print("\n%d cases in %.0f s; wrote %s/{cases.csv, swap.csv, summary.csv, bridge_domain.png}, %s/limits.csv" % (
    len(rows), time.perf_counter() - t0, outdir, os.path.normpath(datadir)))
