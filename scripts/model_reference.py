"""Writes the reference data of every capillary model: tests/data/models/<model>.csv.

Plain python3 (PYTHONPATH=build/python /usr/bin/python3 scripts/model_reference.py [outdir]). Each file
holds the force of the model at 7 gaps (0 to 0.99 of the rupture distance) on Gladkyy's Table 1
cases, a sphere-wall bridge and a bridge with unequal contact angles, as computed by the kernels
when the file was written: a regression record, read by one generic test
(tests/kernels/test_reference_data.cpp) that every model in the table must pass. That the values
are right is checked elsewhere: against the printed formulas (tests/kernels/test_models.cpp) and
the exact solver (tests/kernels/test_young_laplace.cpp). Rupture rule willett, linear_irreversible
calibrated from willett_full.
"""
import math
import os
import subprocess
import sys

from yade_capillary import cases, kernels

FRACTIONS = (0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99)
HEADER = "R1_m,R2_m,volume_m3,gamma_N_m,theta1_rad,theta2_rad,rupture_m,gap_m,force_N"


def bridges():
    """(R1, R2, volume, gamma, theta1, theta2) of the reference bridges [m, m, m^3, N/m, rad, rad]."""
    rows = [(c.R1_m, c.R2_m, c.volume_m3, c.gamma_N_m, c.theta_rad, c.theta_rad) for c in cases.GLADKYY2014_TABLE1]
    rows.append((1e-3, math.inf, 1e-11, 0.07, 0.3, 0.3))          # sphere-wall
    rows.append((2.381e-3, 1.588e-3, 24.7e-12, 20.6e-3, 0.2, 0.5))  # unequal contact angles
    return rows


def write(model, path, made_by):
    with open(path, "w") as f:
        f.write("# reference forces of model %s (rupture rule willett), written by the kernels\n" % model)
        f.write("# made by: %s\n" % made_by)
        f.write(HEADER + "\n")
        for R1, R2, V, g, t1, t2 in bridges():
            try:
                b = kernels.bridge(model, R1, R2, V, g, t1, t2)
            except ValueError:  # outside this model's domain (e.g. unequal angles for the exact table)
                continue
            for frac in FRACTIONS:
                a = frac * b["rupture"]
                F = kernels.force(model, a, R1, R2, V, g, t1, t2)
                f.write(",".join(repr(float(x)) for x in (R1, R2, V, g, t1, t2, b["rupture"], a, F)) + "\n")


def main(outdir):
    os.makedirs(outdir, exist_ok=True)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip() or "unknown"
    made_by = "PYTHONPATH=build/python /usr/bin/python3 scripts/model_reference.py %s (at commit %s)" % (outdir, commit)
    for model in kernels.MODEL_NAMES:
        write(model, os.path.join(outdir, model + ".csv"), made_by)
        print("wrote", os.path.join(outdir, model + ".csv"))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "tests/data/models")
