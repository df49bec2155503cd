"""The shear-cell fit under other conventions than the pipeline's (cellanalysis), over parts of a run, and
against the dry material (the cause analysis of docs/studies/gladkyy-cause-analysis.md): fit_variants,
block_fits, band_profile and excess_shear. Plain numpy."""
import glob
import json
import os

import numpy as np

from yade_capillary import cellanalysis, fits

# Gladkyy 2014 §4.1: "tau = mu p + c ... with mu = 0.13 for the particular granular material", one slope
# for the dry and the wet materials (his Fig. 7), c per liquid content.
GLADKYY_MU = 0.13


def variants_of(fit):
    """fit_variants of a cellanalysis.fit_fields dict."""
    return fit_variants(fit["sigma"], fit["gdot"], fit["away"], fit["gmin"])


def fit_variants(sigma, gdot, away, gamma_dot_min):
    """mu and c of tau = mu p + c under each convention of the fit, applied to the same CG fields (which
    of the differences from Gladkyy the conventions explain): returns {name: fit dict}.

    baseline: tau = sqrt(sigma_rtheta^2 + sigma_ztheta^2), p = tr(sigma)/3, band gamma_dot > 80 % of
    its maximum per height (the analysis' own choice); tau_rtheta: tau = |sigma_rtheta|; p_zz: p =
    sigma_zz; threshold: gamma_dot > gamma_dot_min (Gladkyy's 0.12 1/s, scaled with the period);
    threshold_half_rate: the same threshold on gamma_dot / 2 (a strain-rate norm half of ours, the
    other common convention); low_p / high_p: the baseline band split at its median pressure;
    quadratic: tau = c + mu p + k p^2 over the baseline band (mu: the slope at p = 0, k_1_Pa the
    curvature), to test whether tau(p) is curved at low p; baseline_gladkyy_slope and
    threshold_gladkyy_slope: c with the slope fixed at Gladkyy's mu = 0.13 (his §4.1 gives one mu for the
    dry and every wet material and c per liquid content), the mean of tau - 0.13 p over that band;
    every linear fit also gives p_mean_Pa, the band's mean pressure."""
    s = 0.5 * (sigma + np.swapaxes(sigma, 0, 1))
    p_tr, p_zz = (s[0, 0] + s[1, 1] + s[2, 2]) / 3, s[2, 2]
    tau_full, tau_rt = np.hypot(s[0, 1], s[2, 1]), np.abs(s[0, 1])
    peak = np.nanmax(np.where(away, gdot, 0), axis=0)[None, :]
    band = away & (gdot > 0.8 * peak)
    sel = {"baseline": band, "threshold": away & (gdot > gamma_dot_min), "threshold_half_rate": away & (gdot / 2 > gamma_dot_min)}

    def fit(pp, tt, m):
        m = m & np.isfinite(pp) & np.isfinite(tt)
        if m.sum() < 4:
            return {"error": "fewer than 4 band points", "points": int(m.sum())}
        try:
            return dict(fits.fit_yield(pp[m], tt[m]), points=int(m.sum()), p_min_Pa=float(pp[m].min()), p_max_Pa=float(pp[m].max()),
                        p_mean_Pa=float(pp[m].mean()))
        except (ValueError, np.linalg.LinAlgError) as e:
            return {"error": str(e), "points": int(m.sum())}

    out = {name: fit(p_tr, tau_full, m) for name, m in sel.items()}
    for name in ("baseline", "threshold"):
        m = sel[name] & np.isfinite(p_tr) & np.isfinite(tau_full)
        if m.sum() >= 4:
            e = tau_full[m] - GLADKYY_MU * p_tr[m]
            out[name + "_gladkyy_slope"] = {"mu": GLADKYY_MU, "c_Pa": float(e.mean()), "c_err_Pa": float(e.std(ddof=1) / np.sqrt(m.sum())),
                                            "points": int(m.sum()), "p_mean_Pa": float(p_tr[m].mean())}
    out["tau_rtheta"] = fit(p_tr, tau_rt, band)
    out["p_zz"] = fit(p_zz, tau_full, band)
    if band.sum() >= 8:
        med = np.median(p_tr[band])
        out["low_p"], out["high_p"] = fit(p_tr, tau_full, band & (p_tr <= med)), fit(p_tr, tau_full, band & (p_tr > med))
        pp, tt = p_tr[band], tau_full[band]
        A = np.stack([np.ones_like(pp), pp, pp * pp], axis=1)
        coef, *_ = np.linalg.lstsq(A, tt, rcond=None)
        resid = tt - A @ coef
        cov = (resid @ resid / max(len(pp) - 3, 1)) * np.linalg.pinv(A.T @ A)
        err = np.sqrt(np.abs(np.diag(cov)))
        out["quadratic"] = {"c_Pa": float(coef[0]), "c_err_Pa": float(err[0]), "mu": float(coef[1]), "mu_err": float(err[1]),
                            "k_1_Pa": float(coef[2]), "k_err_1_Pa": float(err[2]), "points": int(len(pp))}
    return out


