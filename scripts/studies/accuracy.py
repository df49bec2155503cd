"""Error of every capillary model and rupture rule against the exact Young-Laplace solver, and
cost per evaluation (plain python3 or inside yade).

Errors are relative, |F_model - F_exact| / F_exact, at gap fractions of the exact rupture gap;
a model whose own rupture distance is shorter than the gap returns 0 there (error 1), as it would
in a simulation. Two point sets: Gladkyy's Table 1 and a seeded random grid over V* = V/Rh^3 in
[1e-4, 0.1], theta in [0, 50 deg], R_large/R_small in [1, 4].
"""
import csv
import json
import math
import os
import random
import statistics
import subprocess

from yade_capillary import cases, kernels

FRACTIONS = (0.0, 0.25, 0.5, 0.75, 0.95)
GAMMA = 0.02  # [N/m]; errors do not depend on it


def grid_points(n, seed=2014):
    """Seeded random bridges (code, R1, R2, V, theta) over the domain, SI units."""
    rng = random.Random(seed)
    pts = []
    for i in range(n):
        vstar = math.exp(rng.uniform(math.log(1e-4), math.log(0.1)))
        theta = rng.uniform(0, math.radians(50))
        R1 = 1e-3
        R2 = R1 * rng.uniform(1, 4)
        Rh = 2 * R1 * R2 / (R1 + R2)
        pts.append(("G%03d" % i, R1, R2, vstar * Rh ** 3, theta))
    return pts


def table1_points():
    return [(c.code, c.R1_m, c.R2_m, c.volume_m3, c.theta_rad) for c in cases.GLADKYY2014_TABLE1]


def evaluate(point_sets):
    """point_sets: {name: [points]}. Returns (force_rows, rupture_rows) as lists of dicts."""
    force_rows, rupture_rows = [], []
    for set_name, points in point_sets.items():
        for code, R1, R2, V, theta in points:
            exact = kernels.YoungLaplaceBridge(R1, R2, V, theta)
            ar = exact.rupture_gap
            F_exact = {f: exact.solve(f * ar, GAMMA)["force_neck"] for f in FRACTIONS}
            for rule in kernels.RUPTURE_NAMES:
                a_rule = kernels.rupture_distance(rule, R1, R2, V, theta)
                rupture_rows.append(dict(set=set_name, point=code, rule=rule, rupture_exact_m=ar, rupture_rule_m=a_rule,
                                         rel_error=abs(a_rule - ar) / ar))
                for model in kernels.MODEL_NAMES:
                    for f in FRACTIONS:
                        F = kernels.force(model, f * ar, R1, R2, V, GAMMA, theta, rupture=rule)
                        force_rows.append(dict(set=set_name, point=code, model=model, rule=rule, fraction=f, F_exact_N=F_exact[f],
                                               F_model_N=F, rel_error=abs(F - F_exact[f]) / F_exact[f]))
    return force_rows, rupture_rows


def summarize(force_rows):
    """Median and worst error per (set, model, rule, fraction), and over all fractions ('all')."""
    groups = {}
    for r in force_rows:
        for frac in (r["fraction"], "all"):
            groups.setdefault((r["set"], r["model"], r["rule"], frac), []).append(r["rel_error"])
    return [dict(set=k[0], model=k[1], rule=k[2], fraction=k[3], median=statistics.median(v), worst=max(v), n=len(v))
            for k, v in groups.items()]


