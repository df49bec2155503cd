"""Analysis of shear-cell snapshots (plain numpy; no yade needed): time-averaged axisymmetric
coarse-graining, erf fits of the angular velocity, tau-p fit in the shear band, contact
statistics versus separation (Gladkyy 2014 eq. 15) and contact numbers. Conventions are written
into the outputs (see CONVENTIONS).

One pipeline: every snapshot is reduced to its coarse-grained fields on the analysis grid
(snapshot_fields: density, momentum, contact stress, momentum flux), the fields are averaged over
the snapshots and fitted (fit_fields). analyse() reduces the snapshots in memory; reduce_snapshot()
keeps a snapshot's fields on disk (what a run in segments keeps, shearcell.run_segment) and
analyse_reduced() fits those. Both take `more`, a function that adds entries to fits.json.
"""
import glob
import json
import os

import numpy as np

from . import cg, fits

CONVENTIONS = {
    "stress": "compression positive; contact part (line integral, wall contacts integrated to the contact point) + kinetic part",
    "kinetic_stress": "sum m v' (x) v' K, v' = v - V the fluctuation about the streaming velocity V = j/rho at the node "
                      "(Goldhirsch 2010; Weinhart et al. 2012): <K> - <j> (x) <j> / <rho> from the time-averaged momentum flux "
                      "K = sum m v (x) v K, momentum density j and density rho",
    "kernel": "Gaussian in (r, z) of width w = particle radius, normalised over 2 pi r dr dz",
    "time_average": "numerators and denominators averaged separately over the snapshots",
    "omega_ratio": "omega / Omega, omega = j_theta / (rho r)",
    "band_fit": "omega/Omega = 1/2 + 1/2 erf((r - Rc)/W) per height (Gladkyy 2014 eq. 13)",
    "gamma_dot": "sqrt((r d omega/dr)^2 + (r d omega/dz)^2), i.e. twice the norm of the (r theta, z theta) strain rate",
    "band": "mu, c: gamma_dot > 80 % of its maximum at that height; mu_threshold, c_threshold: gamma_dot > gamma_dot_min; "
            "both with density > 50 % of the bulk and z > 3 R",
    "tau_p": "tau = sqrt(sigma_rtheta^2 + sigma_ztheta^2), p = tr(sigma)/3; fit tau = mu p + c (Gladkyy 2014 eq. 14)",
    "contacts_vs_a": "a = surface separation (negative: overlap); bins of width (a_crit + delta_max)/100 (Gladkyy 2014 eq. 15); "
                     "all contacts per snapshot and their mean force, and per unit volume inside the band (with the mean force) "
                     "and in the bulk outside it, a contact placed at the middle of its branch",
    "torque": "torque_Nm: on the rotating walls from their contacts (z component about the axis, mean of the second half of the run)",
}
FIELDS = ("rho", "j", "sig_c", "S")  # the coarse-grained fields of a snapshot (snapshot_fields)


def analysis_grid(cfg):
    """The (r, z) grid of the analysis of a cell of configuration dict cfg: nodes R/2 apart, kernel width R."""
    R = cfg["R"]
    return cg.Grid(np.arange(cfg["Ri"] + R, cfg["Ro"] - R + 1e-12, R / 2), np.arange(R, cfg["H"] + 1e-12, R / 2), R)


def snapshot_fields(grid, d):
    """The coarse-grained fields of one snapshot (a dict of shearcell.snapshot's arrays) on `grid`: rho
    [kg/m^3], j (r, theta, z) [kg/(m^2 s)], the contact stress sig_c and the momentum flux S = sum m v (x) v K
    (3 x 3, cylindrical components) [Pa]."""
    rho, j = cg.density_and_momentum(grid, d["x"], d["v"], d["m"])
    return {"rho": rho, "j": j, "sig_c": cg.contact_stress(grid, d["xP"], d["xI"], d["F"]), "S": cg.momentum_flux(grid, d["x"], d["v"], d["m"])}


def average_fields(fields):
    """The mean of a list of snapshot_fields dicts (or of loaded reduced snapshots) over the snapshots, in float64."""
    return {k: np.mean([f[k].astype(float) for f in fields], axis=0) for k in FIELDS}


def stress(fields):
    """The stress [Pa] of (time-averaged) fields: contact part + kinetic part (cg.kinetic_stress)."""
    return fields["sig_c"] + cg.kinetic_stress(fields["rho"], fields["j"], fields["S"])


