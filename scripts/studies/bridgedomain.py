"""Where the pendular bridge exists: the largest liquid volume for which the exact Young-Laplace
solver (``kernels.YoungLaplaceBridge``) follows the bridge from contact to its rupture.

For every case (size ratio R_small/R_large in ``GEOMETRIES`` or a wall, contact angles theta1,
theta2 in ``ANGLES_DEG`` on the small and the large solid) the volume V* = V/R_small^3 (R_small: the
smaller sphere; for a wall, the sphere) is scanned upwards over ``SCAN`` and the first refusal is
bracketed by bisection in ln V* to ``REL_RESOLUTION``. A volume counts as solved when the constructor
succeeds and ``solve`` returns a bridge at every fraction ``GAP_FRACTIONS`` of the rupture gap whose
volume matches the input and whose neck and contact-line forces agree (``VOLUME_TOL``, ``FORCE_TOL``).

Two spheres are computed in both orders, the small one as solid 1 and as solid 2, which should give
the same limit (the solver scales every length by R1, so the two orders take different numerical
paths; a negative rupture gap in one order only would be a failure of the continuation). A wall can only be solid 2 (R1 must be finite).

At the last solved volume the meniscus is integrated again here, in arc length from the contact
line on solid 1 with the pressure the solver returns (``meniscus``), to report what ends the domain:
the steepest meniscus angle max |phi| (the solver integrates the profile as a graph x -> y and
refuses |phi| >= pi/2, young_laplace.cpp ``arc``), and the clearance between the meniscus and both
solids (a profile that cut into a solid would be no physical bridge; the solver does not check it).
phi at the contact line on a sphere is beta + theta - pi/2, so a vertical meniscus there means
beta + theta = pi; beta -> pi would be a sphere engulfed by the liquid. Where the solver stops at contact,
the margin pi - theta - beta is extrapolated to the limit volume (``extrapolated_margin``), which tells a
meniscus that turns vertical there from a largest volume at contact reached before.

The documented limit of a case (``limits_table``) is the smaller of the two orders of the solids.

CSV columns carry their unit as a suffix (_m, _m3, _Pa, _N, _deg, _rad); vstar and the ratios are
dimensionless.
"""
import csv
import math
import os
import time

import numpy as np
from scipy.integrate import solve_ivp

from yade_capillary import kernels

R_SMALL = 1e-3   # [m] radius of the smaller sphere (of the sphere for a wall); the limits are in V/R_small^3
GAMMA = 0.072    # [N/m] scales forces and pressure only
INF = float("inf")
ANGLES_DEG = tuple(range(0, 71, 10))
GEOMETRIES = (("1", 1.0), ("1/2", 0.5), ("1/4", 0.25), ("wall", 0.0))  # name, R_small/R_large (0: wall)
GAP_FRACTIONS = (0.0, 0.25, 0.5, 0.75, 0.95, 1.0)
# Decades up to 1, then doublings: the domain must hold every scanned volume below the limit.
SCAN = (1e-5, 1e-4, 1e-3, 1e-2, 0.1, 0.5) + tuple(2.0 ** k for k in range(0, 11))
VSTAR_CAP = SCAN[-1]
REL_RESOLUTION = 1e-3  # bisection stops when the bracket is narrower than this in ln V*
# [rad] extrapolated margin below which the meniscus counts as vertical at the limit: where it is, the sqrt model
# gives -0.015..0.002; the largest volumes at contact reached before vertical are 0.029-0.073 away.
VERTICAL = 0.02
FOLD_PROBES = (0.0025, 0.01)  # relative distances below the limit where the margin to vertical is extrapolated from
EXTRA_ABOVE = 2        # scan points above the first refusal tried too: any success there is a hole
# The solver matches the volume to its Newton tolerance (1e-12 in the residual, relative) and the
# neck and contact-line forces agree to ~1e-12 (first integral): 1e-8 leaves room and still flags
# a wrong bridge.
VOLUME_TOL = 1e-8
FORCE_TOL = 1e-8       # relative to 2 pi R_small gamma


def radii(ratio, small_first):
    """(R1, R2) [m]: the small sphere as solid 1 or as solid 2; a wall (ratio 0) is always solid 2."""
    large = INF if ratio == 0 else R_SMALL / ratio
    return (R_SMALL, large) if small_first or ratio == 0 else (large, R_SMALL)


