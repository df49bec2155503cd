# Richefeu et al. 2008's simple compression test (section 4.2): the axial stress against the shortening and the
# strength (its peak) for each water content, protocol and fraction of dry pairs.
#   build/yade-capillary -j2 -n -x scripts/compression.py OUTDIR [config] [--w 0.02,0.04,0.06]
#              [--protocol particles[,update,lowest]] [--dry 0[,0.5]]
# Writes OUTDIR/runs.csv (one line per test) and OUTDIR/w<w>_<protocol>_dry<dry>/compression.csv. A test whose
# summary.json exists is read, not run again.
import argparse
import json
import os
import sys

from yade_capillary import compression as cp, glassbeads

floats = lambda s: [float(x) for x in s.split(",")]
p = argparse.ArgumentParser(prog="compression.py", description="Richefeu 2008's simple compression series")
p.add_argument("outdir")
p.add_argument("config", nargs="?", default="ci", choices=sorted(cp.CONFIGS), help="ci (a minute) or paper")
p.add_argument("--w", type=floats, default=[0.02, 0.04, 0.06], help="water contents [-], comma-separated")
p.add_argument("--protocol", type=lambda s: s.split(","), default=["particles"], help="PendularBonds.protocol values, comma-separated")
p.add_argument("--dry", type=floats, default=[0.0], help="fractions of the pairs kept dry [-], comma-separated")
a = p.parse_args(sys.argv[1:])
runs = []
for w in a.w:
    for protocol in a.protocol:
        for dry in a.dry:
            where = os.path.join(a.outdir, "w%g_%s_dry%g" % (w, protocol, dry))
            if os.path.exists(os.path.join(where, "summary.json")):
                with open(os.path.join(where, "summary.json")) as f:
                    runs.append(json.load(f))
                continue
            runs.append(cp.run(a.config, w, where, protocol=protocol, dry_fraction=dry))
glassbeads.write_csv(os.path.join(a.outdir, "runs.csv"), runs)