def fit_fields(grid, fields, run, gamma_dot_min=None, heights=5):
    """The fits of time-averaged fields (average_fields) of a run (its run.json dict): erf band fits at
    `heights` heights and the tau-p fit in the band (two selections). Returns a dict of the fits and the
    intermediate fields (sigma, omega, p, tau, gdot, ratio, and the masks bulk, away, band,
    band_threshold)."""
    cfg, R = run["cfg"], run["cfg"]["R"]
    rho, sigma = fields["rho"], stress(fields)
    omega = cg.angular_velocity(grid, rho, fields["j"])
    p, tau = cg.pressure_and_shear(sigma)
    gdot = cg.strain_rate(grid, np.nan_to_num(omega))
    ratio = omega / run["Omega_rad_s"]

    # erf fits at several heights in the bulk
    bulk = rho > 0.5 * np.nanmax(rho)
    zs = np.linspace(0.2, 0.7, heights) * cfg["H"]
    band_fits = []
    for z in zs:
        k = int(np.argmin(np.abs(grid.z - z)))
        try:
            f = fits.fit_band(grid.r[bulk[:, k]], ratio[bulk[:, k], k], Rc0=cfg["Rs"], W0=4 * R)
            band_fits.append(dict(f, z_m=float(grid.z[k])))
        except (ValueError, RuntimeError) as e:
            band_fits.append({"z_m": float(grid.z[k]), "error": str(e)})

    # Shear band, two selections (both away from the bottom, z > 3R, where the split itself shears
    # the layers that touch it, and from the free surface): 'relative', gamma_dot > 80 % of its
    # maximum at each height (Roy et al.), used for mu and c; 'threshold', gamma_dot > gamma_dot_min
    # (Gladkyy 2014: 0.12 1/s at a period of 100 s, scaled here with 1/period).
    gmin = gamma_dot_min if gamma_dot_min is not None else 0.12 * 100.0 / cfg["period"]
    away = bulk & (grid.Z > 3 * R)
    band = away & (gdot > 0.8 * np.nanmax(np.where(away, gdot, 0), axis=0)[None, :])
    band_threshold = away & (gdot > gmin)

    def yield_fit_of(sel):
        return fits.fit_yield(p[sel], tau[sel]) if sel.sum() >= 3 else {"error": "fewer than 3 band points"}

    return {"rho": rho, "sigma": sigma, "omega": omega, "p": p, "tau": tau, "gdot": gdot, "ratio": ratio, "bulk": bulk, "away": away,
            "band": band, "band_fits": band_fits, "gmin": gmin, "band_threshold": band_threshold, "yield": yield_fit_of(band),
            "yield_threshold": yield_fit_of(band_threshold)}


def fit_summary(run, f, snapshots):
    """The entries of fits.json common to analyse and analyse_reduced, from a run's run.json dict and its
    fit_fields dict f over `snapshots` snapshots."""
    y, yt, band_fits = f["yield"], f["yield_threshold"], f["band_fits"]
    return {
        "config": run["config"], "case": run["case"],
        "mu": y.get("mu"), "mu_err": y.get("mu_err"), "c_Pa": y.get("c_Pa"), "c_err_Pa": y.get("c_err_Pa"),
        "band_points": int(f["band"].sum()), "gamma_dot_min_1_s": f["gmin"], "band_points_threshold": int(f["band_threshold"].sum()),
        "mu_threshold": yt.get("mu"), "mu_err_threshold": yt.get("mu_err"), "c_Pa_threshold": yt.get("c_Pa"), "c_err_Pa_threshold": yt.get("c_err_Pa"),
        "Rc_m": [b.get("Rc_m") for b in band_fits], "W_m": [b.get("W_m") for b in band_fits], "band_fits": band_fits,
        "torque_Nm": run["torque_rotating_Nm"], "torque_static_Nm": run["torque_static_Nm"],
        "particle_steps_per_s": run["particle_steps_per_s"], "snapshots": snapshots,
    }


def _add_more(out, more, *args):
    """out updated with more(*args), whose "conventions" entry, if any, adds to out's conventions."""
    if more is not None:
        extra = dict(more(*args))
        out["conventions"].update(extra.pop("conventions", {}))
        out.update(extra)
    return out


