# The cohesion of wet shear-cell runs against the dry run of the same cell (studies/cell_fits.py, excess_shear):
# at each height of the wet band, tau_wet - tau_dry at the same pressure, and the intercept of the wet
# points with Gladkyy's slope mu = 0.13. Plain python3, from the runs' profiles.csv:
#   PYTHONPATH=build/python /usr/bin/python3 scripts/shear_cell_excess.py DRY WET_DIR [WET_DIR ...]
# DRY: the dry run's directory (its profiles.csv), or a directory with only fits.json: then the dry band is
# its fitted line over the fitted pressures. Prints a table per wet run and writes WET_DIR/excess_shear.csv.
import json
import os
import sys

import numpy as np

from studies import cell_fits

if len(sys.argv) < 3:
    raise SystemExit("usage: shear_cell_excess.py DRY WET_DIR [WET_DIR ...]")
dry = os.path.join(sys.argv[1], "profiles.csv")
if not os.path.exists(dry):
    with open(os.path.join(sys.argv[1], "fits.json")) as f:
        fit = json.load(f)
    base = fit["fit_variants"]["baseline"]
    dry = (fit["mu"], fit["c_Pa"], base["p_min_Pa"], base["p_max_Pa"])
    print("dry band: the line of %s/fits.json, tau = %.4f p + %.3f Pa over %.2f-%.2f Pa" % ((sys.argv[1],) + dry))
for wet_dir in sys.argv[2:]:
    e = cell_fits.excess_shear(os.path.join(wet_dir, "profiles.csv"), dry)
    np.savetxt(os.path.join(wet_dir, "excess_shear.csv"), np.array(e["rows"]), delimiter=",", comments="",
               header="z_m,p_Pa,tau_Pa,tau_dry_at_p_Pa,excess_Pa")
    print("%s against %s: excess %.3f Pa (low p %.3f, high p %.3f); c with mu = %.2f: %.3f +- %.3f Pa"
          % (wet_dir, sys.argv[1], e["excess_Pa"], e["excess_low_Pa"], e["excess_high_Pa"], e["mu_fixed"], e["c_fixed_mu_Pa"], e["c_fixed_mu_err_Pa"]))
    for z, p, tau, tau_dry, ex in e["rows"]:
        print("  z %5.1f mm  p %6.2f Pa  tau %6.3f  dry %6.3f  excess %6.3f Pa" % (1e3 * z, p, tau, tau_dry, ex))
