"""Two-sphere and sphere-wall pull-off scenarios, run inside yade; the viscous pull-off at constant speed.

Two spheres (Gladkyy & Schwarze 2014, section 3): one sphere is fixed, the other starts touching
it (gap a = 0) and is moved away at constant velocity along the line of centres, without gravity,
until the bridge has ruptured. A case with R2_m = inf is a sphere-wall pull-off (Elskamp &
Kruggel-Emden 2018, Fig. 5a): the fixed partner is a wall (plane x = 0) and the sphere R1 is pulled
along the wall normal. The bridge forms at the initial contact. The capillary force is recorded at
every step; the motion is kinematic, so the curve does not depend on the pulling speed, and the
steps land exactly on the gaps of the summary (0, 0.5 and 0.95 of the rupture distance).

Viscous pull-off (Elskamp & Kruggel-Emden 2018, Fig. 5b; viscous_pull_offs): the same pair with a
viscous liquid, pulled at constant speeds; the capillary force, the normal viscous force and their
sum are recorded until the bridge breaks at the dynamic rupture distance (Elskamp eq. 33).
"""
import csv
import math
import os

import numpy as np
from yade import O
from yade.utils import sphere, wall
from yade.wrapper import PendularMat

from . import kernels
from .scene import engines

SUMMARY_FRACTIONS = (0.0, 0.5, 0.95)


def is_wall(case):
    """True for a sphere-wall case (R2_m = inf)."""
    return math.isinf(case.R2_m)


def _pair(case, model, rupture, dt, eta=0.0, viscous="pitois"):
    """Reset the scene to the touching pair of a case; return (b1, b2, R2 [m]).

    Body 1 (sphere R1 centred at the origin, or the wall x = 0) and body 2 (sphere R2 touching it
    along +x, or the sphere R1 on the wall) are fixed, i.e. moved kinematically by their velocity.
    R2 is the radius that the gap x2 - x1 - R1 - R2 subtracts (0 for a wall). The material has F(0)
    in contact (``forceInContact=True``, Richefeu 2008), the liquid viscosity eta [Pa s] and the
    normal viscous law ``viscous`` (used if eta > 0), and tc = 20 dt.
    """
    O.reset()
    O.dt = dt
    mat = PendularMat(tc=20 * dt, en=0.83, et=0.83, density=2500, frictionAngle=0, wet=True, Vb=case.volume_m3,
                      gamma=case.gamma_N_m, theta=case.theta_rad, model=model, rupture=rupture, forceInContact=True,
                      eta=eta, viscousNormal=viscous)
    O.materials.append(mat)
    if is_wall(case):
        b1 = O.bodies.append(wall((0, 0, 0), axis=0, material=mat))
        b2 = O.bodies.append(sphere((case.R1_m, 0, 0), case.R1_m, material=mat, fixed=True))
    else:
        b1 = O.bodies.append(sphere((0, 0, 0), case.R1_m, material=mat, fixed=True))
        b2 = O.bodies.append(sphere((case.R1_m + case.R2_m, 0, 0), case.R2_m, material=mat, fixed=True))
    O.engines = engines()
    return b1, b2, 0.0 if is_wall(case) else case.R2_m


def pull_off(case, model, rupture="willett", steps=1000, dt=1e-6):
    """Pull a case apart (two spheres, or the sphere R1 from a wall if R2_m = inf); return
    (a_crit [m], gaps [m], forces [N]).

    Body 1 (sphere R1 centred at the origin, or the wall x = 0) is fixed; body 2 (sphere R2, or
    the sphere R1 for a wall) starts touching it and moves along +x by a_crit/steps per step.
    The force at a = 0 is the bridge force at contact F(0) (``forceInContact=True``, as in
    Richefeu 2008), so that the curve starts at the touching configuration; the sample after
    the rupture distance shows the jump to zero. a_crit is the rupture distance of the model
    with the given rupture rule (kernels.bridge).
    """
    b1, b2, R2 = _pair(case, model, rupture, dt)
    a_crit = kernels.bridge(model, case.R1_m, case.R2_m, case.volume_m3, case.gamma_N_m, case.theta_rad,
                            rupture=rupture)["rupture"]
    step = a_crit / steps
    O.bodies[b2].state.vel = (step / dt, 0, 0)
    gaps, forces = [], []
    for _ in range(int(steps * 1.02) + 2):
        gaps.append(O.bodies[b2].state.pos[0] - O.bodies[b1].state.pos[0] - case.R1_m - R2)
        O.step()
        forces.append(O.forces.f(b1)[0])  # attraction pulls body 1 towards body 2 (+x)
    return a_crit, gaps, forces


