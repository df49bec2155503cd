"""Unequal contact angles: the cosine of the mean angle against the mean of the cosines.

The kernels combine the two contact angles of a bridge into one. They used the
mean angle, theta = (theta1 + theta2) / 2; this comparison made them use the mean of the cosines,
theta = acos((cos theta1 + cos theta2) / 2), for the force models (``equivalent_angle`` in
pkg/kernels/conventions.hpp), keeping the mean angle for the lian and willett rupture rules. Elskamp & Kruggel-Emden 2018 eq. (14), (15) use the mean of the
cosines, (cos theta_i + cos theta_j) / 2, in the Derjaguin term (and the mean angle only in the
sine term). Both forms are measured here against the exact Young-Laplace solver, which takes the
two angles separately (``kernels.YoungLaplaceBridge(R1, R2, V, theta1, theta2)``).

The forms are emulated with the existing kernels by equal angles theta = theta2 = theta_eff:

* ``mean_cos``:   theta_eff = acos((cos theta1 + cos theta2) / 2)  (Elskamp 2018 eq. 14, 15)
* ``mean_angle``: theta_eff = (theta1 + theta2) / 2                (the kernels before)
* ``native``:     the kernels called with theta, theta2 as given (F(0) equals ``mean_cos``; the
  rupture distance is that of the mean angle; the tabulated model is the exact bridge)

Besides every kernel model (except linear_irreversible, a calibrated law), the pseudo-model
``young_laplace_equal`` is the exact solver itself with the equal angle theta_eff: it isolates the
error of the angle combination from the error of a model's fit.

Cases (``PAIRS``): the material pairs of Elskamp 2018, Table 1 (contact angles with water: glass
15 deg, POM 40 deg, steel 45 deg, PVC 50 deg; also stated in their conclusions), each as a
sphere-wall bridge (angle 1 on the sphere, angle 2 on the wall; R2 = inf, the particles against
the walls of their screen) and as a sphere-sphere bridge of equal radii with the two angles on the
two spheres. Sphere radius 2.5 mm (d = 5 mm of Table 1), water gamma = 72.75 mN/m (their section
4); relative errors do not depend on either. V* = V / R^3 with R the harmonic mean radius of the
Derjaguin-equivalent pair (a wall: R = 2 R1). Gaps: ``N_GAPS`` points from 0 to 0.95 of the exact
rupture gap; a model whose own rupture distance (rule ``willett``) is shorter returns 0 there
(relative error -1), as in a simulation.

Exact small-volume limit (Derjaguin): F(0) -> pi R gamma (cos theta1 + cos theta2), i.e.
2 pi R1 gamma (cos theta1 + cos theta2) for a sphere on a plane, whatever the two angles.

CSV columns carry their unit as a suffix (_m, _m3, _N, _N_m, _deg); columns without one
(vstar, gap_fraction, *rel_error*) are dimensionless, relative errors as fractions (0.01 = 1 %).
"""
import csv
import math
import os
from collections import namedtuple

import numpy as np

from yade_capillary import kernels

SOURCE = "Elskamp & Kruggel-Emden 2018, Table 1 (contact angle with water) and Conclusions"
Pair = namedtuple("Pair", "name body1 theta1_deg body2 theta2_deg")
PAIRS = (Pair("glass-steel", "glass", 15.0, "steel", 45.0),
         Pair("POM-PVC", "POM", 40.0, "PVC", 50.0))
GEOMETRIES = ("sphere-wall", "sphere-sphere")
VSTARS = (1e-4, 1e-3, 1e-2, 0.05)
DERJAGUIN_VSTARS = (1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 0.05)
FORMS = ("mean_cos", "mean_angle", "native")
EXACT_EQUAL = "young_laplace_equal"  # the solver with the equal angle theta_eff
MODELS = tuple(m for m in kernels.MODEL_NAMES if m != "linear_irreversible") + (EXACT_EQUAL,)
R1 = 2.5e-3      # [m] sphere radius, d = 5 mm (Elskamp 2018 Table 1)
GAMMA = 72.75e-3  # [N/m] water (Elskamp 2018 section 4)
N_GAPS = 20
MAX_FRACTION = 0.95