def costs(model_cost_exe, min_time="0.2", repetitions=5):
    """ns per evaluation of every model and of the solver, from the Google Benchmark binary: the
    median CPU time of `repetitions` runs in random order (CPU time, so that other processes on a
    shared machine do not count; interleaved, so that drifts affect every model alike)."""
    out = subprocess.run([model_cost_exe, "--benchmark_format=json", "--benchmark_min_time=%s" % min_time,
                          "--benchmark_repetitions=%d" % repetitions, "--benchmark_enable_random_interleaving=true",
                          "--benchmark_report_aggregates_only=true"], check=True, capture_output=True, text=True).stdout
    scale = {"ns": 1.0, "us": 1e3, "ms": 1e6}
    return {b["run_name"]: b["cpu_time"] * scale[b["time_unit"]] for b in json.loads(out)["benchmarks"]
            if b.get("aggregate_name") == "median" and not b["run_name"].endswith("/make")}  # per force, not per bridge


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def markdown(summary, rupture_rows, cost_ns, set_name, rule="willett"):
    """Markdown table: per model, median/worst error per gap fraction (one rule), cost ratio."""
    cheapest = min(v for k, v in cost_ns.items() if k != "young_laplace")
    lines = ["### %s, rupture rule `%s` (young_laplace_table and linear_irreversible use their own range)" % (set_name, rule), "",
             "| model | " + " | ".join("a = %g a_r: median / worst" % f for f in FRACTIONS) + " | ns/eval | cost ratio |",
             "|---|" + "---|" * (len(FRACTIONS) + 2)]
    for model in kernels.MODEL_NAMES:
        cells = []
        for f in FRACTIONS:
            s = next(r for r in summary if r["set"] == set_name and r["model"] == model and r["rule"] == rule and r["fraction"] == f)
            cells.append("%.2f %% / %.2f %%" % (100 * s["median"], 100 * s["worst"]))
        lines.append("| %s | %s | %.1f | %.2f |" % (model, " | ".join(cells), cost_ns[model], cost_ns[model] / cheapest))
    lines.append("| young_laplace (solver) | exact | | | | | %.0f | %.0f |" % (cost_ns["young_laplace"], cost_ns["young_laplace"] / cheapest))
    lines += ["", "Rupture distance error against the exact rupture gap (%s):" % set_name, "", "| rule | median | worst |", "|---|---|---|"]
    for r in kernels.RUPTURE_NAMES:
        errs = [x["rel_error"] for x in rupture_rows if x["set"] == set_name and x["rule"] == r]
        lines.append("| %s | %.2f %% | %.2f %% |" % (r, 100 * statistics.median(errs), 100 * max(errs)))
    return "\n".join(lines) + "\n"


def pareto_plot(summary, cost_ns, set_name, path, rule="willett"):
    """Median and worst error over all gap fractions versus cost per evaluation (log-log)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.8))
    for model in kernels.MODEL_NAMES:
        s = next(r for r in summary if r["set"] == set_name and r["model"] == model and r["rule"] == rule and r["fraction"] == "all")
        ax.plot([cost_ns[model]] * 2, [max(s["median"], 1e-5), max(s["worst"], 1e-5)], "-", color="0.7")
        ax.plot(cost_ns[model], max(s["median"], 1e-5), "o")
        ax.plot(cost_ns[model], max(s["worst"], 1e-5), "v", color=ax.lines[-1].get_color())
        ax.annotate(model, (cost_ns[model], max(s["median"], 1e-5)), fontsize=7, xytext=(4, 2), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("cost per force evaluation [ns]")
    ax.set_ylabel("relative force error vs Young-Laplace")
    ax.set_title("%s, gaps 0..0.95 a_rupture: median (o) and worst (v)" % set_name, fontsize=9)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def run(outdir, model_cost_exe, n_grid=60, min_time="0.2"):
    """Full benchmark: writes errors.csv, rupture.csv, summary.csv, summary.md, pareto.png."""
    os.makedirs(outdir, exist_ok=True)
    sets = {"table1": table1_points(), "grid": grid_points(n_grid)}
    force_rows, rupture_rows = evaluate(sets)
    summary = summarize(force_rows)
    cost_ns = costs(model_cost_exe, min_time)
    write_csv(os.path.join(outdir, "errors.csv"), force_rows)
    write_csv(os.path.join(outdir, "rupture.csv"), rupture_rows)
    write_csv(os.path.join(outdir, "summary.csv"), summary)
    with open(os.path.join(outdir, "costs.csv"), "w") as f:
        f.write("model,ns_per_evaluation\n" + "".join("%s,%.3f\n" % kv for kv in cost_ns.items()))
    md = "# Capillary models against the exact Young-Laplace solver\n\n" + "\n".join(
        markdown(summary, rupture_rows, cost_ns, s, rule) for s in sets for rule in kernels.RUPTURE_NAMES)
    with open(os.path.join(outdir, "summary.md"), "w") as f:
        f.write(md)
    pareto_plot(summary, cost_ns, "grid", os.path.join(outdir, "pareto.png"))
    return summary, rupture_rows, cost_ns, md