def exact_curve(case, steps=1000):
    """The exact Young-Laplace force at the same kind of gaps: (a_crit [m], gaps [m], forces [N])."""
    b = kernels.YoungLaplaceBridge(case.R1_m, case.R2_m, case.volume_m3, case.theta_rad)
    a_crit = b.rupture_gap
    gaps = [a_crit * i / steps for i in range(int(steps * 1.02) + 2)]
    return a_crit, gaps, [b.solve(g, case.gamma_N_m)["force_neck"] if g <= a_crit else 0.0 for g in gaps]


def rms_relative_deviation(curve, exact):
    """RMS over the exact curve's gaps in [0, exact rupture gap] of (F - F_exact) / F_exact [-].

    curve and exact are (a_crit [m], gaps [m], forces [N]) as returned by pull_off and
    exact_curve. The model's force at the exact curve's gaps is interpolated linearly between its
    samples before rupture and is 0 beyond its rupture distance, so that a bridge breaking early
    counts as -100 % over the missing range (and one breaking late is not credited beyond).
    """
    a_crit, gaps, forces = curve
    alive = [(g, F) for g, F in zip(gaps, forces) if g <= a_crit and F != 0.0]
    g_alive, F_alive = np.array(alive).T
    a_ex, g_ex, F_ex = (np.asarray(x) for x in exact)
    g_ex, F_ex = g_ex[g_ex <= a_ex], F_ex[g_ex <= a_ex]
    F = np.where(g_ex <= a_crit, np.interp(g_ex, g_alive, F_alive), 0.0)
    return float(np.sqrt(np.mean(((F - F_ex) / F_ex) ** 2)))