def effective_angle(form, theta1, theta2):
    """The equal contact angle [rad] that stands for (theta1, theta2) [rad] in a form; None for
    ``native`` (the kernels get both angles)."""
    if form == "mean_cos":
        return math.acos((math.cos(theta1) + math.cos(theta2)) / 2)
    if form == "mean_angle":
        return (theta1 + theta2) / 2
    if form == "native":
        return None
    raise ValueError("form = %r is unknown; allowed: %s" % (form, ", ".join(FORMS)))


def geometry(geom, R1=R1):
    """(R1, R2, R) [m] of a geometry: R2 = inf for a wall, R the harmonic mean radius of the
    Derjaguin-equivalent pair (V* = V / R^3)."""
    if geom == "sphere-wall":
        return R1, float("inf"), 2 * R1
    if geom == "sphere-sphere":
        return R1, R1, R1
    raise ValueError("geometry = %r is unknown; allowed: %s" % (geom, ", ".join(GEOMETRIES)))


def derjaguin_force(R, gamma, theta1, theta2):
    """Small-volume limit of the exact F(0) [N]: pi R gamma (cos theta1 + cos theta2), R [m] the
    harmonic mean radius (sphere-plane: R = 2 R1, so 2 pi R1 gamma (cos theta1 + cos theta2))."""
    return math.pi * R * gamma * (math.cos(theta1) + math.cos(theta2))


def exact_curve(R1, R2, volume, theta1, theta2, gaps, gamma=GAMMA):
    """Exact force [N] at the gaps [m] (neck method), 0 beyond the bridge's rupture gap."""
    b = kernels.YoungLaplaceBridge(R1, R2, volume, theta1, theta2)
    return np.array([b.solve(float(a), gamma)["force_neck"] if a <= b.rupture_gap else 0.0 for a in gaps])


def model_curve(model, form, R1, R2, volume, theta1, theta2, gaps, gamma=GAMMA):
    """(forces [N] at the gaps [m], rupture distance [m]) of a model (or ``EXACT_EQUAL``) in a
    form. Raises ValueError if the model refuses the bridge."""
    t = effective_angle(form, theta1, theta2)
    if model == EXACT_EQUAL:
        if t is None:
            raise ValueError("%s: the native form is the exact solver itself" % EXACT_EQUAL)
        b = kernels.YoungLaplaceBridge(R1, R2, volume, t, t)
        return np.array([b.solve(float(a), gamma)["force_neck"] if a <= b.rupture_gap else 0.0 for a in gaps]), b.rupture_gap
    ta, tb = (theta1, theta2) if t is None else (t, t)
    F = np.asarray(kernels.force(model, gaps, R1, R2, volume, gamma, ta, tb))
    return F, kernels.bridge(model, R1, R2, volume, gamma, ta, tb)["rupture"]