def _write_fits(outdir, out):
    with open(os.path.join(outdir, "fits.json"), "w") as fh:
        json.dump(out, fh, indent=1, default=float)


def analyse(rundir, gamma_dot_min=None, heights=5, more=None):
    """Analyse run directory `rundir` (run.json, torque.csv, snap_*.npz); writes fits.json,
    profiles.csv, contacts_vs_a.csv and PNG plots there; returns the fits dict. more(f, data): further
    entries of fits.json from the fit_fields dict f and the loaded snapshots `data` (a list of dicts); its
    "conventions" entry adds to the conventions."""
    with open(os.path.join(rundir, "run.json")) as fh:
        run = json.load(fh)
    cfg = run["cfg"]
    snaps = sorted(glob.glob(os.path.join(rundir, "snap_*.npz")))
    if not snaps:
        raise ValueError("analyse: no snapshots in %s" % rundir)
    grid = analysis_grid(cfg)
    data = [dict(np.load(s)) for s in snaps]  # decompressed once (an NpzFile decompresses at every access)
    f = fit_fields(grid, average_fields([snapshot_fields(grid, d) for d in data]), run, gamma_dot_min, heights)
    band, bulk = f["band"], f["bulk"]

    # contacts and mean force versus separation (Gladkyy eq. 15), wet-contact density in and out of the band
    gaps = np.concatenate([d["gap"] for d in data])
    forces = np.concatenate([np.linalg.norm(d["F"], axis=1) for d in data])
    a_crit = max(gaps.max(), 0) if len(gaps) else 0
    delta_max = max(-gaps.min(), 0) if len(gaps) else 0
    width = (a_crit + delta_max) / 100 if a_crit + delta_max > 0 else 1e-6
    edges = np.arange(-delta_max, a_crit + width, width)
    counts, _ = np.histogram(gaps, edges)
    fsum, _ = np.histogram(gaps, edges, weights=forces)
    centers = (edges[:-1] + edges[1:]) / 2
    # The same inside the band and in the bulk outside it (Gladkyy Fig. 9-10: contact number and mean
    # force against the gap in the band; wet-contact density in and out of it), per unit volume.
    where = np.concatenate([_region(d, grid, band, bulk) for d in data])
    n_in, _ = np.histogram(gaps[where == 1], edges)
    f_in, _ = np.histogram(gaps[where == 1], edges, weights=forces[where == 1])
    n_out, _ = np.histogram(gaps[where == 2], edges)
    _write_contacts_vs_a(rundir, grid, band, bulk, centers, np.stack([counts, fsum, n_in, f_in, n_out]), len(data))
    wet_in, wet_out = _wet_density(data, grid, band, bulk, cfg)

    out = dict(fit_summary(run, f, len(data)), wet_contact_density_band_1_m3=wet_in, wet_contact_density_outside_1_m3=wet_out,
               contact_numbers=contact_numbers(data), conventions=dict(CONVENTIONS))
    _add_more(out, more, f, data)
    _write_fits(rundir, out)
    _write_profiles(rundir, grid, f, cfg)
    _contact_plot(rundir, centers, counts / len(data), np.where(counts > 0, fsum / np.maximum(counts, 1), np.nan))
    return out


