"""young_laplace_table against the exact Young-Laplace solver over the table's whole domain.

Seeded random bridges (``sample``): V* = V/Rh^3 log-uniform in [1e-5, 0.5] (Rh = 2 R1 R2/(R1 + R2), 2 R1
against a wall), theta1 and theta2 independently uniform in [0, 70 deg], R_small/R_large uniform in
[1/4, 1] with the smaller sphere as solid 1 or solid 2 at random, and one bridge in five a sphere on a
wall. For each bridge the table's rupture distance (``kernels.bridge``) and its transfer ratio at rupture
(``kernels.exact_transfer``) are compared with the solver's (``YoungLaplaceBridge.rupture_gap`` and
``volume1/volume`` at it), and its force (``kernels.force``: the per-step evaluated form a simulation
uses) at ``GAPS_PER_BRIDGE`` random gaps up to the shorter of the two rupture distances. Errors are
relative (|table - solver| / solver) for the force and the rupture distance, absolute for the transfer
ratio, a share in [0, 1]. A bridge the table refuses as repulsive (its force below 1e-3 of its largest
somewhere) is counted, with the solver's smallest force over its largest (the worst column of the
"refused as repulsive" row), and left out of the errors.

CSV columns carry their unit as a suffix (_m, _m3, _N, _rad); vstar and the ratios are dimensionless.
"""
import csv
import math
import os
import time

import numpy as np

from yade_capillary import kernels

SEED = 20261129
THETA_MAX = math.radians(70)
VSTAR = (1e-5, 0.5)
RATIO_MIN = 0.25
WALL_SHARE = 0.2
GAPS_PER_BRIDGE = 5
GAMMA = 0.072           # [N/m]; forces scale with it
R_SMALL = 1e-3          # [m]
TOL = 1e-10             # local error bound of the solver's integration


