# Gladkyy's cell at his scale (the Luding/Roy proportions enlarged 2.2 times: about 168 000 flowing
# spheres, configuration gladkyy_size), run in segments of at most BUDGET_MIN minutes of wall time
# (default 110), each continuing the compact state of the last one (shearcell.save_state, about
# 19 MB). A state may be committed while its run lasts, so that another clone can continue it: once per
# segment, at its end (the 20-min saves are insurance against a crash; a commit per save multiplies the
# repository's size). When the run ends, remove prepared.npz, the states and CASE/interim/ from the
# repository: the summaries (fits.json, profiles.csv, contacts_vs_a.csv, torque.csv, PNGs) stay.
# Run:  build/yade-capillary -j1 -n -x scripts/shear_cell_gladkyy.py CASE [BUDGET_MIN [STOP]]   (two cases side by side, one core each)
#   CASE: prepare (fill and settle the dry cell once) | dry | wet13.6nl | wet74.2nl | wet13.6nl_<model>
#         | analyse (the fits of every complete case again, cellanalysis.analyse_reduced at Gladkyy's 13 heights)
#         | status (the fits of every case so far from its reduced snapshots, cellanalysis.interim, written to
#           CASE/interim/; the wet cases' excess shear stress over the dry band at the same pressure)
#   STOP: window (default: stop before the first snapshot of the averaging window) | end
# Writes data/shear_cell_runs/gladkyy_size/prepared.npz (settling.npz while it settles), and per case
# data/shear_cell_runs/gladkyy_size/CASE/{state.npz, torque.csv, cg_NNN.npz} (what the next segment continues
# from, and the CG fields of each snapshot; run.json and fits.json from cellanalysis.analyse_reduced when
# the run is complete) and results/shear_cell/gladkyy_size/CASE/ (the snapshots themselves).
import glob
import json
import os
import sys

from yade_capillary import cellanalysis, shearcell

case = sys.argv[1]
budget_min = float(sys.argv[2]) if len(sys.argv) > 2 else 110.0
stop = sys.argv[3] if len(sys.argv) > 3 else "window"
if not 0 < budget_min <= 120:
    raise ValueError("BUDGET_MIN: %g is outside (0, 120] (segments of at most 2 h)" % budget_min)
if stop not in ("window", "end"):
    raise ValueError("STOP: %r is not one of window, end" % stop)
if case not in ("prepare", "status", "analyse") and case not in shearcell.ALL_CASES:
    raise ValueError("CASE: %r is not one of prepare, status, analyse, %s" % (case, ", ".join(shearcell.ALL_CASES)))
root = os.path.join("data", "shear_cell_runs", "gladkyy_size")
if case == "analyse":
    for c in shearcell.ALL_CASES:
        if os.path.exists(os.path.join(root, c, "run.json")):
            fit = cellanalysis.analyse_reduced(os.path.join(root, c), heights=cellanalysis.GLADKYY_HEIGHTS)
            print("%s: mu %.4f, c %.3f Pa, Rc %s mm, W %s mm" % (c, fit["mu"], fit["c_Pa"], " ".join("%.0f" % (1e3 * x) for x in fit["Rc_m"] if x is not None),
                                                              " ".join("%.0f" % (1e3 * x) for x in fit["W_m"] if x is not None)))
    sys.exit(0)
if case == "status":
    fits = {}
    for c in shearcell.ALL_CASES:
        keep = os.path.join(root, c)
        if os.path.exists(os.path.join(keep, "state.npz")) and glob.glob(os.path.join(keep, "cg_*.npz")):
            fits[c] = cellanalysis.interim(keep, heights=cellanalysis.GLADKYY_HEIGHTS)
    print("| case | steps | t [s] | snapshots | mu | c [Pa] | c at mu = %.2f [Pa] | torque [mN m] | contacts per sphere |" % cellanalysis.GLADKYY_MU)
    print("|---|---|---|---|---|---|---|---|---|")
    for c, f in fits.items():
        g = f["fit_variants"].get("baseline_gladkyy_slope", {})
        print("| %s | %d of %d | %.3f | %d | %s | %s | %s | %s | %.3f |" % (
            c, f["done_steps"], f["steps"], f["t_s"], f["snapshots"], shearcell.fmt_value(f["mu"], f["mu_err"]),
            shearcell.fmt_value(f["c_Pa"], f["c_err_Pa"], "%.2f"), shearcell.fmt_value(g.get("c_Pa"), g.get("c_err_Pa"), "%.2f"),
            shearcell.fmt_value(None if f["torque_Nm"] is None else abs(f["torque_Nm"]), None, "%.1f", 1e3),
            f["contact_numbers"]["mechanical_per_particle"]))
    if "dry" in fits:
        dry = os.path.join(root, "dry", "interim", "profiles.csv")
        for c in fits:
            if c != "dry":
                try:
                    e = cellanalysis.excess_shear(os.path.join(root, c, "interim", "profiles.csv"), dry)
                    print("%s: excess shear stress over dry at the same pressure %.2f Pa (low p %.2f, high p %.2f)"
                          % (c, e["excess_Pa"], e["excess_low_Pa"], e["excess_high_Pa"]))
                except ValueError as err:
                    print("%s: %s" % (c, err))
    sys.exit(0)
prepared = os.path.join(root, "prepared.npz")
if case == "prepare":
    os.makedirs(root, exist_ok=True)
    # No O.save: its gzip archive of 2e5 bodies takes longer than the settling's last hour. The settling
    # itself is saved every 20 min to settling.npz (continued from it when the settling is stopped before its end).
    settling = os.path.join(root, "settling.npz")
    info = shearcell.prepare("gladkyy_size", "dry", None, checkpoint=settling)
    shearcell.save_state(prepared, info)
    if os.path.exists(settling):
        os.remove(settling)
    print("prepared: %d flowing spheres, %s (%.1f MB)" % (len(info["flowing"]), prepared, os.path.getsize(prepared) / 1e6))
    sys.exit(0)
until = shearcell.snapshot_steps(shearcell.CONFIGS["gladkyy_size"], shearcell.CONFIGS["gladkyy_size"]["dt_over_tc"] * shearcell.CONFIGS["gladkyy_size"]["tc"])[0] if stop == "window" else None
out = shearcell.run_segment(prepared, os.path.join("results", "shear_cell", "gladkyy_size", case), case=case, budget_s=60 * budget_min,
                            until_step=until, keep=os.path.join(root, case))
print("segment: %(done_steps)d of %(steps)d steps done, t = %(t_s).3f s, %(particle_steps_per_s).3g particle-steps/s, complete %(complete)s" % out)
if out["complete"]:  # fits from the reduced snapshots (committed), whichever segments took them
    fit = cellanalysis.analyse_reduced(os.path.join(root, case), heights=cellanalysis.GLADKYY_HEIGHTS)
    print(json.dumps({k: fit[k] for k in ("mu", "mu_err", "c_Pa", "c_err_Pa", "Rc_m", "W_m", "torque_Nm", "band_points")}, indent=1, default=float))
sys.exit(0)