def block_fits(rundir, blocks=3, keep=None):
    """The scatter of a run's fit over time: its snapshots split into `blocks` consecutive blocks, each
    fitted on its own (cellanalysis.fit_fields of the block's reduced snapshots; each snapshot of rundir is
    reduced once to keep/cg_NNN.npz, keep defaulting to rundir). The fit's own standard errors treat
    the band's grid nodes as independent, which neighbouring nodes (R/2 apart, kernel width R) and
    one snapshot set are not; the spread of the blocks is the error of a time average over the
    blocks' length. Returns {blocks: [fit summary per block], and for mu, c_Pa, Rc_mean_m and W_mean_m:
    the mean of the blocks and its standard error (block std / sqrt(blocks))}."""
    keep = rundir if keep is None else keep
    os.makedirs(keep, exist_ok=True)
    with open(os.path.join(rundir, "run.json")) as f:
        run = json.load(f)
    for k, snap in enumerate(sorted(glob.glob(os.path.join(rundir, "snap_*.npz")))):
        out = os.path.join(keep, "cg_%03d.npz" % (k + 1))
        if not os.path.exists(out):
            cellanalysis.reduce_snapshot(snap, run["cfg"], out)
    red = cellanalysis.load_reduced(keep)
    if not 2 <= blocks <= len(red):
        raise ValueError("blocks: %r is outside [2, %d] (the run's %d snapshots)" % (blocks, len(red), len(red)))
    grid = cellanalysis.analysis_grid(run["cfg"])
    out = {"blocks": []}
    for part in np.array_split(np.arange(len(red)), blocks):
        fit = cellanalysis.fit_fields(grid, cellanalysis.average_fields([red[i] for i in part]), run)
        f = cellanalysis.fit_summary(run, fit, len(part))
        out["blocks"].append({"snapshots": [int(i) + 1 for i in part], "mu": f["mu"], "c_Pa": f["c_Pa"],
                              "Rc_mean_m": float(np.mean(f["Rc_m"])), "W_mean_m": float(np.mean(f["W_m"])),
                              "fit_variants": variants_of(fit)})
    for k in ("mu", "c_Pa", "Rc_mean_m", "W_mean_m"):
        v = np.array([b[k] for b in out["blocks"]])
        out[k], out[k + "_err"] = float(v.mean()), float(v.std(ddof=1) / np.sqrt(len(v)))
    return out


def band_profile(profiles_csv):
    """The shear band of a run by height, from its profiles.csv (written by analyse): {z_m, p_Pa, tau_Pa,
    points}, the means over the band's nodes at each height that has at least 2 of them, and those nodes
    themselves (nodes: the rows of profiles.csv)."""
    d = np.genfromtxt(profiles_csv, delimiter=",", names=True)
    b = d[d["in_band"] > 0]
    zs = [z for z in np.unique(b["z_m"]) if (b["z_m"] == z).sum() >= 2]
    rows = [b[b["z_m"] == z] for z in zs]
    return {"z_m": np.array(zs), "p_Pa": np.array([r["p_Pa"].mean() for r in rows]), "tau_Pa": np.array([r["tau_Pa"].mean() for r in rows]),
            "points": np.array([len(r) for r in rows]), "nodes": b[np.isin(b["z_m"], zs)]}


def excess_shear(wet_csv, dry, mu_fixed=GLADKYY_MU):
    """The cohesion of a wet run measured against the dry material of the same cell, without extrapolating
    to p = 0: at each height of the wet band, its shear stress minus the dry band's at the same pressure
    (tau_dry(p) interpolated linearly between the dry band's heights; only wet heights within the dry
    band's pressure range). dry: the dry run's profiles.csv, or its fitted line as (mu, c_Pa, p_min_Pa,
    p_max_Pa) when only the fit is kept (fits.json: mu, c_Pa and the baseline's p range). Gladkyy 2014 §4.1 fits every liquid content with the dry slope (mu = 0.13
    for dry and wet), so his c is this excess if his dry line has no intercept; `mu_fixed` gives the
    intercept of the wet points with that slope as well. Returns {rows: [(z_m, p_Pa, tau_Pa,
    tau_dry_Pa, excess_Pa)], excess_Pa (mean, weighted by band nodes), excess_low_Pa / excess_high_Pa
    (the heights below / above the median pressure), c_fixed_mu_Pa, c_fixed_mu_err_Pa (mean of tau - mu_fixed
    p over the wet band's nodes and its standard error, as fit_variants' gladkyy_slope)}."""
    w = band_profile(wet_csv)
    if isinstance(dry, str):
        d = band_profile(dry)
        order = np.argsort(d["p_Pa"])
        dp, dt = d["p_Pa"][order], d["tau_Pa"][order]
    else:
        mu, c, p_min, p_max = dry
        dp, dt = np.array([p_min, p_max]), c + mu * np.array([p_min, p_max])
    inside = (w["p_Pa"] >= dp[0]) & (w["p_Pa"] <= dp[-1])
    if inside.sum() < 2:
        raise ValueError("excess_shear: %d heights of %s lie within the dry band's pressures %.3g-%.3g Pa (at least 2 needed)"
                         % (inside.sum(), wet_csv, dp[0], dp[-1]))
    p, tau, n = w["p_Pa"][inside], w["tau_Pa"][inside], w["points"][inside]
    tau_dry = np.interp(p, dp, dt)
    excess = tau - tau_dry
    low = p <= np.median(p)
    fixed = w["nodes"]["tau_Pa"] - mu_fixed * w["nodes"]["p_Pa"]
    return {"rows": list(zip(w["z_m"][inside], p, tau, tau_dry, excess)), "excess_Pa": float(np.average(excess, weights=n)),
            "excess_low_Pa": float(np.average(excess[low], weights=n[low])), "excess_high_Pa": float(np.average(excess[~low], weights=n[~low])),
            "c_fixed_mu_Pa": float(fixed.mean()), "c_fixed_mu_err_Pa": float(fixed.std(ddof=1) / np.sqrt(len(fixed))), "mu_fixed": mu_fixed}
