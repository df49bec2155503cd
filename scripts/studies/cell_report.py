"""A Markdown and CSV comparison of the analysed shear-cell runs of one configuration with Gladkyy 2014
(scripts/shear_cell_validation.py report): mu, c, the band and the torques of every case, the surface law
for the band centre, the projected cost of a run, and the study's tables (fit conventions, torque balance,
contact numbers) where fits.json has them."""
import json
import os

import numpy as np

from yade_capillary.shearcell import ALL_CASES, MODEL_CASES


# Gladkyy & Schwarze 2014, section 4.2: tau = mu p + c in the band (gamma_dot > 0.12 1/s), all models.
GLADKYY_2014 = {"dry": dict(mu=0.13, c_Pa=0.0), "wet13.6nl": dict(mu=0.13, c_Pa=1.3), "wet74.2nl": dict(mu=0.13, c_Pa=2.0)}
GLADKYY_2014.update({case: GLADKYY_2014["wet13.6nl"] for case in MODEL_CASES})  # "no obvious influence" of the model


def surface_band_centre(cfg):
    """Band centre at the free surface [m], Rs [1 - (H/Rs)^(5/2)] (Fenistein, van de Meent & van Hecke 2004)."""
    return cfg["Rs"] * (1 - (cfg["H"] / cfg["Rs"]) ** 2.5)


def fmt_value(v, err=None, fmt="%.3f", scale=1.0):
    """A table entry: v (and ± err) times scale in format fmt, "n/a" for a value that could not be had (None)."""
    if v is None:
        return "n/a"
    return (fmt + " ± " + fmt) % (scale * v, scale * err) if err is not None else fmt % (scale * v)


def report(config_dir, particles=200000, duration_s=5.0):
    """Markdown and CSV comparison of every analysed case in config_dir (fits.json, run.json) with
    Gladkyy 2014 and the surface law for Rc; the cost of a run of `particles` for `duration_s` is
    projected from each case's measured speed at the configuration's time step. Writes
    config_dir/report.md and report.csv; returns the Markdown."""
    rows = []
    for case in ALL_CASES:
        d = os.path.join(config_dir, case)
        if not os.path.exists(os.path.join(d, "fits.json")):
            continue
        with open(os.path.join(d, "fits.json")) as f:
            fit = json.load(f)
        with open(os.path.join(d, "run.json")) as f:
            run_info = json.load(f)
        cfg = run_info["cfg"]
        rc = [(b["z_m"], b["Rc_m"], b["W_m"]) for b in fit["band_fits"] if b.get("Rc_m") is not None]  # not the heights whose fit failed
        dt = cfg["dt_over_tc"] * cfg["tc"]
        rows.append({
            "case": case, "mu": fit["mu"], "mu_err": fit["mu_err"], "c_Pa": fit["c_Pa"], "c_err_Pa": fit["c_err_Pa"],
            "mu_threshold": fit["mu_threshold"], "c_threshold_Pa": fit["c_Pa_threshold"], "band_points": fit["band_points"],
            "band_points_threshold": fit["band_points_threshold"],
            "Rc_top_mm": 1e3 * rc[-1][1] if rc else None, "z_top_mm": 1e3 * rc[-1][0] if rc else None,
            "Rc_mean_mm": 1e3 * float(np.mean([r[1] for r in rc])) if rc else None,
            "W_mean_mm": 1e3 * float(np.mean([r[2] for r in rc])) if rc else None,
            "Rc_surface_law_mm": 1e3 * surface_band_centre(cfg),
            "torque_rotating_Nm": fit["torque_Nm"], "torque_static_Nm": fit["torque_static_Nm"], "torque_cg_at_Rs_Nm": fit.get("torque_cg_at_Rs_Nm"),  # not from reduced snapshots
            "mu_gladkyy": GLADKYY_2014[case]["mu"], "c_gladkyy_Pa": GLADKYY_2014[case]["c_Pa"],
            "steps": run_info["steps"], "wall_s": run_info["wall_s"], "particle_steps_per_s": run_info["particle_steps_per_s"],
            "rotation_s": cfg["run_s"], "projected_h": particles * duration_s / dt / run_info["particle_steps_per_s"] / 3600,
        })
    if not rows:
        raise ValueError("config_dir: no analysed case (fits.json) in %s" % config_dir)
    keys = list(rows[0])
    with open(os.path.join(config_dir, "report.csv"), "w") as f:
        f.write(",".join(keys) + "\n")
        for r in rows:
            f.write(",".join("" if r[k] is None else str(r[k]) for k in keys) + "\n")

    md = ["| case | mu (Gladkyy) | c [Pa] (Gladkyy) | mu, c [Pa], gamma_dot threshold | Rc top / mean [mm] (surface law) | W mean [mm] | torque rotating / static / CG at Rs [mN m] | run |",
          "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        md.append("| %s | %s (%.2f) | %s (%.1f) | %s, %s (%d points) | %s / %s (%.1f) | %s | %s / %s / %s | %.1f s of rotation, %d steps, %.0f s, %.2g particle-steps/s; %d particles for %g s: %.0f h |" % (
            r["case"], fmt_value(r["mu"], r["mu_err"]), r["mu_gladkyy"], fmt_value(r["c_Pa"], r["c_err_Pa"], "%.2f"), r["c_gladkyy_Pa"],
            fmt_value(r["mu_threshold"]), fmt_value(r["c_threshold_Pa"], None, "%.2f"), r["band_points_threshold"],
            fmt_value(r["Rc_top_mm"], None, "%.1f"), fmt_value(r["Rc_mean_mm"], None, "%.1f"), r["Rc_surface_law_mm"], fmt_value(r["W_mean_mm"], None, "%.1f"),
            *(fmt_value(r[k], None, "%.2f", 1e3) for k in ("torque_rotating_Nm", "torque_static_Nm", "torque_cg_at_Rs_Nm")),
            r["rotation_s"], r["steps"], r["wall_s"], r["particle_steps_per_s"], particles, duration_s, r["projected_h"]))
    md += _variant_tables(config_dir)
    text = "\n".join(md) + "\n"
    with open(os.path.join(config_dir, "report.md"), "w") as f:
        f.write(text)
    return text