def reduce_snapshot(snap_path, cfg, out_path, more=None):
    """The coarse-grained fields of one snapshot on the analysis grid of cfg (snapshot_fields), in float32,
    written to out_path (npz; about 1 MB for Gladkyy's cell, where a snapshot is about 40 MB), with t and
    the contact numbers, and the contacts against the gap (gap_n, gap_f: count and sum of |F| per coarse
    cell and gap bin, the last row for all contacts, on the grid or not; gap_outside: contacts beyond the
    bins' range). What analyse_reduced averages, for runs whose snapshots are taken in several segments
    and do not outlive them. more(d, cfg): further arrays to keep, from the snapshot's dict d."""
    d = dict(np.load(snap_path))
    grid = analysis_grid(cfg)
    fields = snapshot_fields(grid, d)
    contacts = contact_numbers([d])
    edges = gap_edges(cfg)
    cells = int(np.prod(_coarse_shape(grid)))
    cell = _coarse_cells(grid, (d["xP"] + d["xI"]) / 2) if len(d["gap"]) else np.zeros(0, int)
    cell = np.where(cell < 0, cells, cell)  # off the grid: counted in the last row only
    b = np.searchsorted(edges, d["gap"], side="left") - 1  # bins (lo, hi]: a = 0 is a contact, as in contact_numbers
    inside = (b >= 0) & (b < len(edges) - 1)
    force = np.linalg.norm(d["F"], axis=1) if len(d["gap"]) else np.zeros(0)
    gap_n = np.zeros((cells + 1, len(edges) - 1))
    gap_f = np.zeros_like(gap_n)
    np.add.at(gap_n, (cell[inside], b[inside]), 1.0)
    np.add.at(gap_f, (cell[inside], b[inside]), force[inside])
    gap_n[cells] += gap_n[:cells].sum(axis=0)
    gap_f[cells] += gap_f[:cells].sum(axis=0)
    extra = more(d, cfg) if more is not None else {}
    tmp = out_path + ".tmp"
    with open(tmp, "wb") as fh:
        np.savez_compressed(fh, **{k: v.astype(np.float32) for k, v in fields.items()}, t=float(d["t"]),
                            mechanical_per_particle=contacts["mechanical_per_particle"],
                            separated_bridges_per_particle=contacts["separated_bridges_per_particle"],
                            gap_n=gap_n.astype(np.int32), gap_f=gap_f.astype(np.float32), gap_outside=int((~inside).sum()), **extra)
    os.replace(tmp, out_path)


def load_reduced(rundir):
    """The reduced snapshots cg_*.npz of rundir (reduce_snapshot), loaded as dicts in the order of their names."""
    files = sorted(glob.glob(os.path.join(rundir, "cg_*.npz")))
    if not files:
        raise ValueError("no reduced snapshots (cg_*.npz) in %s" % rundir)
    return [dict(np.load(f)) for f in files]


def analyse_reduced(rundir, gamma_dot_min=None, heights=5, outdir=None, run=None, more=None):
    """analyse() from the reduced snapshots cg_*.npz of rundir (reduce_snapshot) and its run.json:
    the same fields, fits and profiles (to float32 round-off of the fields), the contacts against the
    gap in fixed bins (see reduce_snapshot) and the contact numbers. outdir: where fits.json and the
    profiles go (default rundir); run: the run's dict instead of rundir/run.json (interim). more(f, red):
    further entries of fits.json from the fit_fields dict f and the loaded reduced snapshots `red` (as in
    analyse)."""
    if run is None:
        with open(os.path.join(rundir, "run.json")) as fh:
            run = json.load(fh)
    outdir = rundir if outdir is None else outdir
    cfg = run["cfg"]
    grid = analysis_grid(cfg)
    red = load_reduced(rundir)
    f = fit_fields(grid, average_fields(red), run, gamma_dot_min, heights)
    mech = [float(r["mechanical_per_particle"]) for r in red]
    out = dict(fit_summary(run, f, len(red)),
               contact_numbers={"mechanical_per_particle": float(np.mean(mech)), "mechanical_std": float(np.std(mech)),
                                "separated_bridges_per_particle": float(np.mean([float(r["separated_bridges_per_particle"]) for r in red]))},
               conventions=dict(CONVENTIONS, torque="torque_Nm: on the rotating walls from their contacts, mean of the second half of the run",
                                contacts_vs_a="as analyse, in fixed bins of %g R from %g R to %g R; a contact is in the band by the "
                                              "share of band nodes in its coarse cell of %d x %d nodes" % (GAP_BIN_R, GAP_RANGE_R[0] * GAP_BIN_R,
                                                                                                     GAP_RANGE_R[1] * GAP_BIN_R, COARSE, COARSE)))
    if all("gap_n" in r for r in red):
        out.update(_reduced_contacts(outdir, grid, red, f["band"], f["bulk"], cfg))
    else:
        out["conventions"].pop("contacts_vs_a")
    _add_more(out, more, f, red)
    _write_fits(outdir, out)
    _write_profiles(outdir, grid, f, cfg)
    return out


