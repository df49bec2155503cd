# Two-sphere pull-off validation (Gladkyy & Schwarze 2014, section 3, Table 1), every model.
# Run:  build/yade-capillary -n -x scripts/two_sphere.py [outdir]     (default results/two_sphere)
# Writes forces.csv (case,model,gap_m,force_N,...), summary.csv and fig2_W11.png, fig3_R1.png,
# fig4_summary.png; prints the summary table.
import os
import sys

from yade_capillary import cases, kernels, plots, twosphere

outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join("results", "two_sphere")
table = cases.GLADKYY2014_TABLE1
print("Two-sphere pull-off: %d cases x %d models and the exact Young-Laplace solver -> %s" % (len(table), len(kernels.MODEL_NAMES), outdir))
summary = twosphere.run_all(table, kernels.MODEL_NAMES, outdir)
curves = plots.read_forces(os.path.join(outdir, "forces.csv"))
plots.force_curves(curves, "W11", kernels.MODEL_NAMES + ["young_laplace"], os.path.join(outdir, "fig2_W11.png"),
                   "W11: R = 2.381 mm, V = 13.6 nl (Gladkyy 2014 Fig. 2)")
plots.force_curves(curves, "R1", kernels.MODEL_NAMES + ["young_laplace"], os.path.join(outdir, "fig3_R1.png"),
                   "R1: R = 19/35 um, V = 2e8 nm^3 (Gladkyy 2014 Fig. 3)", scale=1e9, unit="nN", gap_scale=1e9, gap_unit="nm")
plots.summary_bars(summary, {c.code: twosphere.derjaguin_force(c) for c in table}, os.path.join(outdir, "fig4_summary.png"))
print(twosphere.format_summary(summary))
print("wrote %s/{forces.csv, summary.csv, fig2_W11.png, fig3_R1.png, fig4_summary.png}" % outdir)
sys.exit(0)