def evaluate(pairs=PAIRS, geometries=GEOMETRIES, vstars=VSTARS, models=MODELS, forms=FORMS, n_gaps=N_GAPS, R1=R1, gamma=GAMMA):
    """Every (pair, geometry, V*, model, form) against the exact solver.

    Returns (curves, summary): curves, one dict per gap (forces [N] and signed relative error);
    summary, one dict per combination: F(0) relative error, RMS and max |relative error| over the
    gaps, the model's rupture distance relative to the exact one, and the RMS error over the gaps
    where the model's bridge still exists (``rms_rel_error_attached``: the force law without its
    rupture distance); or ``status`` = "refused: ..." (numbers NaN) where the model refuses the input.
    """
    curves, summary = [], []
    for p in pairs:
        t1, t2 = math.radians(p.theta1_deg), math.radians(p.theta2_deg)
        for geom in geometries:
            r1, r2, R = geometry(geom, R1)
            for vs in vstars:
                V = vs * R ** 3
                exact = kernels.YoungLaplaceBridge(r1, r2, V, t1, t2)
                gaps = np.linspace(0.0, MAX_FRACTION, n_gaps) * exact.rupture_gap
                F_ex = np.array([exact.solve(float(a), gamma)["force_neck"] for a in gaps])
                F_derj = derjaguin_force(R, gamma, t1, t2)
                base = dict(pair=p.name, geometry=geom, theta1_deg=p.theta1_deg, theta2_deg=p.theta2_deg, vstar=vs, R1_m=r1,
                            R_m=R, volume_m3=V, gamma_N_m=gamma)
                for model in models:
                    for form in forms:
                        if model == EXACT_EQUAL and form == "native":
                            continue
                        t = effective_angle(form, t1, t2)
                        row = dict(base, model=model, form=form, theta_eff_deg=math.degrees(t) if t is not None else float("nan"),
                                   rupture_exact_m=exact.rupture_gap, F0_exact_N=F_ex[0], F0_derjaguin_N=F_derj)
                        try:
                            F, rupture = model_curve(model, form, r1, r2, V, t1, t2, gaps, gamma)
                        except (ValueError, RuntimeError) as e:
                            nan = float("nan")
                            summary.append(dict(row, rupture_model_m=nan, rupture_rel_error=nan, F0_model_N=nan, F0_rel_error=nan,
                                                rms_rel_error=nan, max_rel_error=nan, rms_rel_error_attached=nan,
                                                status="refused: " + str(e).splitlines()[0][:160]))
                            continue
                        err = (F - F_ex) / F_ex
                        attached = err[gaps <= rupture]
                        summary.append(dict(row, rupture_model_m=rupture, rupture_rel_error=rupture / exact.rupture_gap - 1,
                                            F0_model_N=F[0], F0_rel_error=err[0], rms_rel_error=float(np.sqrt(np.mean(err ** 2))),
                                            max_rel_error=float(np.max(np.abs(err))),
                                            rms_rel_error_attached=float(np.sqrt(np.mean(attached ** 2))), status="ok"))
                        for a, fe, fm, e in zip(gaps, F_ex, F, err):
                            curves.append(dict(pair=p.name, geometry=geom, vstar=vs, model=model, form=form, gap_m=a,
                                               gap_fraction=a / exact.rupture_gap, F_exact_N=fe, F_model_N=fm, rel_error=e))
    return curves, summary


def derjaguin_limit(pairs=PAIRS, vstars=DERJAGUIN_VSTARS, geometries=("sphere-wall",), R1=R1, gamma=GAMMA):
    """Exact F(0) [N] of the mixed-angle bridge against the Derjaguin value
    pi R gamma (cos theta1 + cos theta2) as V* -> 0 (sphere-plane: 2 pi R1 gamma (cos theta1 +
    cos theta2)); ``deficit`` = 1 - F(0) / F_Derjaguin. The equal-angle forms' Derjaguin values,
    relative to it, are the forms' errors in the limit: 0 for mean_cos, cos(mean angle) / mean of
    cosines - 1 for mean_angle."""
    rows = []
    for p in pairs:
        t1, t2 = math.radians(p.theta1_deg), math.radians(p.theta2_deg)
        limit_angle = math.cos((t1 + t2) / 2) / ((math.cos(t1) + math.cos(t2)) / 2) - 1
        for geom in geometries:
            r1, r2, R = geometry(geom, R1)
            for vs in vstars:
                F0 = exact_curve(r1, r2, vs * R ** 3, t1, t2, [0.0], gamma)[0]
                Fd = derjaguin_force(R, gamma, t1, t2)
                rows.append(dict(pair=p.name, geometry=geom, theta1_deg=p.theta1_deg, theta2_deg=p.theta2_deg, vstar=vs, F0_exact_N=F0,
                                 F0_derjaguin_N=Fd, F0_over_derjaguin=F0 / Fd, deficit=1 - F0 / Fd,
                                 limit_rel_error_mean_cos=0.0, limit_rel_error_mean_angle=limit_angle))
    return rows