def _write_contacts_vs_a(rundir, grid, band, bulk, centers, h, snapshots):
    """contacts_vs_a.csv from the histograms h over the bins `centers` [m], summed over `snapshots`:
    h[0] all contacts, h[1] the sum of their |F|, h[2], h[3] the same of the contacts in the band,
    h[4] the contacts in the bulk outside it."""
    cell_vol = grid.volume_elements()
    v_in, v_out = cell_vol[band].sum(), cell_vol[bulk & ~band].sum()
    counts, fsum, n_in, f_in, n_out = h
    np.savetxt(os.path.join(rundir, "contacts_vs_a.csv"),
               np.stack([centers, counts / snapshots, np.where(counts > 0, fsum / np.where(counts > 0, counts, 1), np.nan),
                         n_in / snapshots / v_in if v_in > 0 else np.full(len(centers), np.nan),
                         np.where(n_in > 0, f_in / np.where(n_in > 0, n_in, 1), np.nan),
                         n_out / snapshots / v_out if v_out > 0 else np.full(len(centers), np.nan)], axis=1), delimiter=",",
               header="a_m,contacts_per_snapshot,mean_force_N,band_contacts_per_m3,band_mean_force_N,outside_contacts_per_m3", comments="")


# Reduced snapshots keep the contacts against the gap a in fixed bins of GAP_BIN_R R from GAP_RANGE_R[0] R to
# GAP_RANGE_R[1] R (an edge at a = 0 exactly; the rupture distance of 74.2 nl at R = 2.381 mm is 0.18 R), per
# coarse cell of COARSE x COARSE analysis nodes (2R x 2R), so that the band chosen later from the averaged
# fields can select them.
GAP_BIN_R, GAP_RANGE_R, COARSE = 1e-3, (-50, 250), 4


def gap_edges(cfg):
    """The fixed bin edges of the reduced contact histograms [m]."""
    return np.arange(GAP_RANGE_R[0], GAP_RANGE_R[1] + 1) * GAP_BIN_R * cfg["R"]


