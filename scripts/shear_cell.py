# Split-bottom ring shear cell: prepare (fill, settle, O.save), run (rotate, torques, snapshots)
# and analyse (coarse-graining, fits) one configuration and liquid case.
# Run:  build/yade-capillary -j1 -n -x scripts/shear_cell.py CONFIG CASE [outdir]
#   CONFIG: ci | validation | gladkyy_size (py/yade_capillary/shearcell.py), or a configuration of the studies
#   (scripts/studies/cell_configs.py, e.g. ci_dt100: ci at tc/100)   CASE: dry | wet13.6nl | wet74.2nl
# Writes results/shear_cell/CONFIG/CASE/{prepared.yade.gz, torque.csv, snap_*.npz, fits.json, profiles.csv, ...}
import json
import os
import sys

from yade_capillary import cellanalysis, shearcell

config, case = sys.argv[1], sys.argv[2]
if config not in shearcell.CONFIGS:  # the studies' configurations; yade does not put the script's folder on sys.path
    sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))
    from studies import cell_configs  # noqa: F401  (registers them in shearcell.CONFIGS)
outdir = sys.argv[3] if len(sys.argv) > 3 else os.path.join("results", "shear_cell", config, case)
os.makedirs(outdir, exist_ok=True)
prepared = os.path.join(outdir, "prepared.yade.gz")
shearcell.prepare(config, case, prepared)
run = shearcell.run(prepared, outdir)
print("run: %.3g particle-steps/s, %d steps in %.1f s" % (run["particle_steps_per_s"], run["steps"], run["wall_s"]))
fit = cellanalysis.analyse(outdir)
print(json.dumps({k: fit[k] for k in ("mu", "mu_err", "c_Pa", "c_err_Pa", "Rc_m", "W_m", "torque_Nm", "band_points")}, indent=1, default=float))
sys.exit(0)