def sample(n, seed=SEED):
    """n bridges as dicts: R1_m, R2_m (inf: wall), volume_m3, theta1_rad, theta2_rad, vstar, ratio."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        vstar = math.exp(rng.uniform(math.log(VSTAR[0]), math.log(VSTAR[1])))
        t1, t2 = rng.uniform(0, THETA_MAX, 2)
        if rng.uniform() < WALL_SHARE:
            R1, R2, ratio, Rh = R_SMALL, math.inf, 0.0, 2 * R_SMALL
        else:
            ratio = rng.uniform(RATIO_MIN, 1)
            R1, R2 = R_SMALL, R_SMALL / ratio
            if rng.uniform() < 0.5:
                R1, R2 = R2, R1
            Rh = 2 * R1 * R2 / (R1 + R2)
        out.append(dict(R1_m=R1, R2_m=R2, volume_m3=vstar * Rh ** 3, theta1_rad=t1, theta2_rad=t2, vstar=vstar, ratio=ratio,
                        gap_fractions=rng.uniform(0, 1, GAPS_PER_BRIDGE)))
    return out


def compare(b):
    """The table against the solver for one bridge: a dict of the bridge and its errors."""
    args = (b["R1_m"], b["R2_m"], b["volume_m3"])
    ex = kernels.YoungLaplaceBridge(*args, b["theta1_rad"], b["theta2_rad"], TOL)
    a_ex = ex.rupture_gap
    row = {k: b[k] for k in ("R1_m", "R2_m", "volume_m3", "theta1_rad", "theta2_rad", "vstar", "ratio")}
    try:
        tb = kernels.bridge("young_laplace_table", *args, GAMMA, b["theta1_rad"], b["theta2_rad"])
    except ValueError as e:  # the repulsive corner: the table holds attractive bridges only
        if "repulsive" not in str(e):
            raise
        forces = [ex.solve(a_ex * j / 20, GAMMA)["force_neck"] for j in range(21)]
        row.update(refused=1, solver_min_force_over_max=min(forces) / max(forces))
        return row
    a_tb = tb["rupture"]
    at_rupture = ex.solve(a_ex, GAMMA)
    transfer_ex = at_rupture["volume1"] / at_rupture["volume"]
    transfer_tb = kernels.exact_transfer(*args, b["theta1_rad"], b["theta2_rad"])
    gaps = np.asarray(b["gap_fractions"]) * min(a_ex, a_tb)
    f_tb = np.atleast_1d(kernels.force("young_laplace_table", gaps, *args, GAMMA, b["theta1_rad"], b["theta2_rad"]))
    f_ex = np.array([ex.solve(g, GAMMA)["force_neck"] for g in gaps])
    ferr = np.abs(f_tb / f_ex - 1)
    worst = int(np.argmax(ferr))
    row.update(refused=0, solver_min_force_over_max=float(f_ex.min() / f_ex.max()), rupture_solver_m=a_ex, rupture_table_m=a_tb, rupture_rel_error=abs(a_tb / a_ex - 1),
               transfer1_solver=transfer_ex, transfer1_table=transfer_tb, transfer_abs_error=abs(transfer_tb - transfer_ex),
               force_rel_error_max=float(ferr[worst]), force_worst_gap_fraction=float(gaps[worst] / a_ex),
               force_rel_errors=ferr)
    return row


def summarize(rows):
    """Median, 95th percentile and worst of each error, over all bridges and per part of the domain."""
    parts = {"all": lambda r: True, "vstar<=0.1": lambda r: r["vstar"] <= 0.1, "vstar>0.1": lambda r: r["vstar"] > 0.1,
             "wall": lambda r: math.isinf(r["R2_m"]) or math.isinf(r["R1_m"]), "spheres": lambda r: not (math.isinf(r["R2_m"]) or math.isinf(r["R1_m"])),
             "|theta1-theta2|<5deg": lambda r: abs(r["theta1_rad"] - r["theta2_rad"]) < math.radians(5)}
    out = []
    refused = [r for r in rows if r["refused"]]
    out.append(dict(part="refused as repulsive", quantity="bridges", n=len(refused), median=float("nan"), p95=float("nan"),
                    worst=max([r["solver_min_force_over_max"] for r in refused], default=float("nan"))))
    rows = [r for r in rows if not r["refused"]]
    for name, keep in parts.items():
        sel = [r for r in rows if keep(r)]
        if not sel:
            continue
        forces = np.concatenate([r["force_rel_errors"] for r in sel])
        for quantity, values in (("force", forces), ("rupture", np.array([r["rupture_rel_error"] for r in sel])),
                                 ("transfer", np.array([r["transfer_abs_error"] for r in sel]))):
            out.append(dict(part=name, quantity=quantity, n=len(values), median=float(np.median(values)),
                            p95=float(np.percentile(values, 95)), worst=float(values.max())))
    return out


def run(outdir, n, datadir=None, log=None):
    """Compare n seeded bridges; write outdir/points.csv and summary.csv (and datadir/accuracy.csv)."""
    os.makedirs(outdir, exist_ok=True)
    rows = []
    t0 = time.perf_counter()
    for i, b in enumerate(sample(n)):
        rows.append(compare(b))
        if log and (i + 1) % 200 == 0:
            log(i + 1, time.perf_counter() - t0)
    point_keys = [k for k in max(rows, key=len) if k != "force_rel_errors"]
    with open(os.path.join(outdir, "points.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=point_keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    summary = summarize(rows)
    for d in [outdir] + ([datadir] if datadir else []):
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, "summary.csv" if d == outdir else "accuracy.csv"), "w", newline="") as f:
            f.write("# young_laplace_table against the Young-Laplace solver: %d seeded bridges (seed %d) x %d gaps; "
                    "force and rupture: relative error, transfer: absolute error of the share [-]\n" % (n, SEED, GAPS_PER_BRIDGE))
            w = csv.DictWriter(f, fieldnames=list(summary[0]))
            w.writeheader()
            w.writerows(summary)
    return rows, summary
