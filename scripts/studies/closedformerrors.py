"""What the closed-form bridge models get wrong beyond their fitted range (docs/models.md, "What the closed
forms get wrong beyond their range").

Every closed-form force model of the kernels (``MODELS``: all but the calibrated ``linear_irreversible`` and the
tabulated exact ``young_laplace_table``) and every rupture rule, against the exact Young-Laplace solver
(``kernels.YoungLaplaceBridge``, which takes the two contact angles separately), over the domain of the exact
table's successor, where the pendular bridge exists (docs/models.md, "Where the pendular bridge exists"):

* V* = V/Rh^3 log-uniform in ``VSTAR_RANGE``, Rh = 2 R1 R2/(R1 + R2) and a wall counting as Rh = 2 R1 (the
  kernels' convention, ``kernels.models()``);
* contact angles uniform in [0, ``THETA_MAX_DEG``]: theta2 = theta1 for the even bridges ("equal"), both drawn
  independently for the odd ones ("unequal");
* a sphere on a wall with probability ``WALL_SHARE``, otherwise two spheres with R_small/R_large uniform in
  [``RATIO_MIN``, 1] and the small one as solid 1 or 2 at random.

Each bridge draws the same six numbers from one seeded stream, so the first n bridges of a sample do not depend
on its size (a quick run and the tests recompute the first bridges of the full sample).

Per bridge: the exact rupture gap, the exact force (neck method) at ``FRACTIONS`` of it, and each model's force
at the same gaps with the rupture rule ``RULE`` and both contact angles as given (the models combine them by the
mean of the cosines). A model refuses a bridge outside its fitted domain (V* in [1e-5, 0.1], each angle <= 50
deg, ratio <= 4 for richefeu and soulie); such bridges are evaluated with ``extrapolate=True``, as a user would
run them, and marked ``domain = extrapolated`` with the variable that was refused. Error: (F_model - F_exact) /
F_exact. Where the model's rupture distance is shorter than the gap its force is 0 and the error -1, as in a
simulation: kept in the metric ``force``, left out of ``force_attached``, counted in ``n_ruptured_early``. The
exact force at contact turns repulsive at large angles and volumes; such points (F_exact <= 0) have no relative
error and are counted in ``n_exact_not_attractive`` instead. Rupture rules: (a_rule - a_exact) / a_exact.

CSV columns carry their unit as a suffix (_m, _m3, _N, _deg); columns without one are dimensionless, relative
errors as fractions (0.01 = 1 %).
"""
import csv
import math
import os
from collections import namedtuple

import numpy as np

from yade_capillary import kernels

SEED = 20250
N_BRIDGES = 2000
N_QUICK = 120
VSTAR_RANGE = (1e-5, 0.5)   # V* = V/Rh^3
VSTAR_FIT = 0.1             # upper end of every closed form's fitted V* (kernels.models())
THETA_MAX_DEG = 70.0
RATIO_MIN = 0.25            # R_small/R_large
WALL_SHARE = 0.2
R_SMALL = 1e-3              # [m]; relative errors do not depend on it
GAMMA = 0.072               # [N/m]; relative errors do not depend on it
FRACTIONS = (0.0, 0.25, 0.5, 0.75, 0.95)  # gaps, per exact rupture gap
RULE = "willett"            # the models' rupture rule (the kernels' default)
SKIPPED = {"linear_irreversible": "calibrated from another model", "young_laplace_table": "the tabulated exact bridge"}
MODELS = tuple(m for m in kernels.MODEL_NAMES if m not in SKIPPED)
RULES = tuple(kernels.RUPTURE_NAMES)
SPLITS = ("V*<=0.1 equal", "V*<=0.1 unequal", "V*>0.1 equal", "V*>0.1 unequal")
ALL_SPLITS = SPLITS + ("inside domain", "extrapolated", "all")
METRICS = ("force", "force_attached", "force_contact")

Bridge = namedtuple("Bridge", "index geometry angles vstar ratio R1_m R2_m Rh_m volume_m3 theta1_deg theta2_deg")


