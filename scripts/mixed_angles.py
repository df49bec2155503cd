#!/usr/bin/env python3
# Unequal contact angles: the mean of the cosines (Elskamp 2018 eq. 14, 15)
# against the cosine of the mean angle (the kernels before this comparison), both against the exact Young-Laplace
# solver, for Elskamp's glass-steel and POM-PVC pairs, sphere-wall and sphere-sphere. Plain python3:
#   PYTHONPATH=build/python /usr/bin/python3 scripts/mixed_angles.py [outdir]
# Writes summary.csv, curves.csv, comparison.csv, derjaguin.csv, mixed_angles.png
# (default results/mixed_angles). See studies/mixedangles.py.
import os
import sys

from studies import mixedangles

outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join("results", "mixed_angles")
summary, derj, text = mixedangles.run(outdir)
print("Errors relative to the exact solver (cos: mean of cosines, ang: cosine of the mean angle; rms over 0..0.95 of the exact")
print("rupture gap, att: only where the model's bridge exists; young_laplace_equal: the solver with the equal effective angle)\n")
print(text)
n_cases = len({(r["pair"], r["geometry"], r["vstar"]) for r in summary})
print("\nPer model over the %d cases: mean of cosines closer in |F(0)| / in RMS; median |F(0)| and RMS errors" % n_cases)
for model, t in mixedangles.tally(summary).items():
    print("  %-20s F0 %2d/%-2d rms %2d/%-2d | F0 cos %6.2f%% ang %6.2f%% | rms cos %6.2f%% ang %6.2f%%" % (
        model, t["F0_mean_cos_closer"], t["n"], t["rms_mean_cos_closer"], t["n"], 100 * t["median_F0_mean_cos"],
        100 * t["median_F0_mean_angle"], 100 * t["median_rms_mean_cos"], 100 * t["median_rms_mean_angle"]))
refused = sorted({(r["model"], r["form"]) for r in summary if r["status"] != "ok"})
print("refused (model, form): %s" % (", ".join("%s/%s" % mf for mf in refused) or "none"))
print("\nExact F(0) against Derjaguin pi R gamma (cos theta1 + cos theta2), sphere-plane (R = 2 R1):")
for r in derj:
    print("  %-11s %-11s V* = %-7g F0/F_D = %.4f   (limit error of the mean angle: %+.2f %%)" % (
        r["pair"], r["geometry"], r["vstar"], r["F0_over_derjaguin"], 100 * r["limit_rel_error_mean_angle"]))
for key, k in mixedangles.deficit_exponent(derj).items():
    print("  deficit 1 - F0/F_D ~ V*^%.3f at the smallest V* (%s, %s)" % (k, key[0], key[1]))
print("\nwrote %s/{summary.csv, curves.csv, comparison.csv, derjaguin.csv, mixed_angles.png}" % outdir)
