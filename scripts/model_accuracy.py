#!/usr/bin/env python3
# Error of every model and rupture rule against the exact Young-Laplace solver, and cost per
# evaluation (Google Benchmark). Plain python3:
#   PYTHONPATH=build/python /usr/bin/python3 scripts/model_accuracy.py [outdir] [--quick]
# Writes errors.csv, rupture.csv, summary.csv, costs.csv, summary.md, pareto.png
# (default results/model_accuracy). --quick: 12 grid points and short timings (CI).
import os
import sys

from studies import accuracy

args = [a for a in sys.argv[1:] if not a.startswith("--")]
quick = "--quick" in sys.argv
outdir = args[0] if args else os.path.join("results", "model_accuracy")
exe = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build", "model_cost")
summary, rupture_rows, cost_ns, md = accuracy.run(outdir, os.environ.get("MODEL_COST", exe), n_grid=12 if quick else 60,
                                                  min_time="0.01" if quick else "0.2")
print(md)
print("wrote %s/{errors.csv, rupture.csv, summary.csv, costs.csv, summary.md, pareto.png}" % outdir)