def attempt(R1, R2, vstar, theta1, theta2):
    """One volume: {'ok': True, 'bridge': b, 'solutions': [...]} or {'ok': False, 'stage', 'error'}."""
    volume = vstar * min(R1, R2) ** 3
    try:
        b = kernels.YoungLaplaceBridge(R1, R2, volume, theta1, theta2)
    except (RuntimeError, ValueError) as e:
        return {"ok": False, "stage": "constructor", "error": "%s: %s" % (type(e).__name__, e)}
    sols = []
    f_scale = 2 * math.pi * min(R1, R2) * GAMMA
    for f in GAP_FRACTIONS:
        stage = "solve at %g of the rupture gap" % f
        try:
            s = b.solve(f * b.rupture_gap, GAMMA)
        except (RuntimeError, ValueError) as e:
            return {"ok": False, "stage": stage, "error": "%s: %s" % (type(e).__name__, e)}
        if not abs(s["volume"] / volume - 1) <= VOLUME_TOL:
            return {"ok": False, "stage": stage, "error": "volume off by %.3g (relative)" % (s["volume"] / volume - 1)}
        if not abs(s["force_neck"] - s["force_contact"]) <= FORCE_TOL * f_scale:
            return {"ok": False, "stage": stage, "error": "neck and contact-line forces differ by %.3g N" % (s["force_neck"] - s["force_contact"])}
        sols.append(s)
    return {"ok": True, "bridge": b, "solutions": sols}


def meniscus(sol, R1, R2, theta1, theta2):
    """The meniscus of a solution, integrated again in arc length from solid 1's contact line
    (x' = cos phi, y' = sin phi, phi' = cos phi / y - P, lengths / R1): max and min of phi [rad], where
    max |phi| lies (arc-length fraction, 0: solid 1's contact line, 1: solid 2's), the smallest clearance
    to solid 1 and to solid 2 (/R_small; negative: the profile cuts into the solid), and the mismatch of
    the end point with the solver's contact line on solid 2 (/R_small)."""
    r2 = R2 / R1
    a = sol["gap"] / R1
    P = sol["pressure"] * R1 / GAMMA
    b1, b2 = sol["beta1"], sol["beta2"]
    h1 = 1 - math.cos(b1)
    plane = math.isinf(r2)
    x_end = a / 2 + (0 if plane else r2 * (1 - math.cos(b2)))
    y_end = sol["contact_radius2"] / R1

    def rhs(_, u):
        return [math.cos(u[2]), math.sin(u[2]), math.cos(u[2]) / u[1] - P]

    def arrive(_, u):  # closest approach to solid 2's contact line (x can turn back near a vertical end)
        return (u[0] - x_end) * math.cos(u[2]) + (u[1] - y_end) * math.sin(u[2])
    arrive.terminal, arrive.direction = True, 1

    def pinch(_, u):
        return u[1] - 1e-9
    pinch.terminal = True

    u0 = [-(a / 2 + h1), math.sin(b1), b1 + theta1 - math.pi / 2]
    length = 4 * (x_end - u0[0] + u0[1] + y_end)  # more than the meniscus is long
    r = solve_ivp(rhs, (0, length), u0, method="DOP853", rtol=1e-11, atol=1e-13, events=(arrive, pinch),
                  max_step=length / 4000)
    x, y, phi = r.y
    c1 = -(a / 2 + 1)
    clear1 = np.hypot(x - c1, y) - 1
    clear2 = (a / 2 - x) if plane else np.hypot(x - (a / 2 + r2), y) - r2
    k = int(np.argmax(np.abs(phi)))
    scale = R1 / min(R1, R2)
    return {"phi_max_rad": float(phi.max()), "phi_min_rad": float(phi.min()),
            "steepest_at": float(r.t[k] / r.t[-1]),
            "clearance1": float(clear1.min() * scale), "clearance2": float(clear2.min() * scale),
            "end_mismatch": float(math.hypot(x[-1] - x_end, y[-1] - y_end) * scale)}


