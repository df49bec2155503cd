# Where the wet band's excess shear stress over the dry material comes from, in Gladkyy's cell at his
# scale: for saved states of complete runs (committed state.npz, taken from git by commit), one step from
# the state, then the band's stress split into the separated bridges, the contacts and the kinetic part
# (studies/cell_stress_parts.py, stress_parts), and the excess over the dry line tau - (c + mu p) split the same way
# (band_decomposition; the band of each run is that of its complete fit, the dry line that of
# the dry run's fits.json). Writes OUT (CSV, one row per state, rewritten after each) and prints it as a
# markdown table.
# Run:  build/yade-capillary -j1 -n -x scripts/stress_parts.py OUT.csv CASE@COMMIT [CASE@COMMIT ...]
#   e.g. wet13.6nl_weigert@2c0a8fb (the state.npz of data/shear_cell_runs/gladkyy_size/CASE at that commit)
import csv
import json
import os
import subprocess
import sys
import tempfile

import numpy as np
from yade import O

from yade_capillary import shearcell

sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # yade does not put the script's folder on sys.path
from studies import cell_stress_parts  # noqa: E402

root = os.path.join("data", "shear_cell_runs", "gladkyy_size")
if len(sys.argv) < 3:
    raise ValueError("usage: stress_parts.py OUT.csv CASE@COMMIT [CASE@COMMIT ...]")
out_path, specs = sys.argv[1], sys.argv[2:]
for spec in specs:
    case = spec.split("@")[0]
    if "@" not in spec or case not in shearcell.ALL_CASES:
        raise ValueError("CASE@COMMIT: %r is not of the form CASE@COMMIT with CASE one of %s" % (spec, ", ".join(shearcell.ALL_CASES)))
    if not os.path.exists(os.path.join(root, case, "run.json")):
        raise ValueError("CASE@COMMIT: %r: the run of %s is not complete (no run.json): its band is not known" % (spec, case))
with open(os.path.join(root, "dry", "fits.json")) as f:
    dry = json.load(f)
dry_line = (dry["mu"], dry["c_Pa"])

bands = {}  # case: its band nodes (cell_stress_parts.run_band), fitted once
rows = []
with tempfile.TemporaryDirectory() as tmp:
    for spec in specs:
        case, commit = spec.split("@")
        state = os.path.join(tmp, "state.npz")
        with open(state, "wb") as f:
            subprocess.run(["git", "show", "%s:%s/%s/state.npz" % (commit, root, case)], stdout=f, check=True)
        info = shearcell.load_state(state)
        O.step()  # the forces of the saved state
        snap = os.path.join(tmp, "snapshot.npz")
        shearcell.snapshot(snap, info)
        parts = cell_stress_parts.stress_parts(dict(np.load(snap)), info["cfg"])
        row = {"case": case, "commit": commit, "step": info["done_steps"], "t_s": info["t_offset_s"]}
        if case not in bands:
            bands[case] = cell_stress_parts.run_band(os.path.join(root, case))
        row.update(cell_stress_parts.band_decomposition(parts, bands[case], dry_line))
        rows.append(row)
        with open(out_path, "w", newline="") as f:  # after every state: a run stopped early keeps its rows
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        print("%s: p %.2f Pa, tau %.3f Pa, excess %.3f Pa (bridges %.3f, contacts %.3f, kinetic %.3f)" % (
            spec, row["p_Pa"], row["tau_Pa"], row["excess_Pa"], row["excess_bridges_Pa"], row["excess_contacts_Pa"], row["excess_kinetic_Pa"]), flush=True)

keys = [k for k in rows[0] if k.endswith("_Pa")]
print("| state | " + " | ".join(k.replace("_Pa", " [Pa]") for k in keys) + " |")
print("|---|" + "---|" * len(keys))
for r in rows:
    print("| %s@%s (step %d) | " % (r["case"], r["commit"], r["step"]) + " | ".join("%.3f" % r[k] for k in keys) + " |")