def harmonic_radius(R1, R2):
    """Rh [m] = 2 R1 R2 / (R1 + R2); a wall (R2 = inf) counts as Rh = 2 R1."""
    return 2 * R1 if math.isinf(R2) else 2 * R1 * R2 / (R1 + R2)


def sample(n=N_BRIDGES, seed=SEED):
    """n seeded bridges (``Bridge``, SI units, angles in degrees); six draws per bridge from one stream."""
    rng = np.random.default_rng(seed)
    lo, hi = math.log(VSTAR_RANGE[0]), math.log(VSTAR_RANGE[1])
    out = []
    for i in range(n):
        u = rng.random(6)
        vstar = math.exp(lo + u[0] * (hi - lo))
        angles = "equal" if i % 2 == 0 else "unequal"
        t1 = THETA_MAX_DEG * u[1]
        t2 = t1 if angles == "equal" else THETA_MAX_DEG * u[2]
        if u[3] < WALL_SHARE:
            geometry, ratio, R1, R2 = "sphere-wall", 0.0, R_SMALL, math.inf
        else:
            geometry, ratio = "sphere-sphere", RATIO_MIN + u[4] * (1 - RATIO_MIN)
            R1, R2 = (R_SMALL, R_SMALL / ratio) if u[5] < 0.5 else (R_SMALL / ratio, R_SMALL)
        Rh = harmonic_radius(R1, R2)
        out.append(Bridge(i, geometry, angles, vstar, ratio, R1, R2, Rh, vstar * Rh ** 3, t1, t2))
    return out


def split_of(b):
    """The bridge's split: V* within the fitted range or beyond, equal or unequal angles."""
    return "V*%s0.1 %s" % ("<=" if b.vstar <= VSTAR_FIT else ">", b.angles)


def model_forces(model, b, gaps, gamma=GAMMA):
    """(forces [N] at the gaps [m], the model's rupture distance [m], the variable it refused or "" inside its
    domain): the kernels as a user calls them, with extrapolate=True only where the bridge is refused."""
    t1, t2 = math.radians(b.theta1_deg), math.radians(b.theta2_deg)
    args = (b.R1_m, b.R2_m, b.volume_m3, gamma, t1)
    try:
        F = kernels.force(model, gaps, *args, theta2=t2, rupture=RULE)
        refused = ""
    except ValueError as e:
        refused = str(e).split(" = ")[0].strip()
        F = kernels.force(model, gaps, *args, theta2=t2, rupture=RULE, extrapolate=True)
    rupture = kernels.bridge(model, *args, theta2=t2, rupture=RULE, extrapolate=bool(refused))["rupture"]
    return np.asarray(F, dtype=float), rupture, refused


def evaluate_bridge(b, models=MODELS, rules=RULES, gamma=GAMMA):
    """(force rows, rupture rows) of one bridge: per model and gap fraction, per rupture rule."""
    t1, t2 = math.radians(b.theta1_deg), math.radians(b.theta2_deg)
    exact = kernels.YoungLaplaceBridge(b.R1_m, b.R2_m, b.volume_m3, t1, t2)
    ar = exact.rupture_gap
    gaps = np.array(FRACTIONS) * ar
    F_ex = np.array([exact.solve(float(a), gamma)["force_neck"] for a in gaps])
    base = dict(bridge=b.index, geometry=b.geometry, angles=b.angles, split=split_of(b), vstar=b.vstar,
                ratio_small_large=b.ratio, R1_m=b.R1_m, R2_m=b.R2_m, Rh_m=b.Rh_m, volume_m3=b.volume_m3,
                theta1_deg=b.theta1_deg, theta2_deg=b.theta2_deg, rupture_exact_m=ar)
    force_rows = []
    for model in models:
        F, rupture, refused = model_forces(model, b, gaps, gamma)
        for f, a, fe, fm in zip(FRACTIONS, gaps, F_ex, F):
            force_rows.append(dict(base, model=model, domain="extrapolated" if refused else "inside", refused=refused,
                                   gap_fraction=f, gap_m=float(a), rupture_model_m=rupture, ruptured_early=int(a > rupture),
                                   F_exact_N=float(fe), F_model_N=float(fm),
                                   rel_error=float((fm - fe) / fe) if fe > 0 else float("nan")))
    rupture_rows = []
    for rule in rules:
        a_rule = kernels.rupture_distance(rule, b.R1_m, b.R2_m, b.volume_m3, t1, t2)
        rupture_rows.append(dict(base, rule=rule, rupture_rule_m=a_rule, rel_error=a_rule / ar - 1))
    return force_rows, rupture_rows