def find_limit(R1, R2, theta1, theta2):
    """Scan SCAN upwards, bisect the first refusal in ln V*. Returns (last success, first refusal,
    their V*, the scan points above the refusal that succeed, the rupture gap [m] at each solved scan
    point, number of attempts)."""
    good = bad = None
    v_good = v_bad = None
    n, gaps = 0, {}
    for v in SCAN:
        res = attempt(R1, R2, v, theta1, theta2)
        n += 1
        if not res["ok"]:
            bad, v_bad = res, v
            break
        good, v_good = res, v
        gaps[v] = res["bridge"].rupture_gap
    holes = []
    if bad is None:
        return good, None, v_good, None, holes, gaps, n
    for v in [s for s in SCAN if s > v_bad][:EXTRA_ABOVE]:
        n += 1
        if attempt(R1, R2, v, theta1, theta2)["ok"]:
            holes.append(v)
    if good is None:
        return None, bad, None, v_bad, holes, gaps, n
    while math.log(v_bad / v_good) > REL_RESOLUTION:
        v = math.sqrt(v_good * v_bad)
        res = attempt(R1, R2, v, theta1, theta2)
        n += 1
        if res["ok"]:
            good, v_good = res, v
        else:
            bad, v_bad = res, v
    return good, bad, v_good, v_bad, holes, gaps, n


def extrapolated_margin(R1, R2, theta1_deg, theta2_deg, v_limit, solid):
    """pi - theta - beta on a sphere's contact line at contact, extrapolated to the limit volume: near a
    fold in V the filling angle approaches its value there like sqrt(V_limit - V), so from the margins at
    FOLD_PROBES = (d, 4d) below the limit, m = m0 + c sqrt(d) gives m0 = 2 m(d) - m(4d). m0 ~ 0: the
    meniscus turns vertical at that contact line at the limit; m0 > 0: the volume at contact is largest
    before the meniscus is vertical. NaN if a probe has no bridge."""
    theta = math.radians(theta1_deg if solid == 1 else theta2_deg)
    m = []
    for d in FOLD_PROBES:
        res = attempt(R1, R2, v_limit * (1 - d), math.radians(theta1_deg), math.radians(theta2_deg))
        if not res["ok"]:
            return float("nan")
        m.append(math.pi - theta - res["solutions"][0]["beta%d" % solid])
    return 2 * m[0] - m[1]


def cause(stage, error):
    """Short name of why the solver stopped, from its message."""
    if error is None:
        return "none up to the cap"
    for key, name in (("no pendular bridge at contact", "no bridge at contact"), ("rupture gap = -", "negative rupture gap"),
                      ("continuation stalled", "continuation stalled"), ("near the fold", "no bridge near the fold"),
                      ("no bridge found at gap", "solve: no bridge at gap"), ("singular bridge equations", "singular at contact")):
        if key in error:
            return name
    return stage + ": " + error


