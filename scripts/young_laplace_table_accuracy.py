#!/usr/bin/env python3
# young_laplace_table against the exact Young-Laplace solver on seeded random bridges over the table's domain
# (V* 1e-5..0.5, theta1, theta2 0..70 deg, R_small/R_large 1/4..1 and walls): force at random gaps, rupture
# distance and transfer ratio at rupture. Plain python3:
#   PYTHONPATH=build/python /usr/bin/python3 scripts/young_laplace_table_accuracy.py [outdir] [--bridges N]
# Writes outdir/{points.csv, summary.csv} (default results/young_laplace_table) and, for the default 2000
# bridges, the tracked summary data/young_laplace_table/accuracy.csv. See studies/tableaccuracy.py.
import os
import sys
import time

from studies import tableaccuracy as ta

args = sys.argv[1:]
n = int(args[args.index("--bridges") + 1]) if "--bridges" in args else 2000
pos = [a for i, a in enumerate(args) if not a.startswith("--") and (i == 0 or args[i - 1] != "--bridges")]
outdir = pos[0] if pos else os.path.join("results", "young_laplace_table")
datadir = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "young_laplace_table") if n == 2000 else None

t0 = time.perf_counter()
rows, summary = ta.run(outdir, n, datadir, log=lambda i, t: print("  %d bridges, %.0f s" % (i, t), flush=True))
print("young_laplace_table against the solver, %d bridges x %d gaps (seed %d):" % (n, ta.GAPS_PER_BRIDGE, ta.SEED))
for s in summary:
    print("  %-22s %-9s n %5d  median %.2e  95th %.2e  worst %.2e" % (s["part"], s["quantity"], s["n"], s["median"], s["p95"], s["worst"]))
worst = max((r for r in rows if not r["refused"]), key=lambda r: r["force_rel_error_max"])
print("worst force: V* %.3g, theta1 %.2f, theta2 %.2f rad, R1 %.3g, R2 %.3g m at a/a_r %.3f" % (
    worst["vstar"], worst["theta1_rad"], worst["theta2_rad"], worst["R1_m"], worst["R2_m"], worst["force_worst_gap_fraction"]))
print("%.0f s; wrote %s/{points.csv, summary.csv}%s" % (time.perf_counter() - t0, outdir, ", data/young_laplace_table/accuracy.csv" if datadir else ""))
