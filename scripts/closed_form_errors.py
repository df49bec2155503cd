#!/usr/bin/env python3
# What the closed-form bridge models and rupture rules get wrong, inside and beyond their fitted range, against the
# exact Young-Laplace solver over the domain where the pendular bridge exists (V* = V/Rh^3 in 1e-5..0.5, contact angles
# 0..70 deg equal or unequal, R_small/R_large 1/4..1 and walls). Plain python3, one core:
#   PYTHONPATH=build/python /usr/bin/python3 scripts/closed_form_errors.py [outdir] [--quick]
# Writes points.csv, rupture.csv (every point; default results/closed_form_errors) and the tracked
# data/closed_form_errors/{summary.csv, check_points.csv, closed_form_errors.png} (with --quick, a small sample, into
# outdir/data). See studies/closedformerrors.py.
import argparse
import os
import time

from studies import closedformerrors as cfe

parser = argparse.ArgumentParser(description="Closed-form bridge models and rupture rules against the exact solver")
parser.add_argument("outdir", nargs="?", default=os.path.join("results", "closed_form_errors"), help="per-point CSV files")
parser.add_argument("--quick", action="store_true", help="the first %d bridges of the sample; summaries in outdir/data" % cfe.N_QUICK)
args = parser.parse_args()
here = os.path.dirname(os.path.abspath(__file__))
datadir = os.path.join(args.outdir, "data") if args.quick else os.path.join(here, "..", "data", "closed_form_errors")
n = cfe.N_QUICK if args.quick else cfe.N_BRIDGES

t0 = time.perf_counter()
summary, force_rows, rupture_rows = cfe.run(args.outdir, datadir, n=n)
seconds = time.perf_counter() - t0
print("%d bridges (seed %d), gaps %s of the exact rupture gap, rupture rule %s; |relative error| in %%, median / 95th "
      "percentile / worst:\n" % (n, cfe.SEED, ", ".join("%g" % f for f in cfe.FRACTIONS), cfe.RULE))
for metric, title in (("force", "force, every gap (0 beyond the model's rupture distance counted as -100 %)"),
                      ("force_attached", "force, only the gaps the model's bridge reaches"),
                      ("force_contact", "force at contact"), ("rupture", "rupture distance of each rule")):
    print(title)
    print(cfe.table(summary, metric))
    print()
for s in summary:
    if s["split"] in ("inside domain", "extrapolated") and s["metric"] == "force":
        print("  %-18s %-13s median %6.2f %%  95th %7.1f %%  worst %8.0f %%  signed median %+7.2f %%  (%d bridges)" % (
            s["model"], s["split"], 100 * s["median_abs_rel_error"], 100 * s["p95_abs_rel_error"], 100 * s["worst_abs_rel_error"],
            100 * s["signed_median_rel_error"], s["n_bridges"]))
early = sum(r["ruptured_early"] for r in force_rows)
absent = sum(1 for r in force_rows if r["model"] == cfe.MODELS[0] and r["F_exact_N"] <= 0)
print("\npoints where a model's bridge had already broken (rule %s): %d; points with F_exact <= 0 (no relative error): %d"
      % (cfe.RULE, early, absent))
print("%d bridges in %.0f s; wrote %s/{points.csv, rupture.csv}, %s/{summary.csv, check_points.csv, closed_form_errors.png}" % (
    n, seconds, args.outdir, os.path.normpath(datadir)))
