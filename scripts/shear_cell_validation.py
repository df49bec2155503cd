# Validation runs of the split-bottom cell, the experiments of the cause analysis
# (docs/studies/gladkyy-cause-analysis.md): one dry cell is prepared (filled and settled) once; each case
# runs from that same packing (wet cases get their liquid at the first step).
# Run:  build/yade-capillary -j1 -n -x scripts/shear_cell_validation.py CASE [CONFIG [PREPARATION]]
#   CASE: dry | wet13.6nl | wet74.2nl, or Gladkyy's other models at 13.6 nl: wet13.6nl_weigert |
#   wet13.6nl_willett_reduced | wet13.6nl_rabinovich_lambert
#   CONFIG (scripts/studies/cell_configs.py): validation_2s (default) | validation_4s, validation_5s
#   (continue validation_2s to 4 or 5 s of rotation) | validation_10s (continue validation_5s to 10 s) | validation (5 s from the prepared cell)
#   | validation_g22 (5 s of the validation cell under 2.2 g, prepared on its own)
#   PREPARATION: dry (default: the dry cell given the liquid at the first step) | wet (a cell filled
#   and settled with the liquid of CASE; results in results/shear_cell/CONFIG_wetprep/CASE)
#   CASE = report: compare the analysed cases of CONFIG with Gladkyy 2014 (report.md, report.csv)
# Cases may run in parallel once the dry cell exists (run dry first, or prepare alone with CASE = prepare).
# Writes results/shear_cell/CONFIG/CASE/{torque.csv, snap_*.npz, run.json, fits.json, profiles.csv, ...,
# final.yade.gz} (fits.json with the study's entries, scripts/studies/cell_study.py); the prepared cell is
# results/shear_cell/validation/dry/prepared.yade.gz (for a configuration that differs from validation in
# more than its run parameters: results/shear_cell/CONFIG/dry/prepared.yade.gz).
import json
import os
import sys

from yade_capillary import shearcell

sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # yade does not put the script's folder on sys.path
from studies import cell_configs, cell_report, cell_study  # noqa: E402

case = sys.argv[1]
config = sys.argv[2] if len(sys.argv) > 2 else "validation_2s"
if case == "report":
    print(cell_report.report(os.path.join("results", "shear_cell", config)))
    sys.exit(0)
preparation = sys.argv[3] if len(sys.argv) > 3 else "dry"
if preparation not in ("dry", "wet"):
    raise ValueError("PREPARATION: %r is not one of dry, wet" % preparation)
if preparation == "wet":  # settled with its own liquid: bridges formed while the packing settled
    prepared = os.path.join("results", "shear_cell", "validation", case, "prepared_wet.yade.gz")
    if not os.path.exists(prepared):
        os.makedirs(os.path.dirname(prepared), exist_ok=True)
        shearcell.prepare("validation", case, prepared)
    outdir = os.path.join("results", "shear_cell", config + "_wetprep", case)
    run = shearcell.run(prepared, outdir, config=config)
    print("run: %.3g particle-steps/s, %d steps in %.1f s" % (run["particle_steps_per_s"], run["steps"], run["wall_s"]))
    fit = cell_study.analyse(outdir)
    print(json.dumps({k: fit[k] for k in ("mu", "mu_err", "c_Pa", "c_err_Pa", "Rc_m", "W_m", "torque_Nm", "band_points")}, indent=1, default=float))
    sys.exit(0)
cell = shearcell.preparation_of(config)
prepared = os.path.join("results", "shear_cell", cell, "dry", "prepared.yade.gz")
if not os.path.exists(prepared):
    os.makedirs(os.path.dirname(prepared), exist_ok=True)
    shearcell.prepare(cell, "dry", prepared)
if case == "prepare":
    sys.exit(0)
if config in cell_configs.CONTINUES:  # from the final state of the earlier run of this case
    prepared = os.path.join("results", "shear_cell", cell_configs.CONTINUES[config], case, "final.yade.gz")
outdir = os.path.join("results", "shear_cell", config, case)
run = shearcell.run(prepared, outdir, config=config, case=case)
print("run: %.3g particle-steps/s, %d steps in %.1f s" % (run["particle_steps_per_s"], run["steps"], run["wall_s"]))
fit = cell_study.analyse(outdir)
print(json.dumps({k: fit[k] for k in ("mu", "mu_err", "c_Pa", "c_err_Pa", "Rc_m", "W_m", "torque_Nm", "torque_cg_at_Rs_Nm", "band_points")}, indent=1, default=float))
sys.exit(0)