def deficit_exponent(rows):
    """Per (pair, geometry): the log-log slope of the deficit 1 - F(0)/F_Derjaguin against V*
    between the two smallest V* (the filling angle grows like V*^(1/4), and the deficit with it)."""
    out = {}
    for key in dict.fromkeys((r["pair"], r["geometry"]) for r in rows):
        rs = sorted((r for r in rows if (r["pair"], r["geometry"]) == key), key=lambda r: r["vstar"])[:2]
        out[key] = math.log(rs[1]["deficit"] / rs[0]["deficit"]) / math.log(rs[1]["vstar"] / rs[0]["vstar"])
    return out


def write_csv(path, rows):
    """Rows (dicts with the same keys) to CSV; floats with 10 significant digits."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.10g" % v if isinstance(v, float) else v) for k, v in r.items()})


def _row(summary, **key):
    return next(r for r in summary if all(r[k] == v for k, v in key.items()))


def comparison(summary, models=MODELS):
    """Per (pair, geometry, V*, model): both forms' F(0), RMS (all gaps and attached gaps) and
    rupture errors side by side, and which form is closer (by the RMS error over all gaps);
    refused combinations left out."""
    out = []
    keys = dict.fromkeys((r["pair"], r["geometry"], r["vstar"]) for r in summary)
    for pair, geom, vs in keys:
        for model in models:
            c = _row(summary, pair=pair, geometry=geom, vstar=vs, model=model, form="mean_cos")
            m = _row(summary, pair=pair, geometry=geom, vstar=vs, model=model, form="mean_angle")
            if c["status"] != "ok" or m["status"] != "ok":
                continue
            row = dict(pair=pair, geometry=geom, vstar=vs, model=model)
            for q in ("F0_rel_error", "rms_rel_error", "rms_rel_error_attached", "max_rel_error", "rupture_rel_error"):
                row[q + "_mean_cos"], row[q + "_mean_angle"] = c[q], m[q]
            row["closer"] = "mean_cos" if c["rms_rel_error"] < m["rms_rel_error"] else "mean_angle"
            out.append(row)
    return out


def table(summary, models=("willett_full", "rabinovich_lambert", "willett_reduced", "young_laplace_table", EXACT_EQUAL)):
    """Text table [%]: F(0) error, RMS error over all gaps and over the attached gaps, of both
    forms (cos: mean of cosines, ang: cosine of the mean angle), per case and model."""
    lines = ["%-11s %-13s %-6s %-19s | %7s %7s | %6s %6s | %6s %6s | closer (rms)" % (
        "pair", "geometry", "V*", "model", "F0 cos", "F0 ang", "rms c", "rms a", "att c", "att a")]
    for r in comparison(summary, models):
        lines.append("%-11s %-13s %-6g %-19s | %+6.2f%% %+6.2f%% | %5.2f%% %5.2f%% | %5.2f%% %5.2f%% | %s" % (
            r["pair"], r["geometry"], r["vstar"], r["model"], 100 * r["F0_rel_error_mean_cos"], 100 * r["F0_rel_error_mean_angle"],
            100 * r["rms_rel_error_mean_cos"], 100 * r["rms_rel_error_mean_angle"], 100 * r["rms_rel_error_attached_mean_cos"],
            100 * r["rms_rel_error_attached_mean_angle"], r["closer"]))
    return "\n".join(lines)


def tally(summary):
    """Per model: the number of cases, in how many the mean of cosines has the smaller |F(0)|
    error and the smaller RMS error, and the median of each form's |F(0)| and RMS errors [fraction]."""
    comp = comparison(summary)
    out = {}
    for model in dict.fromkeys(r["model"] for r in comp):
        rs = [r for r in comp if r["model"] == model]
        med = lambda q: float(np.median([abs(r[q]) for r in rs]))  # noqa: E731
        f0_closer = sum(abs(r["F0_rel_error_mean_cos"]) < abs(r["F0_rel_error_mean_angle"]) for r in rs)
        out[model] = dict(n=len(rs), F0_mean_cos_closer=f0_closer,
                          rms_mean_cos_closer=sum(r["closer"] == "mean_cos" for r in rs),
                          median_F0_mean_cos=med("F0_rel_error_mean_cos"), median_F0_mean_angle=med("F0_rel_error_mean_angle"),
                          median_rms_mean_cos=med("rms_rel_error_mean_cos"), median_rms_mean_angle=med("rms_rel_error_mean_angle"))
    return out


