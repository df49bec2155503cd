# Viscous pull-off (Elskamp & Kruggel-Emden 2018, section 3.1, Fig. 5b; Pitois et al. 2001 experiments):
# two spheres r = 4 mm, V = 5e-10 m^3, theta = 10 deg, sigma = 21 mN/m, eta = 0.1 Pa s, one fixed and
# the other pulled from contact at 0.1, 1 and 10 mm/s; Rabinovich's capillary force, Pitois' normal
# viscous force (eq. 26), Willett's rupture distance with Pitois' dynamic extension (eq. 33).
# Run:  build/yade-capillary -j1 -n -x scripts/viscous_pull_off.py [outdir]   (default results/viscous_pull_off)
# Writes forces.csv (speed_m_s, gap_m, F_cap_N, F_visc_N, F_tot_N, ... per step) and
# fig5b_viscous_pull_off.png; prints the summary (rupture distances, F_visc/F_cap, linearity in v).
import math
import os
import sys

from yade_capillary import cases, plots, twosphere

outdir = sys.argv[1] if len(sys.argv) > 1 else os.path.join("results", "viscous_pull_off")
os.makedirs(outdir, exist_ok=True)
case = cases.ELSKAMP2018_FIG5B
r_eff = twosphere.effective_radius(case)
print("Viscous pull-off (Elskamp 2018 Fig. 5b): r = %g mm, V = %g m^3, eta = %g Pa s, speeds %s mm/s -> %s" % (
    case.R1_m * 1e3, case.volume_m3, case.eta_Pa_s, ", ".join("%g" % (v * 1e3) for v in case.speeds_m_s), outdir))
runs = twosphere.viscous_pull_offs(case, model="rabinovich", rupture="willett+pitois", viscous="pitois")
twosphere.write_viscous_forces(runs, os.path.join(outdir, "forces.csv"), r_eff)
plots.viscous_pull_off(runs, r_eff, case.gamma_N_m, os.path.join(outdir, "fig5b_viscous_pull_off.png"),
                       "Elskamp 2018 Fig. 5b: r1 = r2 = %g mm, V = %g m^3, theta = %g deg,\nsigma = %g mN/m, eta = %g Pa s; "
                       "rabinovich + Pitois eq. (26), rupture willett + eq. (33)" % (
                           case.R1_m * 1e3, case.volume_m3, math.degrees(case.theta_rad), case.gamma_N_m * 1e3, case.eta_Pa_s))
print(twosphere.format_viscous_summary(twosphere.viscous_summary(case, runs, viscous="pitois")))
print("wrote %s/{forces.csv, fig5b_viscous_pull_off.png}" % outdir)
sys.exit(0)
