# Regenerates tests/data/direct_shear_ci_reference.json: the ci configuration of the direct shear cell, dry and
# w = 1 % at its two lid stresses, for several packings (seeds). Stores the mean and seed-to-seed standard deviation
# of the Mohr-Coulomb c and phi of each water content (fitted alone), of the friction angle fitted to both at once
# and of the cohesion that the wetting adds with it (directshear.common_friction), and the command line. The CI
# regression (tests/yade/test_direct_shear_ci.py) compares its own run (seed 1) with these values.
# Run:  build/yade-capillary -j1 -n -x scripts/direct_shear_reference.py [nseeds] [workdir]   (about 7 min per seed)
# A workdir that holds the runs of an earlier call is read, not run again.
import os
import sys
import tempfile

from yade_capillary import directshear as ds
sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # yade does not put the script's folder on sys.path
from studies import seedref  # noqa: E402

nseeds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
work = sys.argv[2] if len(sys.argv) > 2 else tempfile.mkdtemp(prefix="direct_shear_ref_")
root = os.path.dirname(os.path.dirname(os.path.realpath(sys.argv[0])))  # yade puts the script's path in sys.argv[0]
cfg = ds.CONFIGS["ci"]
values = {}
for seed in range(1, nseeds + 1):
    runs, fitted = ds.series("ci", (0.0, 0.01), cfg["sigmas"], os.path.join(work, "seed%d" % seed), seed=seed)
    for w, fit in fitted.items():
        for k in ("c_Pa", "phi_deg"):
            values.setdefault("w%g" % w, {}).setdefault(k, []).append(fit[k])
    both = ds.common_friction(runs)
    values.setdefault("common", {}).setdefault("phi_deg", []).append(both["phi_deg"])
    values["common"].setdefault("dc_Pa", []).append(both["c_Pa"][0.01] - both["c_Pa"][0.0])
    print("seed", seed, values)
seedref.write(os.path.join(root, "tests", "data", "direct_shear_ci_reference.json"),
              "build/yade-capillary -j1 -n -x scripts/direct_shear_reference.py %d" % nseeds, values, config="ci",
              lid_stresses_Pa=list(cfg["sigmas"]), seeds=list(range(1, nseeds + 1)))
sys.exit(0)
