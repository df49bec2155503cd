"""PNG figures (matplotlib, Agg backend) for the scenarios."""
import csv
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (backend first)


def read_forces(path):
    """Read forces.csv into {(case, model): (gaps [m], forces [N])}."""
    curves = defaultdict(lambda: ([], []))
    with open(path) as f:
        for row in csv.DictReader(f):
            g, F = curves[(row["case"], row["model"])]
            g.append(float(row["gap_m"]))
            F.append(float(row["force_N"]))
    return curves


def _force_axes(ax, curves, case, models, title, scale, unit, gap_scale, gap_unit):
    """Draw F(a) of one case for several models on ax; young_laplace as the exact (dashed black) curve."""
    for m in models:
        g, F = curves[(case, m)]
        style = dict(color="k", ls="--", lw=2, label="young_laplace (exact)") if m == "young_laplace" else dict(lw=1.2, label=m)
        ax.plot([x * gap_scale for x in g], [y * scale for y in F], **style)
    ax.set_xlabel("separation a [%s]" % gap_unit)
    ax.set_ylabel("capillary force F [%s]" % unit)
    ax.set_title(title, fontsize=10)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)


def force_curves(curves, case, models, path, title, scale=1e3, unit="mN", gap_scale=1e6, gap_unit="um"):
    """F(a) of one case for several models, as in Gladkyy 2014 Figures 2 and 3."""
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    _force_axes(ax, curves, case, models, title, scale, unit, gap_scale, gap_unit)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def force_panels(curves, cases, models, path, titles, scale=1e9, unit="nN", gap_scale=1e9, gap_unit="nm"):
    """F(a) of several cases side by side, one panel per case (e.g. Elskamp 2018 Fig. 5a)."""
    fig, axes = plt.subplots(1, len(cases), figsize=(6.0 * len(cases), 4.6))
    for ax, case, title in zip(list(axes) if len(cases) > 1 else [axes], cases, titles):
        _force_axes(ax, curves, case, models, title, scale, unit, gap_scale, gap_unit)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def summary_bars(summary, derjaguin, path):
    """Forces at a = 0, 0.5 a_crit, 0.95 a_crit per case and model, scaled by 2 pi R gamma cos(theta).

    Gladkyy 2014 Figure 4 scales by measured forces; without the experimental data the
    Derjaguin force of each case is the common scale here.
    """
    keys = ("F_0_N", "F_0.5_N", "F_0.95_N")
    titles = ("a = 0", "a = 0.5 a_crit", "a = 0.95 a_crit")
    cases = list(dict.fromkeys(r["case"] for r in summary))
    models = list(dict.fromkeys(r["model"] for r in summary))
    fig, axes = plt.subplots(3, 1, figsize=(9, 9), sharex=True)
    width = 0.8 / len(models)
    for ax, key, title in zip(axes, keys, titles):
        for j, m in enumerate(models):
            vals = [next(r[key] for r in summary if r["case"] == c and r["model"] == m) / derjaguin[c] for c in cases]
            ax.bar([i + (j - len(models) / 2) * width for i in range(len(cases))], vals, width, label=m)
        ax.set_ylabel("F / (2 pi R gamma cos theta)")
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3, axis="y")
    axes[-1].set_xticks(range(len(cases)))
    axes[-1].set_xticklabels(cases)
    axes[0].legend(fontsize=7, ncol=4)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def viscous_pull_off(runs, r_eff, gamma, path, title):
    """F_tot / (gamma r_eff) against S / r_eff for the runs of twosphere.viscous_pull_offs: one curve
    per speed (F_cap + F_visc), the capillary-only run (eta = 0) dashed, a marker at the last gap
    before each rupture; log force axis (the viscous force near contact is 10^2 times the
    capillary one at 10 mm/s). r_eff [m], gamma [N/m], as Elskamp 2018 Fig. 5b.
    """
    fig, ax = plt.subplots(figsize=(6.8, 4.8))
    scale = gamma * r_eff
    for k, r in enumerate(runs):
        alive = [i for i, b in enumerate(r["bridge"]) if b]
        S = [r["gap_m"][i] / r_eff for i in alive]
        F = [(r["F_cap_N"][i] + r["F_visc_N"][i]) / scale for i in alive]
        if r["eta_Pa_s"] > 0:
            line, = ax.plot(S, F, lw=2.0, zorder=2.5 - 0.1 * k, label="v = %g mm/s" % (r["speed_m_s"] * 1e3))  # slower on top
        else:  # on top, thin: the slowest speed runs along it
            line, = ax.plot(S, F, "k--", lw=1.0, zorder=3, label="capillary only (eta = 0)")
        ax.plot(S[-1], F[-1], "o", color=line.get_color(), ms=6, mfc="none", mew=1.5, zorder=4)
    ax.plot([], [], "o", color="grey", mfc="none", label="rupture (last step with a bridge)")
    ax.set_yscale("log")
    ax.set_xlim(left=0)
    ax.set_xlabel("S / r_eff [-]   (r_eff = 2 r1 r2/(r1 + r2) = %g mm)" % (r_eff * 1e3))
    ax.set_ylabel("F_tot / (sigma r_eff) [-],  F_tot = F_cap + F_visc")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