def case_row(geom, ratio, theta_small, theta_large, small_first):
    """Limit of one ordered case, with the quantities at the last solved volume. For equal spheres the
    "small" sphere is the one with theta_small."""
    R1, R2 = radii(ratio, small_first)
    t1, t2 = (theta_small, theta_large) if small_first or ratio == 0 else (theta_large, theta_small)
    t0 = time.perf_counter()
    good, bad, v_good, v_bad, holes, gaps, n = find_limit(R1, R2, math.radians(t1), math.radians(t2))
    row = {"geometry": geom, "ratio_small_large": ratio, "small_is_solid1": int(small_first or ratio == 0),
           "theta_small_deg": theta_small, "theta_large_deg": theta_large, "R1_m": R1, "R2_m": R2,
           "theta1_deg": t1, "theta2_deg": t2, "vstar_limit": v_good if v_good is not None else 0.0,
           "vstar_first_refused": v_bad if v_bad is not None else "",
           "cause": cause(bad["stage"], bad["error"]) if bad else cause(None, None),
           "stage": bad["stage"] if bad else "", "message": bad["error"] if bad else "",
           "holes_above": " ".join("%g" % h for h in holes), "attempts": n, "_gaps": gaps}
    if good is not None:
        c, r = good["solutions"][0], good["solutions"][-1]
        row["rupture_gap_m"] = good["bridge"].rupture_gap
        for tag, s in (("contact", c), ("rupture", r)):
            m = meniscus(s, R1, R2, math.radians(t1), math.radians(t2))
            row["beta1_%s_rad" % tag], row["beta2_%s_rad" % tag] = s["beta1"], s["beta2"]
            row["pressure_%s_Pa" % tag] = s["pressure"]
            row["neck_radius_%s_m" % tag] = s["neck_radius"]
            row["force_%s_N" % tag] = s["force_neck"]
            row["phi_max_%s_rad" % tag], row["phi_min_%s_rad" % tag] = m["phi_max_rad"], m["phi_min_rad"]
            row["steepest_at_%s" % tag] = m["steepest_at"]
            row["clearance1_%s" % tag], row["clearance2_%s" % tag] = m["clearance1"], m["clearance2"]
            row["profile_end_mismatch_%s" % tag] = m["end_mismatch"]
        # pi - theta - beta: how far a sphere's contact line is from leaving the meniscus vertical (phi = pi/2 there)
        margins = [math.pi - math.radians(t1) - c["beta1"], INF if math.isinf(R2) else math.pi - math.radians(t2) - c["beta2"]]
        row["margin1_contact_rad"], row["margin2_contact_rad"] = margins
        # The steepest point of the meniscus at contact: pi/2 - max |phi| and on which solid's contact line it lies.
        row["vertical_margin_rad"] = math.pi / 2 - max(row["phi_max_contact_rad"], -row["phi_min_contact_rad"])
        at = row["steepest_at_contact"]
        solid = 1 if at < 1e-3 else 2 if at > 1 - 1e-3 else 0
        names = {1: "small sphere" if row["small_is_solid1"] else "large sphere", 2: "large sphere" if row["small_is_solid1"] else "small sphere"}
        if ratio == 0:
            names = {1: "sphere", 2: "wall"}
        row["vertical_on"] = names.get(solid, "interior")
        if abs(row["phi_max_contact_rad"] + row["phi_min_contact_rad"]) < 1e-4 and solid:  # as steep on both contact lines
            row["vertical_on"] = "both spheres" if ratio else "both solids"
        if row["cause"] == "no bridge at contact":  # on the sphere whose contact line is nearest to vertical
            k = 1 if margins[0] <= margins[1] else 2
            row["margin_on"] = {1: "small sphere" if row["small_is_solid1"] else "large sphere",
                                2: "large sphere" if row["small_is_solid1"] else "small sphere"}[k] if ratio else "sphere"
            row["vertical_margin_extrapolated_rad"] = extrapolated_margin(R1, R2, t1, t2, math.sqrt(v_good * v_bad), k)
    row["seconds"] = time.perf_counter() - t0
    return row


def evaluate(geometries=GEOMETRIES, angles=ANGLES_DEG, log=None):
    """Every ordered case: two spheres in both orders; for equal spheres the swapped order of
    (theta1, theta2) is the case (theta2, theta1), computed once and listed twice."""
    rows = []
    for geom, ratio in geometries:
        first = {}
        for ts in angles:
            for tl in angles:
                for small_first in ((True,) if ratio in (0, 1) else (True, False)):
                    row = case_row(geom, ratio, ts, tl, small_first)
                    first[ts, tl] = row
                    rows.append(row)
                    if log:
                        log(row)
        if ratio == 1:
            flip = {"small sphere": "large sphere", "large sphere": "small sphere"}
            for ts in angles:
                for tl in angles:
                    r = dict(first[tl, ts], small_is_solid1=0, theta_small_deg=ts, theta_large_deg=tl, seconds=0.0)
                    for k in ("vertical_on", "margin_on"):
                        if k in r:
                            r[k] = flip.get(r[k], r[k])
                    rows.append(r)
    return rows


def swap_pairs(rows):
    """(small sphere first, small sphere second) rows of each sphere case."""
    by = {(r["geometry"], r["theta_small_deg"], r["theta_large_deg"], r["small_is_solid1"]): r for r in rows}
    return [(by[k], by[k[:3] + (0,)]) for k in by if k[3] == 1 and k[:3] + (0,) in by]


def swap_rows(rows):
    """Rupture gaps of both orders at every scan volume solved in both."""
    out = []
    for a, b in swap_pairs(rows):
        for v in sorted(set(a["_gaps"]) & set(b["_gaps"])):
            ga, gb = a["_gaps"][v], b["_gaps"][v]
            out.append({"geometry": a["geometry"], "theta_small_deg": a["theta_small_deg"], "theta_large_deg": a["theta_large_deg"],
                        "vstar": v, "rupture_gap_m": ga, "rupture_gap_swapped_m": gb, "rel_diff": abs(gb / ga - 1)})
    return out


