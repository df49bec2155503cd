"""Plot of a simple compression series written by scripts/compression.py (Richefeu2008 Fig. 10):
  python3 scripts/studies/compression_plots.py OUTDIR
writes OUTDIR/axial_stress.png, the axial stress against the shortening over the mean diameter for every test in
OUTDIR (each w<w>_<protocol>_dry<dry>/summary.json: water content, protocol, fraction of dry pairs, bond
coordination after wetting), whichever series wrote it."""
import csv
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

MEAN_DIAMETER = 1.05e-3  # 10/20/20/20/20/10 % by number of 0.8 to 1.3 mm (yade_capillary.compression.PAPER)


def main(argv):
    outdir = argv[0]
    runs = []
    for path in sorted(glob.glob(os.path.join(outdir, "w*_dry*", "summary.json"))):
        with open(path) as f:
            runs.append(json.load(f))
    fig, ax = plt.subplots(figsize=(6, 4))
    for r in runs:
        where = os.path.join(outdir, "w%g_%s_dry%g" % (float(r["w"]), r["protocol"], float(r["dry_fraction"])))
        with open(os.path.join(where, "compression.csv")) as f:
            rows = list(csv.DictReader(f))
        ax.plot([float(x["shortening_m"]) / MEAN_DIAMETER for x in rows], [float(x["axial_stress_Pa"]) for x in rows],
                label="w = %g %%, %s, dry %g (z = %.2f)" % (100 * float(r["w"]), r["protocol"], float(r["dry_fraction"]), float(r["bond_coordination_wet"])))
    ax.set_xlabel("shortening / mean diameter [-]")
    ax.set_ylabel("axial stress [Pa]")
    ax.set_title("Simple compression, plate at 1 mm/s")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(outdir, "axial_stress.png"), dpi=120)


if __name__ == "__main__":
    main(sys.argv[1:])