def evaluate(bridges, models=MODELS, rules=RULES, log=None):
    """Every bridge against every model and rule: (force rows, rupture rows)."""
    force_rows, rupture_rows = [], []
    for b in bridges:
        fr, rr = evaluate_bridge(b, models, rules)
        force_rows += fr
        rupture_rows += rr
        if log:
            log(b)
    return force_rows, rupture_rows


def in_split(r, split):
    if split == "all":
        return True
    if split in ("inside domain", "extrapolated"):
        return r.get("domain", "inside") == ("inside" if split == "inside domain" else "extrapolated")
    return r["split"] == split


def stats(rows):
    """Median, 95th percentile and largest |relative error|, signed median, n of the rows with an error."""
    e = np.array([r["rel_error"] for r in rows if not math.isnan(r["rel_error"])])
    if len(e) == 0:
        return dict(median_abs_rel_error=float("nan"), p95_abs_rel_error=float("nan"), worst_abs_rel_error=float("nan"),
                    signed_median_rel_error=float("nan"), n=0)
    a = np.abs(e)
    return dict(median_abs_rel_error=float(np.median(a)), p95_abs_rel_error=float(np.percentile(a, 95)),
                worst_abs_rel_error=float(a.max()), signed_median_rel_error=float(np.median(e)), n=len(e))


def summarize(force_rows, rupture_rows, models=MODELS, rules=RULES):
    """Per model (or rule), split and metric: stats() and the counts of points left out or at -100 %.
    force: every gap, a model's 0 beyond its own rupture distance counted (-1); force_attached: only the gaps
    the model's bridge reaches; force_contact: gap 0 only; rupture: the rules' rupture distances."""
    out = []
    for model in models:
        mine = [r for r in force_rows if r["model"] == model]
        for split in ALL_SPLITS:
            rows = [r for r in mine if in_split(r, split)]
            n_bridges = len({r["bridge"] for r in rows})
            for metric in METRICS:
                sel = rows if metric == "force" else (
                    [r for r in rows if not r["ruptured_early"]] if metric == "force_attached" else [r for r in rows if r["gap_fraction"] == 0.0])
                out.append(dict(model=model, split=split, metric=metric, **stats(sel), n_bridges=n_bridges,
                                n_ruptured_early=sum(r["ruptured_early"] for r in sel),
                                n_exact_not_attractive=sum(1 for r in sel if math.isnan(r["rel_error"]))))
    for rule in rules:
        mine = [r for r in rupture_rows if r["rule"] == rule]
        for split in SPLITS + ("all",):
            rows = [r for r in mine if in_split(r, split)]
            out.append(dict(model=rule, split=split, metric="rupture", **stats(rows), n_bridges=len(rows), n_ruptured_early=0,
                            n_exact_not_attractive=0))
    return out


CHECK_COLUMNS = ("bridge", "geometry", "angles", "vstar", "theta1_deg", "theta2_deg", "model", "domain", "gap_fraction",
                 "rupture_exact_m", "rupture_model_m", "F_exact_N", "F_model_N", "rel_error")


def check_bridges(bridges):
    """The first bridge of each (geometry, split) in sample order: the per-point basis committed with the
    summary (check_points.csv) and recomputed by tests/python/test_closed_form_errors.py."""
    seen = {}
    for b in bridges:
        seen.setdefault((b.geometry, split_of(b)), b)
    return sorted(seen.values(), key=lambda b: b.index)


def write_csv(path, rows, digits=10):
    """Rows (dicts with the same keys) to CSV; floats with `digits` significant digits."""
    fmt = "%%.%dg" % digits
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: (fmt % v if isinstance(v, float) else v) for k, v in r.items()})


def _row(summary, model, split, metric):
    return next(r for r in summary if r["model"] == model and r["split"] == split and r["metric"] == metric)


