"""The shear-cell configurations of the cause analysis (docs/studies/gladkyy-cause-analysis.md), each a
variant of a configuration of yade_capillary.shearcell; importing this module registers them in
shearcell.CONFIGS, so that shearcell.prepare and run take their names."""
from yade_capillary import shearcell

VALIDATION = shearcell.VALIDATION
# The validation cell for the first 2 s of rotation (of Gladkyy's 5 s), averaged over the last 1 s.
# It is prepared exactly like `validation`, so run(..., config="validation_2s") accepts a cell
# prepared for either, and run() saves final.yade.gz to continue from.
VALIDATION_2S = dict(VALIDATION, run_s=2.0, snapshots=10, snapshot_dt_s=0.1)
# Continue a validation_2s run (its final.yade.gz) to 4 s and to Gladkyy's 5 s of rotation, averaged
# over the continuation with Gladkyy's 0.25 s between snapshots (he averaged 15 snapshots over the
# last 3.5 s of 5 s).
VALIDATION_4S = dict(VALIDATION, run_s=2.0, snapshots=8, snapshot_dt_s=0.25)
VALIDATION_5S = dict(VALIDATION, run_s=3.0, snapshots=12, snapshot_dt_s=0.25)
# Continue a validation_5s run to 10 s of rotation (the run-length experiment), averaged over the last
# 3.5 s (6.5-10 s), Gladkyy's averaging window.
VALIDATION_10S = dict(VALIDATION, run_s=5.0, snapshots=14, snapshot_dt_s=0.25)
# The ci cell at Gladkyy's time step, about tc/100 (he needed about 1e6 steps for 5 s at tc = 5.4e-4 s):
# the time-step experiment, compared with the ci references (tc/20).
CI_DT100 = dict(shearcell.CI, dt_over_tc=0.01)
# The validation cell under 2.2 g (5 s of rotation as Gladkyy): the pressures of a cell 2.2 times
# taller (the Gladkyy-size cell), p ~ rho g depth, with the particles, bridges and band geometry of
# the validation cell; the pressure-range experiment (c is a capillary stress, independent of g; only
# the range of p over which tau(p) is fitted grows). Prepared on its own.
VALIDATION_G22 = dict(VALIDATION, g=2.2 * shearcell.GRAVITY)
CONFIGS = {"validation_2s": VALIDATION_2S, "validation_4s": VALIDATION_4S, "validation_5s": VALIDATION_5S, "validation_10s": VALIDATION_10S,
           "ci_dt100": CI_DT100, "validation_g22": VALIDATION_G22}
# Configurations that start from the final state of another one's run of the same case.
CONTINUES = {"validation_4s": "validation_2s", "validation_5s": "validation_2s", "validation_10s": "validation_5s"}

shearcell.CONFIGS.update(CONFIGS)
