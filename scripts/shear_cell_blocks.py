# The scatter of shear-cell fits over time (studies/cell_fits.py, block_fits): a run's snapshots in BLOCKS
# consecutive blocks (default 3), each fitted on its own; prints mu and c (and the band) per block with
# the standard error of their mean, and writes RUNDIR/blocks.json. Each snapshot is reduced once to its
# CG fields (cg_NNN.npz in KEEP, default RUNDIR; kept so that the blocks can be refitted without the
# snapshots). Plain python3:
#   PYTHONPATH=build/python /usr/bin/python3 scripts/shear_cell_blocks.py RUNDIR [BLOCKS [KEEP]]
import json
import os
import sys

from studies import cell_fits

rundir = sys.argv[1]
blocks = int(sys.argv[2]) if len(sys.argv) > 2 else 3
keep = sys.argv[3] if len(sys.argv) > 3 else None
out = cell_fits.block_fits(rundir, blocks, keep)
with open(os.path.join(rundir if keep is None else keep, "blocks.json"), "w") as f:
    json.dump(out, f, indent=1, default=float)
for b in out["blocks"]:
    q = b["fit_variants"].get("quadratic", {})
    print("snapshots %s: mu %.3f, c %.3f Pa, Rc %.1f mm, W %.1f mm, quadratic k %.4f 1/Pa" % (
        b["snapshots"], b["mu"], b["c_Pa"], 1e3 * b["Rc_mean_m"], 1e3 * b["W_mean_m"], q.get("k_1_Pa", float("nan"))))
print("%s, %d blocks: mu %.3f +- %.3f, c %.3f +- %.3f Pa, Rc %.1f +- %.1f mm, W %.1f +- %.1f mm" % (
    rundir, blocks, out["mu"], out["mu_err"], out["c_Pa"], out["c_Pa_err"], 1e3 * out["Rc_mean_m"], 1e3 * out["Rc_mean_m_err"],
    1e3 * out["W_mean_m"], 1e3 * out["W_mean_m_err"]))