def table(summary, metric="force", models=MODELS, rules=RULES):
    """Markdown table: per model (and rule) median / 95th percentile / worst |relative error| in % per split."""
    def cell(s):
        if s["n"] == 0:
            return "-"
        return " / ".join(_pct(s[k]) for k in ("median_abs_rel_error", "p95_abs_rel_error", "worst_abs_rel_error"))
    lines = ["| %s | %s |" % ("model" if metric != "rupture" else "rule", " | ".join(SPLITS)), "|---" * (len(SPLITS) + 1) + "|"]
    names = rules if metric == "rupture" else models
    for m in names:
        lines.append("| `%s` | %s |" % (m, " | ".join(cell(_row(summary, m, s, metric)) for s in SPLITS)))
    return "\n".join(lines)


def _pct(x):
    p = 100 * x
    return "%.2g" % p if p < 10 else "%.0f" % p


def plot(summary, path, models=MODELS, rules=RULES):
    """One PNG: per model the median (dot), 95th percentile (bar) and largest (cross) |force error| over every gap
    (metric force) in the four splits, and the same for the rupture rules' distances, on a log axis."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(models) + list(rules)
    fig, ax = plt.subplots(figsize=(11, 4.8))
    colors = ("C0", "C1", "C2", "C3")
    width = 0.8 / len(SPLITS)
    for i, name in enumerate(names):
        metric = "rupture" if name in rules else "force"
        for k, split in enumerate(SPLITS):
            s = _row(summary, name, split, metric)
            if s["n"] == 0:
                continue
            x = i - 0.4 + (k + 0.5) * width
            lo, p95, hi = s["median_abs_rel_error"], s["p95_abs_rel_error"], s["worst_abs_rel_error"]
            ax.plot([x, x], [lo, hi], color=colors[k], lw=1)
            ax.plot([x], [lo], "o", color=colors[k], ms=5, label=split if i == 0 else None)
            ax.plot([x], [p95], "_", color=colors[k], ms=12, mew=2.5)
            ax.plot([x], [hi], "x", color=colors[k], ms=5)
    ax.axvline(len(models) - 0.5, color="k", lw=0.8, ls="--")
    ax.axhline(1.0, color="grey", lw=0.8, ls=":")
    ax.set_xticks(range(len(names)))
    ax.set_xticklabels(list(models) + ["rupture: %s" % r for r in rules], rotation=30, ha="right", fontsize=8)
    ax.set_yscale("log")
    ax.set_ylabel("|relative error| [-]")
    ax.set_title("Closed forms against the exact bridge, gaps 0-0.95 of the exact rupture (dot: median, bar: 95th percentile,"
                 " cross: worst)", fontsize=9)
    ax.grid(alpha=0.3, which="both", axis="y")
    ax.set_ylim(top=ax.get_ylim()[1] * 10)
    ax.legend(fontsize=8, loc="upper left", ncol=len(SPLITS), title="V* = V/Rh^3; angles theta1, theta2 on the two solids",
              title_fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(outdir, datadir, n=N_BRIDGES, seed=SEED, log=None):
    """The study: writes outdir/{points.csv, rupture.csv} (every point) and datadir/{summary.csv,
    check_points.csv, closed_form_errors.png}; returns (summary, force rows, rupture rows)."""
    os.makedirs(outdir, exist_ok=True)
    os.makedirs(datadir, exist_ok=True)
    bridges = sample(n, seed)
    force_rows, rupture_rows = evaluate(bridges, log=log)
    summary = summarize(force_rows, rupture_rows)
    write_csv(os.path.join(outdir, "points.csv"), force_rows)
    write_csv(os.path.join(outdir, "rupture.csv"), rupture_rows)
    write_csv(os.path.join(datadir, "summary.csv"), summary, digits=6)
    checked = {b.index for b in check_bridges(bridges)}
    write_csv(os.path.join(datadir, "check_points.csv"), [{k: r[k] for k in CHECK_COLUMNS} for r in force_rows if r["bridge"] in checked])
    plot(summary, os.path.join(datadir, "closed_form_errors.png"))
    return summary, force_rows, rupture_rows
