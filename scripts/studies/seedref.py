"""The seed-scatter references of the CI regressions (scripts/shear_cell_reference.py,
scripts/direct_shear_reference.py): per case and quantity the mean, the seed-to-seed standard deviation and the
values, written as JSON with the command that made them. Plain numpy."""
import json

import numpy as np


def write(path, command, values, **meta):
    """values: {case: {quantity: [one value per seed]}}; meta: what else the reference records (config, seeds, ...)."""
    ref = dict(command=command, **meta,
               cases={c: {k: {"mean": float(np.mean(v)), "std": float(np.std(v, ddof=1)), "values": v} for k, v in q.items()} for c, q in values.items()})
    with open(path, "w") as f:
        json.dump(ref, f, indent=1)
    print("wrote", path)
