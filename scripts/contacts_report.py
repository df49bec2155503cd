# Contacts against the surface separation a in the shear band and outside it (Gladkyy 2014 section
# 4.2, Fig. 9-10), from the contacts_vs_a.csv of analysed runs: per run, a_crit, the contacts per
# snapshot in contact / in the bin at a = 0 / short bridges (a <= a_crit/2) / long bridges, the share of short bridges and
# the band-over-outside density ratio of each class, and the mean force of the separated bins over the
# model's two-sphere force at those gaps (Fig. 9, bottom row). Prints a markdown table.
# Run:  PYTHONPATH=build/python /usr/bin/python3 scripts/contacts_report.py [RUNDIR ...]   (default: data/shear_cell_runs/*/*)
import glob
import json
import os
import sys

from yade_capillary import shearcell

from studies import cell_contacts

dirs = sys.argv[1:] or sorted(os.path.dirname(p) for p in glob.glob("data/shear_cell_runs/*/*/contacts_vs_a.csv"))
print("| run | a_crit [mm] | in contact | bin at a = 0 | short bridges | long bridges | short share | band/outside: contact, short, long "
      "| mean force / model, separated bins: median, weighted |")
print("|---|---|---|---|---|---|---|---|---|")
for d in dirs:
    try:
        g = cell_contacts.gap_classes(os.path.join(d, "contacts_vs_a.csv"))
    except ValueError as e:
        print("(skipped: %s)" % e, file=sys.stderr)
        continue
    print("| %s | %.3f | %.0f | %.0f | %.0f | %.0f | %.2f | %.2f, %.2f, %.2f |" % (
        os.path.relpath(d, "data/shear_cell_runs") if d.startswith("data/") else d, g["a_crit_m"] * 1e3, g["contact_per_snapshot"],
        g["straddling_per_snapshot"], g["short_per_snapshot"], g["long_per_snapshot"], g["short_share"], g["contact_band_over_outside"],
        g["short_band_over_outside"], g["long_band_over_outside"]), end="")
    with open(os.path.join(d, "run.json")) as f:
        run = json.load(f)
    liquid = shearcell.ALL_CASES[run["case"]]
    if liquid["wet"]:
        fm = cell_contacts.force_against_model(os.path.join(d, "contacts_vs_a.csv"), liquid["model"], run["cfg"]["R"], liquid["Vb"], liquid["gamma"],
                                              liquid["theta"])
        print(" %.4f, %.4f (%d bins) |" % (fm["median"], fm["weighted_mean"], fm["bins"]))
    else:
        print(" |")

# Gladkyy's "about 20 % more mechanical contacts" wet than dry (section 4.2) against where a contact is
# taken to end: wet pairs with a <= a_max over dry ones, for each wet run beside a finished dry run of the
# same cell (its interim/ snapshots if it is still running) whose bins are the same and have an edge at a = 0.
GAPS_OVER_R = (0.0, 0.001, 0.005, 0.01, 0.02, 0.05, 0.1, 0.25)
pairs = []
for d in dirs:
    cell = os.path.dirname(d.rstrip("/")) if os.path.basename(d.rstrip("/")) != "interim" else os.path.dirname(os.path.dirname(d.rstrip("/")))
    dry = os.path.join(cell, "dry", "contacts_vs_a.csv")
    if os.path.exists(dry) and os.path.abspath(os.path.dirname(dry)) != os.path.abspath(d) and "dry" not in os.path.relpath(d, cell):
        pairs.append((d, dry))
if pairs:
    print("\n| wet / dry pairs with a <= a_max | %s |" % " | ".join("%g R" % g for g in GAPS_OVER_R))
    print("|---|%s" % ("---|" * len(GAPS_OVER_R)))
    for d, dry in pairs:
        with open(os.path.join(d, "run.json")) as f:
            R = json.load(f)["cfg"]["R"]
        try:  # fixed bins with an edge at a = 0: the reduced snapshots of the Gladkyy-size runs
            rows = cell_contacts.count_ratio_vs_gap(os.path.join(d, "contacts_vs_a.csv"), dry, [g * R for g in GAPS_OVER_R])
        except ValueError as e:
            print("(skipped: %s)" % e, file=sys.stderr)
            continue
        print("| %s | %s |" % (os.path.relpath(d, "data/shear_cell_runs") if d.startswith("data/") else d, " | ".join("%.3f" % r[3] for r in rows)))