def limits_table(rows):
    """One row per case: the documented limit is the smaller of the two orders of two spheres (below it the
    solver works whichever solid comes first), with the cause and the state at contact of the order that set it."""
    swapped = {(a["geometry"], a["theta_small_deg"], a["theta_large_deg"]): b for a, b in swap_pairs(rows)}
    diffs = {}
    for s in swap_rows(rows):
        key = (s["geometry"], s["theta_small_deg"], s["theta_large_deg"])
        diffs[key] = max(diffs.get(key, 0.0), s["rel_diff"])
    out = []
    for r in rows:
        if not r["small_is_solid1"]:
            continue
        key = (r["geometry"], r["theta_small_deg"], r["theta_large_deg"])
        s = swapped.get(key)
        m = r if s is None or r["vstar_limit"] <= s["vstar_limit"] else s
        small, large = ("1", "2") if m["small_is_solid1"] else ("2", "1")
        out.append({"geometry": r["geometry"], "theta_small_deg": r["theta_small_deg"], "theta_large_deg": r["theta_large_deg"],
                    "vstar_limit": m["vstar_limit"], "vstar_limit_small_first": r["vstar_limit"],
                    "vstar_limit_small_second": s["vstar_limit"] if s else "", "cause": m["cause"],
                    "steepest_on": m.get("vertical_on", ""), "vertical_margin_rad": m.get("vertical_margin_rad", ""),
                    "margin_on": m.get("margin_on", ""), "vertical_margin_extrapolated_rad": m.get("vertical_margin_extrapolated_rad", ""),
                    "beta_small_rad": m.get("beta%s_contact_rad" % small, ""),
                    "beta_large_rad": m.get("beta%s_contact_rad" % large, "") if r["ratio_small_large"] else "",
                    "swap_gap_rel_diff_max": diffs.get(key, "")})
    return out


def summary(rows):
    """Per geometry: the range of the documented limit over the angle pairs (the smaller of the two
    orders), where its minimum and maximum are; over the ordered cases: the causes, how close to vertical
    the meniscus is where the solver stops at contact, holes, the agreement of the two orders."""
    table = limits_table(rows)
    pairs = swap_pairs(rows)
    sw = swap_rows(rows)
    out = []
    for geom, _ in GEOMETRIES:
        ts = [t for t in table if t["geometry"] == geom]
        rs = [r for r in rows if r["geometry"] == geom]
        if not ts:
            continue
        lo = min(ts, key=lambda t: t["vstar_limit"])
        hi = max(ts, key=lambda t: t["vstar_limit"])
        vertical = [r for r in rs if r["cause"] == "no bridge at contact"]
        solved = [r for r in rs if "vertical_margin_rad" in r]
        ln_diffs = [abs(math.log(a["vstar_limit"] / b["vstar_limit"])) for a, b in pairs if a["geometry"] == geom]
        count = lambda values: "; ".join("%s (%d)" % (v, values.count(v)) for v in sorted(set(values)))
        out.append({"geometry": geom, "angle_pairs": len(ts), "ordered_cases": len(rs),
                    "vstar_limit_min": lo["vstar_limit"], "min_at_theta_small_deg": lo["theta_small_deg"], "min_at_theta_large_deg": lo["theta_large_deg"],
                    "vstar_limit_max": hi["vstar_limit"], "max_at_theta_small_deg": hi["theta_small_deg"], "max_at_theta_large_deg": hi["theta_large_deg"],
                    "vstar_limit_median": float(np.median([t["vstar_limit"] for t in ts])),
                    "causes": count([r["cause"] for r in rs]),
                    "steepest_on_where_no_bridge_at_contact": count([r["vertical_on"] for r in vertical]),
                    "vertical_margin_max_where_no_bridge_at_contact_rad": max((r["vertical_margin_rad"] for r in vertical), default=""),
                    "vertical_at_limit": sum(r.get("vertical_margin_extrapolated_rad", INF) < VERTICAL for r in vertical),
                    "fold_before_vertical": sum(r.get("vertical_margin_extrapolated_rad", -INF) >= VERTICAL for r in vertical),
                    "vertical_margin_extrapolated_max_rad": max((r["vertical_margin_extrapolated_rad"] for r in vertical), default=""),
                    "margin_on_where_no_bridge_at_contact": count([r["margin_on"] for r in vertical]),
                    "clearance_min": min(min(r["clearance1_%s" % t], r["clearance2_%s" % t]) for r in solved for t in ("contact", "rupture")),
                    "profile_end_mismatch_max": max(r["profile_end_mismatch_%s" % t] for r in solved for t in ("contact", "rupture")),
                    "holes": sum(bool(r["holes_above"]) for r in rs),
                    "swap_ln_limit_diff_max": max(ln_diffs, default=""),
                    "swap_gap_rel_diff_max": max((s["rel_diff"] for s in sw if s["geometry"] == geom), default=""),
                    "seconds": sum(r["seconds"] for r in rs)})
    return out


