# CI regression of Richefeu 2008's direct shear test (yade_capillary.directshear, ci configuration, seed 1), dry
# and at w = 1 %, against the references of scripts/direct_shear_reference.py within 4 seed-to-seed standard
# deviations: the Mohr-Coulomb c and phi of each water content, and of the fit of both with one friction angle its
# phi and the cohesion that the wetting adds. And the capillary cohesion itself (Richefeu2008 section 3.2.2, Fig. 6:
# c of about 120 Pa above w = 0.1 %, phi independent of w): the wet c above the dry c by at least 3 standard errors,
# both c from the fit with one friction angle, the standard error being the larger of the difference's
# seed-to-seed scatter and its fit's. (Fitted alone, each c carries the error of the steeper stress's
# fluctuations extrapolated to sigma = 0: about 19 Pa against 11 Pa for the difference with one angle.)
import json
import os
import sys
import tempfile

from testing import Checker

from yade_capillary import directshear as ds

ck = Checker("test_direct_shear_ci")
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(sys.argv[0]))))  # yade puts the script's path in sys.argv[0]
with open(os.path.join(root, "tests", "data", "direct_shear_ci_reference.json")) as f:
    ref = json.load(f)
cfg = ds.CONFIGS["ci"]
ck.true(list(cfg["sigmas"]) == ref["lid_stresses_Pa"], "the reference was made at the configuration's lid stresses %s" % (ref["lid_stresses_Pa"],))
runs, fitted = ds.series("ci", (0.0, 0.01), cfg["sigmas"], tempfile.mkdtemp(prefix="direct_shear_ci_"), seed=1)
both = ds.common_friction(runs)
cov = both["c_cov_Pa2"]
dc = both["c_Pa"][0.01] - both["c_Pa"][0.0]
got = {"w0": fitted[0.0], "w0.01": fitted[0.01], "common": dict(phi_deg=both["phi_deg"], dc_Pa=dc)}
for case, values in got.items():
    for k, v in values.items():
        if k in ref["cases"][case]:
            r = ref["cases"][case][k]
            ck.close(v, r["mean"], 0, "%s %s" % (case, k), "seed scatter of %s (%s)" % (ref["command"], r["values"]), atol=4 * r["std"])
se = max(ref["cases"]["common"]["dc_Pa"]["std"], (cov[0.0][0.0] + cov[0.01][0.01] - 2 * cov[0.0][0.01]) ** 0.5)
ck.true(dc >= 3 * se, "capillary cohesion: c(1 %%) - c(dry) = %.1f - %.1f Pa = %.1f standard errors of %.1f Pa (>= 3)"
        % (both["c_Pa"][0.01], both["c_Pa"][0.0], dc / se, se))
ck.finish()