def _variant_tables(config_dir):
    """Markdown lines: mu and c of every case under each convention of the fit (fits.json
    fit_variants), the torque balance of cylinders near the inner wall and up to the split
    (torque_closure) and the contact numbers; empty for analyses without them."""
    fits_by_case = {}
    for case in ALL_CASES:
        path = os.path.join(config_dir, case, "fits.json")
        if os.path.exists(path):
            with open(path) as f:
                fits_by_case[case] = json.load(f)
    out = []
    have = [c for c, f in fits_by_case.items() if f.get("fit_variants")]
    if have:
        names = list(fits_by_case[have[0]]["fit_variants"])
        out += ["", "Conventions of the fit, applied to the same CG fields (mu, c [Pa], band points):", "",
                "| variant | " + " | ".join(have) + " |", "|---|" + "---|" * len(have)]
        for n in names:
            cells = []
            for c in have:
                v = fits_by_case[c]["fit_variants"].get(n, {})
                if "mu" not in v:
                    cells.append(v.get("error", "n/a"))
                else:
                    extra = ", k = %.4f ± %.4f 1/Pa" % (v["k_1_Pa"], v["k_err_1_Pa"]) if "k_1_Pa" in v else ""
                    mu = "%.3f ± %.3f" % (v["mu"], v["mu_err"]) if "mu_err" in v else "%.3f (fixed)" % v["mu"]  # *_gladkyy_slope
                    cells.append("%s, %.2f ± %.2f (%d)%s" % (mu, v["c_Pa"], v["c_err_Pa"], v["points"], extra))
            out.append("| %s | %s |" % (n, " | ".join(cells)))
    have = [c for c, f in fits_by_case.items() if f.get("torque_closure")]
    if have:
        out += ["", "Torque balance inside cylinders r0 (torque on the walls inside by contact point [mN m]; contact-by-contact "
                    "crossing torque, CG flux at w and w/4, as fractions of it):", "",
                "| case | r0 [mm] | walls inside | crossing | CG w | CG w/4 |", "|---|---|---|---|---|---|"]
        for c in have:
            for r in fits_by_case[c]["torque_closure"]:
                out.append("| %s | %.1f | %.3f | %s | %s | %s |" % (c, 1e3 * r["r0_m"], 1e3 * r["walls_inside_Nm"],
                           *("n/a" if r[k] is None else "%.3f" % r[k] for k in ("crossing_over_walls", "cg_w_over_walls", "cg_w4_over_walls"))))
    have = [c for c, f in fits_by_case.items() if f.get("contact_numbers")]
    if have:
        out += ["", "| case | mechanical contacts per sphere | separated bridges per sphere |", "|---|---|---|"]
        for c in have:
            k = fits_by_case[c]["contact_numbers"]
            out.append("| %s | %.3f ± %.3f | %.3f |" % (c, k["mechanical_per_particle"], k["mechanical_std"], k["separated_bridges_per_particle"]))
    return out