def write_csv(path, rows, digits=None):
    """Rows to CSV; keys starting with _ are internal; floats to `digits` significant digits if given."""
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys and not k.startswith("_")]
    fmt = (lambda v: "%.*g" % (digits, v) if isinstance(v, float) else v) if digits else (lambda v: v)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows({k: fmt(v) for k, v in r.items()} for r in rows)


def plot(rows, path):
    """The limit against the angle on the small sphere, one line per angle on the other solid, one panel per
    geometry: the documented limit (line), each order (o: small sphere first, x: second) and the volumes where
    an order stops on a negative rupture gap (red square) or at the cap (triangle)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    table = limits_table(rows)
    fig, axes = plt.subplots(2, 2, figsize=(11, 8.5), sharey=True)
    cmap = plt.get_cmap("viridis")
    for ax, (geom, ratio) in zip(axes.flat, GEOMETRIES):
        for i, tl in enumerate(ANGLES_DEG):
            color = cmap(i / (len(ANGLES_DEG) - 1))
            ts = sorted((t for t in table if t["geometry"] == geom and t["theta_large_deg"] == tl), key=lambda t: t["theta_small_deg"])
            ax.plot([t["theta_small_deg"] for t in ts], [t["vstar_limit"] for t in ts], "-", color=color, label="%d" % tl)
            for r in rows:
                if r["geometry"] != geom or r["theta_large_deg"] != tl:
                    continue
                x, y = r["theta_small_deg"], r["vstar_limit"]
                ax.plot(x, y, "o" if r["small_is_solid1"] else "x", color=color, ms=4, mfc="none")
                if r["cause"] == "negative rupture gap":
                    ax.plot(x, y, "s", color="red", ms=8, mfc="none")
                elif r["cause"] == "none up to the cap":
                    ax.plot(x, y, "^", color=color, ms=7)
        ax.set_yscale("log")
        ax.set_title("wall" if ratio == 0 else "R_small/R_large = %s" % geom)
        ax.set_xlabel("contact angle on the %s [deg]" % ("sphere" if ratio == 0 else "small sphere"))
        ax.grid(True, which="both", alpha=0.3)
    for ax in axes[:, 0]:
        ax.set_ylabel("largest V* = V/R_small^3 solved")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, title="contact angle on the other solid (large sphere or wall) [deg]", fontsize=8,
               title_fontsize=8, ncol=len(ANGLES_DEG), loc="lower center")
    fig.suptitle("Exact Young-Laplace solver: largest volume followed from contact to rupture\n"
                 "line: smaller of both orders; o / x: small sphere as solid 1 / 2; red square: negative rupture gap; "
                 "triangle: scan cap", fontsize=9)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def run(outdir, datadir, geometries=GEOMETRIES, angles=ANGLES_DEG, log=None):
    """Map the limits, write outdir/{cases.csv, swap.csv, summary.csv, bridge_domain.png} and datadir/limits.csv."""
    os.makedirs(outdir, exist_ok=True)
    os.makedirs(datadir, exist_ok=True)
    rows = evaluate(geometries, angles, log)
    write_csv(os.path.join(outdir, "cases.csv"), rows)
    write_csv(os.path.join(outdir, "swap.csv"), swap_rows(rows))
    summ = summary(rows)
    write_csv(os.path.join(outdir, "summary.csv"), summ)
    write_csv(os.path.join(datadir, "limits.csv"), limits_table(rows), digits=5)
    plot(rows, os.path.join(outdir, "bridge_domain.png"))
    return rows, summ
