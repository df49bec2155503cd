# Sphere-wall pull-off (Elskamp & Kruggel-Emden 2018, Fig. 5a), every model against the exact solver.
# Run:  build/yade-capillary -j1 -n -x scripts/sphere_wall.py [outdir]     (default results/sphere_wall)
# Writes forces.csv (case,model,gap_m,force_N,...), summary.csv and fig5a_sphere_wall.png; prints
# per configuration and model F(0), the rupture gap and the RMS relative deviation from the exact curve.
import math
import os
import sys

from yade_capillary import cases, kernels, plots, twosphere

outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join("results", "sphere_wall")
table = cases.ELSKAMP2018_FIG5A
models = kernels.MODEL_NAMES  # linear_irreversible calibrates itself (from willett_full) per bridge
print("Sphere-wall pull-off: %d configurations x %d models and the exact Young-Laplace solver -> %s" % (len(table), len(models), outdir))
summary = twosphere.run_all(table, models, outdir)
curves = plots.read_forces(os.path.join(outdir, "forces.csv"))
titles = ["Elskamp 2018 Fig. 5a, %s\nr = %g um, V = %g m^3, theta = %g deg (sphere and wall), sigma = %g mN/m"
          % (c.code, c.R1_m * 1e6, c.volume_m3, math.degrees(c.theta_rad), c.gamma_N_m * 1e3) for c in table]
plots.force_panels(curves, [c.code for c in table], models + ["young_laplace"], os.path.join(outdir, "fig5a_sphere_wall.png"), titles)
print(twosphere.format_deviation_summary(summary))
for c in table:
    print("%s: Derjaguin sphere-plane force 4 pi r sigma cos(theta) = %.3f nN" % (c.code, twosphere.derjaguin_force(c) * 1e9))
print("wrote %s/{forces.csv, summary.csv, fig5a_sphere_wall.png}" % outdir)
sys.exit(0)