def _coarse_shape(grid):
    """Coarse cells (COARSE x COARSE nodes, the last ones in r and z possibly partial) in r and in z."""
    return -(-len(grid.r) // COARSE), -(-len(grid.z) // COARSE)


def _coarse_cells(grid, points):
    """The coarse cell (index ic * cells in z + kc) of the nearest analysis node of each point, -1 off the grid."""
    on, i, k = _nearest_node(grid, points)
    return np.where(on, (i // COARSE) * _coarse_shape(grid)[1] + k // COARSE, -1)


def _reduced_contacts(rundir, grid, red, band, bulk, cfg):
    """contacts_vs_a.csv and the wet-contact densities from the reduced histograms (reduce_snapshot): a
    coarse cell's contacts count for the band and for the bulk outside it by the volume shares of its
    nodes there. Returns the entries of fits.json."""
    vol = grid.volume_elements()
    nr, nz = _coarse_shape(grid)

    def per_cell(v):  # node values summed over each coarse cell, in _coarse_cells' order
        padded = np.zeros((nr * COARSE, nz * COARSE))
        padded[:v.shape[0], :v.shape[1]] = v
        return padded.reshape(nr, COARSE, nz, COARSE).sum(axis=(1, 3)).ravel()

    share = np.stack([per_cell(np.where(m, vol, 0.0)) for m in (band, bulk & ~band)]) / np.maximum(per_cell(vol), 1e-300)
    n = np.sum([r["gap_n"] for r in red], axis=0, dtype=float)
    fsum = np.sum([r["gap_f"] for r in red], axis=0, dtype=float)
    edges = gap_edges(cfg)
    h = np.stack([n[-1], fsum[-1], share[0] @ n[:-1], share[0] @ fsum[:-1], share[1] @ n[:-1]])
    _write_contacts_vs_a(rundir, grid, band, bulk, (edges[:-1] + edges[1:]) / 2, h, len(red))
    v_in, v_out = vol[band].sum(), vol[bulk & ~band].sum()
    separated = edges[:-1] >= 0  # bins (lo, hi] above a = 0: a > 0, as _wet_density
    return {"wet_contact_density_band_1_m3": float(h[2][separated].sum() / len(red) / v_in) if v_in > 0 else None,
            "wet_contact_density_outside_1_m3": float(h[4][separated].sum() / len(red) / v_out) if v_out > 0 else None,
            "contacts_beyond_gap_bins_per_snapshot": float(np.mean([int(r["gap_outside"]) for r in red]))}


def contact_numbers(data):
    """Mechanical contacts (overlap, gap <= 0) and separated bridges (gap > 0) per flowing sphere,
    averaged over the snapshots (Gladkyy 2014 section 4.2: about 20 % more mechanical contacts wet
    than dry). A contact between two flowing spheres counts for both, a wall contact for one."""
    mech, sep = [], []
    for d in data:
        n = len(d["m"])
        if len(d["gap"]) == 0:
            mech.append(0.0), sep.append(0.0)
            continue
        weight = np.where(wall_contact_mask(d), 1.0, 2.0)
        mech.append(float(weight[d["gap"] <= 0].sum()) / n)
        sep.append(float(weight[d["gap"] > 0].sum()) / n)
    return {"mechanical_per_particle": float(np.mean(mech)), "mechanical_std": float(np.std(mech)),
            "separated_bridges_per_particle": float(np.mean(sep))}


def wall_contact_mask(d):
    """Which contacts of snapshot d are with a wall sphere: their partner point xI is a contact point,
    not the (exactly copied) position of a flowing sphere."""
    if "_wall" not in d:  # cached in the snapshot's dict
        rows = np.dtype((np.void, 3 * np.dtype(float).itemsize))
        x, xI = (np.ascontiguousarray(d[k], dtype=float).reshape(-1, 3).view(rows).ravel() for k in ("x", "xI"))
        d["_wall"] = ~np.isin(xI, x)
    return d["_wall"]


def _region(d, grid, band, bulk):
    """For every contact of snapshot d: 1 if the middle of its branch lies in the band, 2 in the bulk
    outside it, 0 elsewhere, also off the grid by more than half a node spacing (the nearest grid
    node decides)."""
    if len(d["gap"]) == 0:
        return np.zeros(0, int)
    on, i, k = _nearest_node(grid, (d["xP"] + d["xI"]) / 2)
    return np.where(on & band[i, k], 1, np.where(on & bulk[i, k], 2, 0))


def _nearest_node(grid, points):
    """For points (n, 3): whether each lies on the grid (within half a node spacing of it) and the (i, k)
    of its nearest node."""
    dr, dz = grid.r[1] - grid.r[0], grid.z[1] - grid.z[0]
    fi, fk = (np.hypot(points[:, 0], points[:, 1]) - grid.r[0]) / dr, (points[:, 2] - grid.z[0]) / dz
    on = (fi > -0.5) & (fi < len(grid.r) - 0.5) & (fk > -0.5) & (fk < len(grid.z) - 0.5)
    i = np.clip(np.round(fi).astype(int), 0, len(grid.r) - 1)
    k = np.clip(np.round(fk).astype(int), 0, len(grid.z) - 1)
    return on, i, k


def _wet_density(data, grid, band, bulk, cfg):
    """Contacts with a bridge and a gap (a > 0) per volume, inside and outside the band [1/m^3]."""
    cell_vol = grid.volume_elements()
    n_in = n_out = 0
    for d in data:
        where, wet = _region(d, grid, band, bulk), d["gap"] > 0
        n_in += np.sum(wet & (where == 1))
        n_out += np.sum(wet & (where == 2))
    v_in, v_out = cell_vol[band].sum(), cell_vol[bulk & ~band].sum()
    return (n_in / len(data) / v_in if v_in > 0 else None), (n_out / len(data) / v_out if v_out > 0 else None)


def _plots(rundir, grid, ratio, bulk, band_fits, p, tau, band, yield_fit, cfg):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    for b in band_fits:
        k = int(np.argmin(np.abs(grid.z - b["z_m"])))
        line, = ax[0].plot(grid.r[bulk[:, k]] * 1e3, ratio[bulk[:, k], k], ".", ms=3, label="z = %.1f mm" % (b["z_m"] * 1e3))
        if "Rc_m" in b:
            ax[0].plot(grid.r * 1e3, fits.erf_profile(grid.r, b["Rc_m"], b["W_m"]), "-", color=line.get_color(), lw=1)
    ax[0].axvline(cfg["Rs"] * 1e3, color="k", ls=":", lw=0.8)
    ax[0].set_xlabel("r [mm]")
    ax[0].set_ylabel("omega / Omega")
    ax[0].legend(fontsize=7)
    ax[1].plot(p[band], tau[band], ".", ms=3)
    if "mu" in yield_fit:
        pp = np.linspace(0, np.nanmax(p[band]) if band.any() else 1, 10)
        ax[1].plot(pp, yield_fit["mu"] * pp + yield_fit["c_Pa"], "r-",
                   label="mu = %.3f +- %.3f, c = %.2f +- %.2f Pa" % (yield_fit["mu"], yield_fit["mu_err"], yield_fit["c_Pa"], yield_fit["c_err_Pa"]))
        ax[1].legend(fontsize=7)
    ax[1].set_xlabel("p [Pa]")
    ax[1].set_ylabel("tau [Pa]")
    fig.tight_layout()
    fig.savefig(os.path.join(rundir, "profiles.png"), dpi=110)
    plt.close(fig)


def _contact_plot(rundir, a, n, f):
    """Contact number and mean force versus separation a (as Gladkyy 2014 Fig. 9)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    ax[0].plot(a * 1e6, n, "-")
    ax[0].set_ylabel("contacts per snapshot")
    ax[1].plot(a * 1e6, f * 1e3, "-")
    ax[1].set_ylabel("mean |F| [mN]")
    ax[1].set_xlabel("separation a [um] (negative: overlap)")
    for x in ax:
        x.axvline(0, color="k", lw=0.6)
        x.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(os.path.join(rundir, "contacts_vs_a.png"), dpi=110)
    plt.close(fig)


def _write_profiles(rundir, grid, f, cfg):
    rho = f["rho"]
    header = "r_m,z_m,rho_kg_m3,omega_over_Omega,gamma_dot_1_s,p_Pa,tau_Pa,in_band"
    np.savetxt(os.path.join(rundir, "profiles.csv"),
               np.stack([grid.R.ravel(), grid.Z.ravel(), rho.ravel(), f["ratio"].ravel(), f["gdot"].ravel(), f["p"].ravel(), f["tau"].ravel(),
                         f["band"].ravel()], axis=1), delimiter=",", header=header, comments="", fmt="%.10g")  # 10 digits: under 2 MB at Gladkyy's size
    _plots(rundir, grid, f["ratio"], f["bulk"], f["band_fits"], f["p"], f["tau"], f["band"], f["yield"], cfg)


def interim(keep, outdir=None, heights=5, more=None):
    """The fits of a run in segments before it ends (analyse_reduced of its reduced snapshots so far),
    from what run_segment keeps in `keep`: state.npz (configuration, progress), torque.csv and
    cg_*.npz. The torques are the means of the records since the first snapshot (those of the second
    half of the run when it ends; None before the first save after it). Writes fits.json, profiles and run.json to outdir (default
    keep/interim); heights, more: as analyse_reduced. Returns the fits with done_steps, steps and t_s of the run so far."""
    outdir = os.path.join(keep, "interim") if outdir is None else outdir
    with np.load(os.path.join(keep, "state.npz")) as d:
        meta, flowing = json.loads(str(d["meta"])), len(d["ids_flowing"])
    files = sorted(glob.glob(os.path.join(keep, "cg_*.npz")))
    if not files:
        raise ValueError("interim: no reduced snapshots (cg_*.npz) in %s yet" % keep)
    with np.load(files[0]) as first:
        t_first = float(first["t"])
    T = np.loadtxt(os.path.join(keep, "torque.csv"), delimiter=",", skiprows=1, ndmin=2)
    late = T[T[:, 0] >= t_first - 1e-9]
    cfg = meta["cfg"]
    steps = int(cfg["run_s"] / meta["dt_s"])
    # torque.csv grows at each save: until the first save after the first snapshot there is no record yet
    run = {"cfg": cfg, "config": meta["config"], "case": meta["case"], "Omega_rad_s": 2 * np.pi / cfg["period"], "steps": steps,
           "torque_rotating_Nm": float(late[:, 1].mean()) if len(late) else None, "torque_static_Nm": float(late[:, 2].mean()) if len(late) else None,
           "particle_steps_per_s": flowing * meta["done_steps"] / meta["wall_s"] if meta.get("wall_s") else 0.0}
    os.makedirs(outdir, exist_ok=True)
    with open(os.path.join(outdir, "run.json"), "w") as f:
        json.dump(dict(run, done_steps=meta["done_steps"], t_s=meta["time_s"]), f, indent=1)
    out = analyse_reduced(keep, heights=heights, outdir=outdir, run=run, more=more)
    return dict(out, done_steps=meta["done_steps"], steps=steps, t_s=meta["time_s"])