def plot(curves, path, vstar=1e-3, models=("rabinovich_lambert", "willett_full", EXACT_EQUAL)):
    """PNG at one V*: per pair, the exact force and both forms of the given models against
    gap / exact rupture gap (upper row), and each form's force relative to the exact one (lower
    row); one column per geometry. Dashed: mean of cosines; dotted: cosine of the mean angle."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pairs = list(dict.fromkeys(r["pair"] for r in curves))
    geoms = list(dict.fromkeys(r["geometry"] for r in curves))
    fig, axes = plt.subplots(2 * len(pairs), len(geoms), figsize=(5.4 * len(geoms), 3.3 * 2 * len(pairs)), squeeze=False)
    colors = ["C0", "C3", "C2", "C4"]
    for i, pair in enumerate(pairs):
        p = next((q for q in PAIRS if q.name == pair), None)
        angles = " (%g/%g deg)" % (p.theta1_deg, p.theta2_deg) if p else ""
        for j, geom in enumerate(geoms):
            ax, axr = axes[2 * i][j], axes[2 * i + 1][j]
            sel = [r for r in curves if r["pair"] == pair and r["geometry"] == geom and r["vstar"] == vstar]
            ex = [r for r in sel if r["model"] == models[0] and r["form"] == "mean_cos"]
            if not ex:
                ax.set_visible(False)
                axr.set_visible(False)
                continue
            ax.plot([r["gap_fraction"] for r in ex], [1e3 * r["F_exact_N"] for r in ex], "k-", lw=2.2,
                    label="exact, angles %s" % angles.strip())
            axr.axhline(1.0, color="k", lw=1.5)
            for k, model in enumerate(models):
                for form, ls in (("mean_cos", "--"), ("mean_angle", ":")):
                    rs = [r for r in sel if r["model"] == model and r["form"] == form]
                    if not rs:
                        continue
                    style = dict(color=colors[k % len(colors)], ls=ls, lw=1.4,
                                 label="%s, %s" % (model, "mean of cosines" if form == "mean_cos" else "cos of mean angle"))
                    ax.plot([r["gap_fraction"] for r in rs], [1e3 * r["F_model_N"] for r in rs], **style)
                    axr.plot([r["gap_fraction"] for r in rs], [1 + r["rel_error"] for r in rs], **style)
            ax.set_title("%s%s, %s, V* = %g" % (pair, angles, geom, vstar), fontsize=9)
            ax.set_ylabel("capillary force [mN]")
            ax.set_ylim(bottom=0)
            axr.set_ylabel("F / F_exact [-]")
            axr.set_xlabel("gap / exact rupture gap [-]")
            axr.set_ylim(0.6, 1.3)
            for a in (ax, axr):
                a.set_xlim(0, 1)
                a.grid(alpha=0.3)
            ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(outdir, vstars=VSTARS, n_gaps=N_GAPS, plot_vstar=1e-3, derjaguin_vstars=DERJAGUIN_VSTARS):
    """Full study: writes summary.csv, curves.csv, comparison.csv, derjaguin.csv and
    mixed_angles.png in outdir; returns (summary, derjaguin rows, text table)."""
    os.makedirs(outdir, exist_ok=True)
    curves, summary = evaluate(vstars=vstars, n_gaps=n_gaps)
    derj = derjaguin_limit(vstars=derjaguin_vstars)
    write_csv(os.path.join(outdir, "summary.csv"), summary)
    write_csv(os.path.join(outdir, "curves.csv"), curves)
    write_csv(os.path.join(outdir, "comparison.csv"), comparison(summary))
    write_csv(os.path.join(outdir, "derjaguin.csv"), derj)
    plot(curves, os.path.join(outdir, "mixed_angles.png"), vstar=plot_vstar)
    return summary, derj, table(summary)
