# Richefeu et al. 2008's direct shear test (section 3.2): the residual shear stress of a split cylinder of
# glass beads for each water content and normal stress, and the Mohr-Coulomb c and phi per water content.
#   build/yade-capillary -j2 -n -x scripts/direct_shear.py OUTDIR [config] [--w 0,0.0005,0.001,0.01,0.02]
#              [--sigma 300,600,900] [--protocol particles] [--dry 0] [--speed 1]
# Writes OUTDIR/runs.csv (one line per test), OUTDIR/mohr_coulomb.csv (c, phi per water content, against the
# normal stress on the shear plane) and OUTDIR/w<w>_sigma<sigma>/shear.csv (stresses against displacement).
# config: ci (the default, minutes) or paper. --speed multiplies the shear speed of the configuration's inertial
# number. A test whose summary.json exists is read, not run again, so an interrupted series goes on where it
# stopped; the settled packing (OUTDIR/settled_<config>.yade.gz) is kept until the series is complete.
import csv
import json
import os
import sys

from yade_capillary import directshear as ds

args = sys.argv[1:]
options = {"--w": "0,0.01", "--sigma": "300,900", "--protocol": "particles", "--dry": "0", "--speed": "1"}
rest = []
while args:
    a = args.pop(0)
    if a in options:
        options[a] = args.pop(0)
    else:
        rest.append(a)
outdir = rest[0] if rest else "results/direct_shear"
config = rest[1] if len(rest) > 1 else "ci"
ws = [float(x) for x in options["--w"].split(",")]
sigmas = [float(x) for x in options["--sigma"].split(",")]
os.makedirs(outdir, exist_ok=True)
state = os.path.join(outdir, "settled_%s.yade.gz" % config)
runs = []
for w in ws:
    for sigma in sigmas:
        where = os.path.join(outdir, "w%g_sigma%g" % (w, sigma))
        if os.path.exists(os.path.join(where, "summary.json")):
            with open(os.path.join(where, "summary.json")) as f:
                runs.append(json.load(f))
            continue
        if not os.path.exists(state + ".json"):
            ds.prepare(config, state)
        runs.append(ds.run(config, w, sigma, where, protocol=options["--protocol"], dry_fraction=float(options["--dry"]),
                           speed=float(options["--speed"]), state=state))
with open(os.path.join(outdir, "runs.csv"), "w", newline="") as f:
    out = csv.DictWriter(f, fieldnames=list(runs[0]))
    out.writeheader()
    out.writerows(runs)
with open(os.path.join(outdir, "mohr_coulomb.csv"), "w", newline="") as f:
    out = csv.writer(f)
    out.writerow(["w", "c_Pa", "c_se_Pa", "phi_deg", "phi_se_deg"])
    for w in ws if len(sigmas) > 1 else ():  # a fit needs two normal stresses
        mine = [r for r in runs if r["w"] == w]
        c, se_c, phi, se_phi = ds.mohr_coulomb([r["sigma_plane_Pa"] for r in mine], [r["tau_residual_Pa"] for r in mine],
                                               [r["tau_se_Pa"] for r in mine])
        out.writerow([w, c, se_c, phi, se_phi])
        print("w = %g: c = %.1f +- %.1f Pa, phi = %.1f +- %.1f deg" % (w, c, se_c, phi, se_phi))
for path in (state, state + ".json"):
    if os.path.exists(path):
        os.remove(path)
