"""Two-sphere pull-off scenario (Gladkyy & Schwarze 2014, section 3), run inside yade.

One sphere is fixed, the other starts touching it (gap a = 0) and is moved away at constant
velocity along the line of centres, without gravity, until the bridge has ruptured. The bridge
forms at the initial contact. The capillary force is recorded at every step; the motion is
kinematic, so the curve does not depend on the pulling speed, and the steps land exactly on the
gaps of the summary (0, 0.5 and 0.95 of the rupture distance).
"""
import csv
import math
import os

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from . import kernels
from .scene import engines

SUMMARY_FRACTIONS = (0.0, 0.5, 0.95)


def pull_off(case, model, rupture="willett", steps=1000, dt=1e-6):
    """Pull two spheres of a Table 1 case apart; return (a_crit [m], gaps [m], forces [N]).

    The force at a = 0 is the bridge force at contact F(0) (``forceInContact=True``, as in
    Richefeu 2008), so that the curve starts at the touching configuration; the sample after
    the rupture distance shows the jump to zero.
    """
    O.reset()
    O.dt = dt
    mat = PendularMat(tc=20 * dt, en=0.83, et=0.83, density=2500, frictionAngle=0, wet=True, Vb=case.volume_m3,
                      gamma=case.gamma_N_m, theta=case.theta_rad, model=model, rupture=rupture, forceInContact=True)
    O.materials.append(mat)
    b1 = O.bodies.append(sphere((0, 0, 0), case.R1_m, material=mat, fixed=True))
    b2 = O.bodies.append(sphere((case.R1_m + case.R2_m, 0, 0), case.R2_m, material=mat, fixed=True))
    O.engines = engines()
    a_crit = kernels.bridge(model, case.R1_m, case.R2_m, case.volume_m3, case.gamma_N_m, case.theta_rad,
                            rupture=rupture)["rupture"]
    step = a_crit / steps
    O.bodies[b2].state.vel = (step / dt, 0, 0)
    gaps, forces = [], []
    for _ in range(int(steps * 1.02) + 2):
        gaps.append(O.bodies[b2].state.pos[0] - O.bodies[b1].state.pos[0] - case.R1_m - case.R2_m)
        O.step()
        forces.append(O.forces.f(b1)[0])  # attraction pulls sphere 1 towards sphere 2 (+x)
    return a_crit, gaps, forces


def exact_curve(case, steps=1000):
    """The exact Young-Laplace force at the same kind of gaps: (a_crit [m], gaps [m], forces [N])."""
    b = kernels.YoungLaplaceBridge(case.R1_m, case.R2_m, case.volume_m3, case.theta_rad)
    a_crit = b.rupture_gap
    gaps = [a_crit * i / steps for i in range(int(steps * 1.02) + 2)]
    return a_crit, gaps, [b.solve(g, case.gamma_N_m)["force_neck"] if g <= a_crit else 0.0 for g in gaps]


def run_all(cases, models, outdir, steps=1000, log=print):
    """Run every case with every model; write forces.csv and summary.csv in outdir.

    Besides the models (run in YADE through the Law2), the exact solver's curve is written as
    model ``young_laplace``. Returns the summary rows: dicts with case, model, a_crit_m and the
    force at each SUMMARY_FRACTIONS of a_crit (F_0_N, F_0.5_N, F_0.95_N).
    """
    os.makedirs(outdir, exist_ok=True)
    summary = []
    with open(os.path.join(outdir, "forces.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "model", "gap_m", "force_N", "gap_over_acrit", "R1_m", "R2_m", "volume_m3", "gamma_N_m", "theta_rad"])
        for c in cases:
            for m in list(models) + ["young_laplace"]:
                a_crit, gaps, forces = exact_curve(c, steps) if m == "young_laplace" else pull_off(c, m, steps=steps)
                for g, F in zip(gaps, forces):
                    w.writerow([c.code, m, "%.9e" % g, "%.9e" % F, "%.6f" % (g / a_crit), c.R1_m, c.R2_m, c.volume_m3, c.gamma_N_m, c.theta_rad])
                row = {"case": c.code, "model": m, "a_crit_m": a_crit}
                for frac in SUMMARY_FRACTIONS:
                    row["F_%g_N" % frac] = forces[int(round(frac * steps))]
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


def derjaguin_force(case):
    """2 pi R gamma cos(theta) with the harmonic-mean radius (Gladkyy eq. 1) [N]."""
    R = 2 * case.R1_m * case.R2_m / (case.R1_m + case.R2_m)
    return 2 * math.pi * R * case.gamma_N_m * math.cos(case.theta_rad)
