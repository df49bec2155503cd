# Richefeu et al. 2008's simple compression test (section 4.2): the axial stress against the shortening and the
# strength (its peak) for each water content, protocol and fraction of dry pairs.
#   build/yade-capillary -j2 -n -x scripts/compression.py OUTDIR [config] [--w 0.02,0.04,0.06]
#              [--protocol particles[,update,lowest]] [--dry 0[,0.5]]
# Writes OUTDIR/runs.csv (one line per test) and OUTDIR/w<w>_<protocol>_dry<dry>/compression.csv. config: ci (the
# default, seconds) or paper. A test whose summary.json exists is read, not run again.
import csv
import json
import os
import sys

from yade_capillary import compression as cp

args = sys.argv[1:]
options = {"--w": "0.02,0.04,0.06", "--protocol": "particles", "--dry": "0"}
rest = []
while args:
    a = args.pop(0)
    if a in options:
        options[a] = args.pop(0)
    else:
        rest.append(a)
outdir = rest[0] if rest else "results/compression"
config = rest[1] if len(rest) > 1 else "ci"
runs = []
for w in [float(x) for x in options["--w"].split(",")]:
    for protocol in options["--protocol"].split(","):
        for dry in [float(x) for x in options["--dry"].split(",")]:
            where = os.path.join(outdir, "w%g_%s_dry%g" % (w, protocol, dry))
            if os.path.exists(os.path.join(where, "summary.json")):
                with open(os.path.join(where, "summary.json")) as f:
                    runs.append(json.load(f))
                continue
            runs.append(cp.run(config, w, where, protocol=protocol, dry_fraction=dry))
with open(os.path.join(outdir, "runs.csv"), "w", newline="") as f:
    out = csv.DictWriter(f, fieldnames=list(runs[0]))
    out.writeheader()
    out.writerows(runs)