def run_all(cases, models, outdir, steps=1000, rupture="willett", log=print):
    """Run every case (two spheres, or sphere-wall if R2_m = inf) with every model; write
    forces.csv and summary.csv in outdir.

    Besides the models (run in YADE through the Law2, rupture rule ``rupture``), the exact
    solver's curve is written as model ``young_laplace``. Returns the summary rows: dicts with
    case, model, a_crit_m [m], the force [N] at each SUMMARY_FRACTIONS of a_crit (F_0_N, F_0.5_N,
    F_0.95_N) and rms_rel_dev [-] (rms_relative_deviation from the exact curve; 0 for it).
    """
    os.makedirs(outdir, exist_ok=True)
    summary = []
    with open(os.path.join(outdir, "forces.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "model", "gap_m", "force_N", "gap_over_acrit", "R1_m", "R2_m", "volume_m3", "gamma_N_m", "theta_rad"])
        for c in cases:
            exact = exact_curve(c, steps)
            for m in list(models) + ["young_laplace"]:
                curve = exact if m == "young_laplace" else pull_off(c, m, rupture=rupture, steps=steps)
                a_crit, gaps, forces = curve
                for g, F in zip(gaps, forces):
                    w.writerow([c.code, m, "%.9e" % g, "%.9e" % F, "%.6f" % (g / a_crit), c.R1_m, c.R2_m, c.volume_m3, c.gamma_N_m, c.theta_rad])
                row = {"case": c.code, "model": m, "a_crit_m": a_crit}
                for frac in SUMMARY_FRACTIONS:
                    row["F_%g_N" % frac] = forces[int(round(frac * steps))]
                row["rms_rel_dev"] = rms_relative_deviation(curve, exact)
                summary.append(row)
            log("  %s done" % c.code)
    with open(os.path.join(outdir, "summary.csv"), "w", newline="") as f:
        keys = list(summary[0].keys())
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(summary)
    return summary


def format_summary(summary):
    """Text table of the summary: forces in mN (micro-scale cases) or nN (Rabinovich cases)."""
    lines = ["%-5s %-20s %12s %12s %12s %12s" % ("case", "model", "a_crit[um]", "F(0)", "F(0.5ac)", "F(0.95ac)")]
    for r in summary:
        unit, scale = ("mN", 1e3) if r["case"].startswith("W") else ("nN", 1e9)
        lines.append("%-5s %-20s %12.4f %10.4f%s %10.4f%s %10.4f%s" % (
            r["case"], r["model"], r["a_crit_m"] * 1e6, r["F_0_N"] * scale, unit, r["F_0.5_N"] * scale, unit,
            r["F_0.95_N"] * scale, unit))
    return "\n".join(lines)


def format_deviation_summary(summary, scale=1e9, unit="nN", gap_scale=1e9, gap_unit="nm"):
    """Text table: per case and model F(0), the rupture gap and the RMS relative deviation from
    the exact curve (rms_relative_deviation), forces times scale in unit, gaps times gap_scale."""
    head = ("case", "model", "F(0)[%s]" % unit, "a_crit[%s]" % gap_unit, "RMS dev[%]")
    lines = ["%-6s %-20s %10s %12s %11s" % head]
    for r in summary:
        lines.append("%-6s %-20s %10.3f %12.2f %11.2f" % (r["case"], r["model"], r["F_0_N"] * scale, r["a_crit_m"] * gap_scale,
                                                       100 * r["rms_rel_dev"]))
    return "\n".join(lines)


def effective_radius(case):
    """Harmonic-mean radius 2 R1 R2 / (R1 + R2) of the capillary models (Gladkyy eq. 1) [m]; 2 R1 for
    a wall (Derjaguin sphere-plane limit). Elskamp 2018 calls it r_eff (R1 = R2 = r: r_eff = r)."""
    return 2 * case.R1_m if is_wall(case) else 2 * case.R1_m * case.R2_m / (case.R1_m + case.R2_m)


def derjaguin_force(case):
    """2 pi R gamma cos(theta) with the harmonic-mean radius R = effective_radius(case) [N]: for a
    wall the sphere-plane value 4 pi R1 gamma cos(theta)."""
    return 2 * math.pi * effective_radius(case) * case.gamma_N_m * math.cos(case.theta_rad)


# --- Viscous pull-off at constant speed (Elskamp & Kruggel-Emden 2018, Fig. 5b) -------------------
# Elskamp's choices: Rabinovich's capillary force with the sine term (our "rabinovich"), Pitois'
# normal viscous force (eq. 26), Goldman's tangential one (eq. 28-29, no tangential motion here)
# and Willett's rupture distance with Pitois' dynamic extension (eq. 33).
VISCOUS_GAP_FRACTIONS = (0.01, 0.1)  # S / r_eff at which the summary gives F_visc / F_cap
DYNAMIC_SUFFIX = "+pitois"


def static_rupture_distance(case, model, rupture):
    """Static rupture distance [m] of a bridge: the rule of ``rupture`` without its "+pitois" suffix
    ("pitois" alone means willett+pitois), or the model's own range (kernels.bridge)."""
    static_rule = "willett" if rupture == "pitois" else rupture[:-len(DYNAMIC_SUFFIX)] if rupture.endswith(DYNAMIC_SUFFIX) else rupture
    return static_rule, kernels.bridge(model, case.R1_m, case.R2_m, case.volume_m3, case.gamma_N_m, case.theta_rad,
                                       rupture=static_rule)["rupture"]


def expected_rupture_distance(case, model, rupture, speed, eta):
    """(static, expected) rupture distance [m] of a pull at the relative speed ``speed`` [m/s]:
    expected = the static one, stretched by Pitois' rule S_rup (1 + sqrt(speed eta / gamma))
    (Elskamp 2018 eq. 33, kernels.dynamic_rupture_distance) if ``rupture`` is dynamic."""
    _, static = static_rupture_distance(case, model, rupture)
    dynamic = rupture == "pitois" or rupture.endswith(DYNAMIC_SUFFIX)
    return static, kernels.dynamic_rupture_distance(static, speed, eta, case.gamma_N_m) if dynamic else static


def _bridge_phys(b1, b2):
    """The PendularPhys of the pair's bridge, or None once the bridge has broken (the law resets the
    interaction at rupture)."""
    try:
        I = O.interactions[b1, b2]
    except (IndexError, ValueError):
        return None
    return I.phys if I.isReal and I.phys is not None and I.phys.active else None


def pull_at_speed(case, model, speed, gap_step, eta=None, rupture="willett+pitois", viscous="pitois"):
    """Pull body 2 of a case away from contact at constant speed [m/s] until the bridge breaks; return
    a dict of the run.

    The pair is that of pull_off (body 1 fixed at the origin, body 2 moved kinematically along +x
    from contact) with the liquid viscosity eta [Pa s] (default case.eta_Pa_s; 0: capillary force
    only, and then ``rupture`` must be static). The motion is kinematic, so the time step
    dt = gap_step / speed [s] only sets the sampling: the gap grows by gap_step [m] per step, and
    pulls at different speeds with one gap_step sample the same gaps. At every step it records the
    gap S before the step [m] and, from the step's force evaluation, the bridge's capillary force
    phys.Fcap [N] and normal viscous force phys.Fvisc [N] (attraction > 0), the force on body 1 along
    +x from O.forces [N] (= Fcap + Fvisc while the bridge exists), the rupture distance of the
    step phys.sRupture [m], and the kernels' expectation F_cap(S) + c_n(S) speed [N]
    (kernels.force, continued to the dynamic rupture distance, + kernels.viscous_normal_force with
    v_n = -speed). It stops after the first step without a bridge (all forces 0 there).

    Returned keys: speed_m_s, eta_Pa_s, dt_s, static_m and expected_m (expected_rupture_distance),
    last_gap_m (largest gap with a bridge), broke_gap_m (first gap without), and the per-step lists
    gap_m, F_cap_N, F_visc_N, F_body_N, F_kernel_N, s_rupture_m (0 without bridge), bridge (bool).
    """
    eta = case.eta_Pa_s if eta is None else eta
    static_rule, _ = static_rupture_distance(case, model, rupture)
    static, expected = expected_rupture_distance(case, model, rupture, speed, eta)
    dt = gap_step / speed
    b1, b2, R2 = _pair(case, model, rupture, dt, eta=eta, viscous=viscous)
    O.bodies[b2].state.vel = (speed, 0, 0)
    run = dict(speed_m_s=speed, eta_Pa_s=eta, dt_s=dt, static_m=static, expected_m=expected, last_gap_m=math.nan,
               broke_gap_m=math.nan)
    keys = ("gap_m", "F_cap_N", "F_visc_N", "F_body_N", "F_kernel_N", "s_rupture_m", "bridge")
    run.update({k: [] for k in keys})
    for _ in range(int(expected / gap_step * 1.05) + 2):
        gap = O.bodies[b2].state.pos[0] - O.bodies[b1].state.pos[0] - case.R1_m - R2
        O.step()
        phys = _bridge_phys(b1, b2)
        fcap, fvisc, srup = (phys.Fcap, phys.Fvisc, phys.sRupture) if phys is not None else (0.0, 0.0, 0.0)
        F_kernel = 0.0
        if phys is not None:
            F_kernel = float(kernels.force(model, gap, case.R1_m, case.R2_m, case.volume_m3, case.gamma_N_m, case.theta_rad,
                                           rupture=static_rule, range=expected)) + kernels.viscous_normal_force(
                viscous, gap, -speed, case.R1_m, case.R2_m, eta, case.volume_m3)
        for k, v in zip(keys, (gap, fcap, fvisc, O.forces.f(b1)[0], F_kernel, srup, phys is not None)):
            run[k].append(v)
        if phys is None:
            run["broke_gap_m"] = gap
            break
        run["last_gap_m"] = gap
    return run


def viscous_pull_offs(case, model="rabinovich", rupture="willett+pitois", viscous="pitois", steps=1000, log=print):
    """Every pull of a ViscousCase (cases.ELSKAMP2018_FIG5B): one pull_at_speed per case.speeds_m_s
    with the viscosity case.eta_Pa_s, and one without viscosity (eta = 0, the static rule of
    ``rupture``: the capillary force alone) at the smallest speed. Returns the list of runs, the
    capillary-only run last.

    All pulls use one gap step [m]: the smallest expected rupture distance over the speeds divided
    by ``steps``, so that every pull has at least ``steps`` steps to rupture and all pulls sample
    the same gaps (F_visc / v then compares at equal S without interpolation).
    """
    speeds = sorted(case.speeds_m_s)
    gap_step = min(expected_rupture_distance(case, model, rupture, v, case.eta_Pa_s)[1] for v in speeds) / steps
    static_rule, _ = static_rupture_distance(case, model, rupture)
    runs = []
    for v in speeds:
        runs.append(pull_at_speed(case, model, v, gap_step, rupture=rupture, viscous=viscous))
        log("  v = %g mm/s: %d steps, bridge broke at S = %.4f mm" % (v * 1e3, len(runs[-1]["gap_m"]), runs[-1]["broke_gap_m"] * 1e3))
    runs.append(pull_at_speed(case, model, speeds[0], gap_step, eta=0.0, rupture=static_rule, viscous=viscous))
    log("  capillary only (eta = 0): %d steps, bridge broke at S = %.4f mm" % (len(runs[-1]["gap_m"]), runs[-1]["broke_gap_m"] * 1e3))
    return runs


def write_viscous_forces(runs, path, r_eff):
    """Write every step of every run (viscous_pull_offs) as CSV; r_eff [m] scales gap_over_reff."""
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["speed_m_s", "eta_Pa_s", "step", "time_s", "gap_m", "gap_over_reff", "F_cap_N", "F_visc_N", "F_tot_N",
                    "F_body_N", "F_kernel_N", "S_rupture_m", "bridge"])
        for r in runs:
            for i, g in enumerate(r["gap_m"]):
                w.writerow(["%g" % r["speed_m_s"], "%g" % r["eta_Pa_s"], i, "%.9e" % (i * r["dt_s"]), "%.9e" % g, "%.6f" % (g / r_eff),
                            "%.9e" % r["F_cap_N"][i], "%.9e" % r["F_visc_N"][i], "%.9e" % (r["F_cap_N"][i] + r["F_visc_N"][i]),
                            "%.9e" % r["F_body_N"][i], "%.9e" % r["F_kernel_N"][i], "%.9e" % r["s_rupture_m"][i], int(r["bridge"][i])])


def viscous_summary(case, runs, viscous="pitois"):
    """Checks of the viscous pull-offs (runs of viscous_pull_offs, the capillary-only run last).

    Per run: speed [m/s], static and expected (eq. 33) rupture distance and the last gap with a
    bridge and the first without [m]; rel_phys_body, the largest |F_body - (F_cap + F_visc)| /
    (F_cap + F_visc) (O.forces against the phys) and rel_kernel, the largest |F_body - F_kernel| /
    F_kernel (against the kernels), both over the steps with a bridge; F_visc / F_cap at S = f r_eff
    for f in VISCOUS_GAP_FRACTIONS (linear interpolation between samples); visc_over_cap_max and
    its gap over all steps with a bridge, and over those with S >= 0.01 r_eff.
    Across speeds: linearity, the largest |F_visc(S; v) / v - c_n(S)| / c_n(S) over the samples
    with S <= the smallest last gap, c_n(S) = kernels.viscous_normal_force at v_n = -1 m/s, and
    spread, the largest (max - min) / mean over the speeds of F_visc(S; v) / v at equal S
    (interpolated onto the slowest run's gaps; all runs of viscous_pull_offs share them).
    """
    r_eff = effective_radius(case)
    rows = []
    for r in runs:
        g = np.array(r["gap_m"])
        alive = np.array(r["bridge"])
        fcap, fvisc, fbody, fker = (np.array(r[k])[alive] for k in ("F_cap_N", "F_visc_N", "F_body_N", "F_kernel_N"))
        ga = g[alive]
        ratio = fvisc / fcap
        far = ga >= 0.01 * r_eff
        row = dict(speed_m_s=r["speed_m_s"], eta_Pa_s=r["eta_Pa_s"], static_m=r["static_m"], expected_m=r["expected_m"],
                   last_gap_m=r["last_gap_m"], broke_gap_m=r["broke_gap_m"],
                   broke_ok=bool(r["last_gap_m"] <= r["expected_m"] < r["broke_gap_m"]),
                   rel_phys_body=float(np.max(np.abs(fbody - (fcap + fvisc)) / np.abs(fcap + fvisc))),
                   rel_kernel=float(np.max(np.abs(fbody - fker) / np.abs(fker))),
                   all_finite=bool(np.all(np.isfinite(np.concatenate([fcap, fvisc, fbody])))),
                   visc_over_cap_max=float(np.max(ratio)), visc_over_cap_max_at_m=float(ga[np.argmax(ratio)]),
                   visc_over_cap_max_far=float(np.max(ratio[far])), visc_over_cap_max_far_at_m=float(ga[far][np.argmax(ratio[far])]))
        for f in VISCOUS_GAP_FRACTIONS:
            row["visc_over_cap_%g" % f] = float(np.interp(f * r_eff, ga, fvisc) / np.interp(f * r_eff, ga, fcap))
        rows.append(row)
    viscid = [r for r in runs if r["eta_Pa_s"] > 0]
    s_max = min(r["last_gap_m"] for r in viscid)
    base = np.array(viscid[0]["gap_m"])
    base = base[base <= s_max]
    per_v = []
    linearity = 0.0
    for r in viscid:
        g = np.array(r["gap_m"])[np.array(r["bridge"])]
        fv = np.array(r["F_visc_N"])[np.array(r["bridge"])] / r["speed_m_s"]
        cn = np.array([kernels.viscous_normal_force(viscous, s, -1.0, case.R1_m, case.R2_m, r["eta_Pa_s"], case.volume_m3) for s in g])
        linearity = max(linearity, float(np.max(np.abs(fv - cn) / cn)))
        per_v.append(np.interp(base, g, fv))
    per_v = np.array(per_v)
    spread = float(np.max((per_v.max(axis=0) - per_v.min(axis=0)) / per_v.mean(axis=0)))
    return dict(r_eff_m=r_eff, rows=rows, linearity=linearity, spread=spread, spread_gaps=len(base), spread_s_max_m=s_max)


def format_viscous_summary(summary):
    """Text table of viscous_summary: gaps in mm and over r_eff, ratios in %."""
    r_eff = summary["r_eff_m"]
    f1, f2 = VISCOUS_GAP_FRACTIONS
    lines = ["r_eff = %.3g mm; rupture distances in mm (S/r_eff in brackets); Fv/Fc = F_visc / F_cap at S = %g and %g r_eff"
             % (r_eff * 1e3, f1, f2),
             "%-9s %-15s %-15s %-27s %10s %10s %14s %10s %10s" % (
                 "v[mm/s]", "S_rup static", "S_rup,dyn(33)", "simulated break (last,first)", "Fv/Fc@%g" % f1, "Fv/Fc@%g" % f2,
                 "max Fv/Fc[%]", "body-phys", "body-kern")]
    for r in summary["rows"]:
        label = "%g" % (r["speed_m_s"] * 1e3) if r["eta_Pa_s"] > 0 else "cap only"
        lines.append("%-9s %7.4f(%.4f) %7.4f(%.4f) %8.5f-%8.5f %-8s %9.3f%% %9.3f%% %7.2f@S=%.3g %10.1e %10.1e" % (
            label, r["static_m"] * 1e3, r["static_m"] / r_eff, r["expected_m"] * 1e3, r["expected_m"] / r_eff,
            r["last_gap_m"] * 1e3, r["broke_gap_m"] * 1e3, "ok" if r["broke_ok"] else "WRONG",
            100 * r["visc_over_cap_%g" % f1], 100 * r["visc_over_cap_%g" % f2], 100 * r["visc_over_cap_max"],
            r["visc_over_cap_max_at_m"] / r_eff, r["rel_phys_body"], r["rel_kernel"]))
    slow = min((r for r in summary["rows"] if r["eta_Pa_s"] > 0), key=lambda r: r["speed_m_s"])
    lines.append("v = %g mm/s: max |F_tot - F_cap| / F_cap = %.2f %% (at S = %.3g r_eff; at contact S_eff = S_min); "
                 "over S >= 0.01 r_eff: %.2f %% (at S = %.3g r_eff)" % (
                     slow["speed_m_s"] * 1e3, 100 * slow["visc_over_cap_max"], slow["visc_over_cap_max_at_m"] / r_eff,
                     100 * slow["visc_over_cap_max_far"], slow["visc_over_cap_max_far_at_m"] / r_eff))
    lines.append("eq. (26) linear in v: max |F_visc/v - c_n(S)| / c_n(S) = %.1e (every speed, every step with a bridge); "
                 "spread of F_visc/v across the speeds at equal S = %.1e (%d gaps, S <= %.4f mm)" % (
                     summary["linearity"], summary["spread"], summary["spread_gaps"], summary["spread_s_max_m"] * 1e3))
    return "\n".join(lines)
