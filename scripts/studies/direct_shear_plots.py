"""Plots of a direct shear series written by scripts/direct_shear.py (Richefeu2008 Fig. 5 and 6):
  python3 scripts/studies/direct_shear_plots.py OUTDIR [--sigma 300]
writes OUTDIR/shear_curves.png (shear stress against displacement over the mean diameter, each water content at
one normal stress), OUTDIR/cohesion.png (the yield loci of each water content, and c against w with its standard
error, each water content fitted alone and all with one friction angle) and OUTDIR/stress_drops.csv (per test, the falls of the shear stress between two records by more than DROP of
its residual mean, within the residual window: the instabilities of Richefeu2008 Fig. 5). Reads OUTDIR/runs.csv,
OUTDIR/mohr_coulomb.csv and OUTDIR/w<w>_sigma<sigma>/shear.csv."""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MEAN_DIAMETER = 1.65e-3  # 50/30/20 % by number of 2, 1.5 and 1 mm (yade_capillary.directshear.PAPER)
RESIDUAL_FROM = 2e-3  # m, yade_capillary.directshear.PAPER["residual_from"]
DROP = 0.05


def _rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main(argv):
    outdir = argv[0]
    sigma = float(argv[argv.index("--sigma") + 1]) if "--sigma" in argv else 300.0
    runs = _rows(os.path.join(outdir, "runs.csv"))
    ws = sorted({float(r["w"]) for r in runs})

    fig, ax = plt.subplots(figsize=(6, 4))
    for w in ws:
        path = os.path.join(outdir, "w%g_sigma%g" % (w, sigma), "shear.csv")
        if not os.path.exists(path):
            continue
        rows = _rows(path)
        ax.plot([float(r["displacement_m"]) / MEAN_DIAMETER for r in rows], [float(r["tau_Pa"]) for r in rows], label="w = %g %%" % (100 * w))
    ax.set_xlabel("displacement / mean diameter [-]")
    ax.set_ylabel("shear stress tau [Pa]")
    ax.set_title("Direct shear at %g Pa on the lid" % sigma)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "shear_curves.png"), dpi=120)

    with open(os.path.join(outdir, "stress_drops.csv"), "w", newline="") as f:
        out = csv.writer(f)
        out.writerow(["w", "sigma_Pa", "drops", "records"])
        for r in runs:
            rows = _rows(os.path.join(outdir, "w%g_sigma%g" % (float(r["w"]), float(r["sigma_Pa"])), "shear.csv"))
            taus = [float(x["tau_Pa"]) for x in rows if float(x["displacement_m"]) >= RESIDUAL_FROM]
            falls = sum(1 for a, b in zip(taus, taus[1:]) if a - b > DROP * float(r["tau_residual_Pa"]))
            out.writerow([r["w"], r["sigma_Pa"], falls, len(taus)])

    fits = _rows(os.path.join(outdir, "mohr_coulomb.csv"))
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for w in ws:
        mine = [r for r in runs if float(r["w"]) == w]
        line = left.errorbar([float(r["sigma_plane_Pa"]) for r in mine], [float(r["tau_residual_Pa"]) for r in mine],
                             yerr=[float(r["tau_se_Pa"]) for r in mine], fmt="o", label="w = %g %%" % (100 * w))
        fit = [f for f in fits if float(f["w"]) == w]
        if fit:
            c, phi = float(fit[0]["c_Pa"]), float(fit[0]["phi_deg"])
            xs = [0.0, max(float(r["sigma_plane_Pa"]) for r in mine)]
            left.plot(xs, [c + x * math.tan(math.radians(phi)) for x in xs], color=line[0].get_color())
    left.set_xlabel("normal stress on the shear plane sigma = N/S + rho g h [Pa]")
    left.set_ylabel("residual shear stress [Pa]")
    left.legend()
    right.errorbar([100 * float(f["w"]) for f in fits], [float(f["c_Pa"]) for f in fits], yerr=[float(f["c_se_Pa"]) for f in fits], fmt="o-",
                   label="this cell, each w alone")
    right.errorbar([100 * float(f["w"]) for f in fits], [float(f["c_one_phi_Pa"]) for f in fits], yerr=[float(f["c_one_phi_se_Pa"]) for f in fits],
                   fmt="s--", label="this cell, one phi for all w (%.1f deg)" % float(fits[0]["one_phi_deg"]))
    right.axhline(120, ls="--", color="grey", label="Richefeu2008 simulations, c_m")
    right.set_xscale("symlog", linthresh=0.05)
    right.set_xlim(left=0)
    right.set_xlabel("water content w [%]")
    right.set_ylabel("Coulomb cohesion c [Pa]")
    right.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "cohesion.png"), dpi=120)


if __name__ == "__main__":
    main(sys.argv[1:])
