#!/usr/bin/env python3
# Kernel fuzz, nightly size: 1e6 force evaluations over every model x rupture rule with wide and
# absurd inputs (tests/support/fuzz.py); prints the counts of every outcome and exits 1 if any
# failure category is non-zero. Plain python3:
#   PYTHONPATH=build/python /usr/bin/python3 tests/fuzz_kernels.py [n_evaluations=1e6] [seed=1]
# (the CI size, 1e5, is tests/python/test_fuzz.py)
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "support"))
import fuzz  # noqa: E402

n = int(float(sys.argv[1])) if len(sys.argv) > 1 else 1000000
seed = int(sys.argv[2]) if len(sys.argv) > 2 else 1
report = fuzz.run(n, seed=seed, progress=lambda i, m: print("  %d/%d bridges" % (i, m), file=sys.stderr) if i % 5000 == 0 else None)
print(fuzz.format_report(report))
sys.exit(1 if fuzz.failures(report) else 0)
