"""Analysis of shear-cell snapshots (plain numpy; no yade needed): time-averaged axisymmetric
coarse-graining, erf fits of the angular velocity, tau-p fit in the shear band, contact
statistics versus separation (Gladkyy 2014 eq. 15), torques. Conventions are written into the
outputs (see CONVENTIONS).
"""
import glob
import json
import os

import numpy as np

from . import cg, fits

CONVENTIONS = {
    "stress": "compression positive; contact part (line integral, wall contacts integrated to the contact point) + kinetic part",
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
    "torque": "torque_Nm: on the rotating walls from their contacts (z component about the axis, mean of the second half of "
              "the run); torque_cg_at_Rs_Nm: 2 pi Rs^2 times the integral of sigma_r_theta over z on the cylinder r = Rs, "
              "from 3 kernel widths below the bottom to 3 above the highest particle; lower than torque_Nm because the "
              "kernel averages the torque flux over r around Rs, where it peaks, and bottom contacts straddling the split "
              "pass torque to the static bottom outside Rs (ci, dry: 74 % of torque_Nm with w = R, 83 % with w = R/4); "
              "torque_cg_at_Rs_w4_Nm: the same with w/4; torque_closure: the balance of cylinders r0, see torque_closure()",
}


# Gladkyy 2014 §4.1: "tau = mu p + c ... with mu = 0.13 for the particular granular material", one slope
# for the dry and the wet materials (his Fig. 7), c per liquid content.
GLADKYY_MU = 0.13
# Gladkyy 2014 §4.2: band centres and widths "obtained for 13 different heights" (Fig. 6; which heights
# is not stated: here evenly from 0.2 to 0.7 of the bed height, as for the 5 heights of the smaller cells).
GLADKYY_HEIGHTS = 13


def analysis_grid(cfg):
    """The (r, z) grid of the analysis of a cell of configuration dict cfg: nodes R/2 apart, kernel width R."""
    R = cfg["R"]
    return cg.Grid(np.arange(cfg["Ri"] + R, cfg["Ro"] - R + 1e-12, R / 2), np.arange(R, cfg["H"] + 1e-12, R / 2), R)


def _omega_lookup(grid, omega):
    """omega at points (r, z): the value of the nearest node at or above (searchsorted), 0 where NaN."""
    def omega_at(r, z):
        i = np.clip(np.searchsorted(grid.r, r), 0, len(grid.r) - 1)
        k = np.clip(np.searchsorted(grid.z, z), 0, len(grid.z) - 1)
        return np.nan_to_num(omega[i, k])
    return omega_at


def _fit_fields(grid, rho, sigma, omega, cfg, Omega, gamma_dot_min, heights):
    """The fits of time-averaged CG fields: erf band fits at `heights` heights, the tau-p fit in the band
    (two selections) and its variants. Returns a dict of the fits and the intermediate fields."""
    R = cfg["R"]
    p, tau = cg.pressure_and_shear(sigma)
    gdot = cg.strain_rate(grid, np.nan_to_num(omega))
    ratio = omega / Omega

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

    return {"p": p, "tau": tau, "gdot": gdot, "ratio": ratio, "bulk": bulk, "band": band, "band_fits": band_fits, "gmin": gmin,
            "band_threshold": band_threshold, "yield": yield_fit_of(band), "yield_threshold": yield_fit_of(band_threshold),
            "variants": fit_variants(sigma, gdot, away, gmin)}


def _fit_summary(run, f, snapshots):
    """The entries of fits.json common to analyse and analyse_reduced."""
    y, yt, band_fits = f["yield"], f["yield_threshold"], f["band_fits"]
    return {
        "config": run["config"], "case": run["case"],
        "mu": y.get("mu"), "mu_err": y.get("mu_err"), "c_Pa": y.get("c_Pa"), "c_err_Pa": y.get("c_err_Pa"),
        "band_points": int(f["band"].sum()), "gamma_dot_min_1_s": f["gmin"], "band_points_threshold": int(f["band_threshold"].sum()),
        "mu_threshold": yt.get("mu"), "mu_err_threshold": yt.get("mu_err"), "c_Pa_threshold": yt.get("c_Pa"), "c_err_Pa_threshold": yt.get("c_err_Pa"),
        "Rc_m": [b.get("Rc_m") for b in band_fits], "W_m": [b.get("W_m") for b in band_fits], "band_fits": band_fits,
        "torque_Nm": run["torque_rotating_Nm"], "torque_static_Nm": run["torque_static_Nm"], "fit_variants": f["variants"],
        "particle_steps_per_s": run["particle_steps_per_s"], "snapshots": snapshots,
    }


def _write_profiles(rundir, grid, rho, f, cfg):
    header = "r_m,z_m,rho_kg_m3,omega_over_Omega,gamma_dot_1_s,p_Pa,tau_Pa,in_band"
    np.savetxt(os.path.join(rundir, "profiles.csv"),
               np.stack([grid.R.ravel(), grid.Z.ravel(), rho.ravel(), f["ratio"].ravel(), f["gdot"].ravel(), f["p"].ravel(), f["tau"].ravel(),
                         f["band"].ravel()], axis=1), delimiter=",", header=header, comments="", fmt="%.10g")  # 10 digits: under 2 MB at Gladkyy's size
    _plots(rundir, grid, f["ratio"], f["bulk"], f["band_fits"], f["p"], f["tau"], f["band"], f["yield"], cfg)


def analyse(rundir, gamma_dot_min=None, heights=5):
    """Analyse run directory `rundir` (run.json, torque.csv, snap_*.npz); writes fits.json,
    profiles.csv, contacts_vs_a.csv and PNG plots there; returns the fits dict."""
    with open(os.path.join(rundir, "run.json")) as f:
        run = json.load(f)
    cfg = run["cfg"]
    Omega = run["Omega_rad_s"]
    snaps = sorted(glob.glob(os.path.join(rundir, "snap_*.npz")))
    if not snaps:
        raise ValueError("analyse: no snapshots in %s" % rundir)
    grid = analysis_grid(cfg)
    rho = np.zeros_like(grid.R)
    j = np.zeros((3,) + grid.R.shape)
    sig_c = np.zeros((3, 3) + grid.R.shape)
    data = [dict(np.load(s)) for s in snaps]  # decompressed once (an NpzFile decompresses at every access)
    for d in data:
        r_, j_ = cg.density_and_momentum(grid, d["x"], d["v"], d["m"])
        rho += r_ / len(data)
        j += j_ / len(data)
        sig_c += cg.contact_stress(grid, d["xP"], d["xI"], d["F"]) / len(data)
    omega = cg.angular_velocity(grid, rho, j)
    omega_at = _omega_lookup(grid, omega)
    sig_k = sum(cg.kinetic_stress(grid, d["x"], d["v"], d["m"], omega_at) for d in data) / len(data)
    f = _fit_fields(grid, rho, sig_c + sig_k, omega, cfg, Omega, gamma_dot_min, heights)
    band, bulk = f["band"], f["bulk"]

    torque_cg = cylinder_flux(data, cfg["Rs"], grid.w, omega_at)
    torque_cg_narrow = cylinder_flux(data, cfg["Rs"], grid.w / 4, omega_at)
    closure = torque_closure(data, cfg, grid.w, omega_at)

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
    contacts = contact_numbers(data)

    out = dict(_fit_summary(run, f, len(data)), torque_cg_at_Rs_Nm=torque_cg, torque_cg_at_Rs_w4_Nm=torque_cg_narrow,
               wet_contact_density_band_1_m3=wet_in, wet_contact_density_outside_1_m3=wet_out, torque_closure=closure,
               contact_numbers=contacts, conventions=CONVENTIONS)
    with open(os.path.join(rundir, "fits.json"), "w") as fh:
        json.dump(out, fh, indent=1, default=float)
    _write_profiles(rundir, grid, rho, f, cfg)
    _contact_plot(rundir, centers, counts / len(data), np.where(counts > 0, fsum / np.maximum(counts, 1), np.nan))
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


def closure_radii(cfg, step_over_R=2.0):
    """The cylinders r0 [m] of the torque balance: from the inner wall to beyond the split, step_over_R R apart."""
    return np.arange(cfg["Ri"] + step_over_R * cfg["R"], cfg["Rs"] + 3 * cfg["R"], step_over_R * cfg["R"])


def _coarse_shape(grid):
    """Coarse cells (COARSE x COARSE nodes, the last ones in r and z possibly partial) in r and in z."""
    return -(-len(grid.r) // COARSE), -(-len(grid.z) // COARSE)


def _coarse_cells(grid, points):
    """The coarse cell (index ic * cells in z + kc) of the nearest analysis node of each point, -1 off the grid."""
    on, i, k = _nearest_node(grid, points)
    return np.where(on, (i // COARSE) * _coarse_shape(grid)[1] + k // COARSE, -1)


def reduce_snapshot(snap_path, cfg, out_path):
    """The coarse-grained fields of one snapshot on the analysis grid of cfg, in float32, written to
    out_path (npz; about 1 MB for Gladkyy's cell, where a snapshot is about 40 MB): rho, j (r, theta,
    z), sig_c (3 x 3) and the kinetic moment S = sum m v (x) v K (3 x 3; cylindrical components), t,
    and the contact numbers; the contacts against the gap (gap_n, gap_f: count and sum of |F| per coarse
    cell and gap bin, the last row for all contacts, on the grid or not; gap_outside: contacts beyond
    the bins' range) and the torque balance of the cylinders closure_radii(cfg) counted contact by
    contact (closure_walls: walls_inside by contact point and by centre, closure_crossing:
    crossing_torque; snapshots with the wall torques only). What analyse_reduced averages, for runs
    whose snapshots are taken in several segments and do not outlive them."""
    d = dict(np.load(snap_path))
    grid = analysis_grid(cfg)
    rho, j = cg.density_and_momentum(grid, d["x"], d["v"], d["m"])
    sig_c = cg.contact_stress(grid, d["xP"], d["xI"], d["F"])
    S = cg.kinetic_stress(grid, d["x"], d["v"], d["m"], lambda r, z: np.zeros_like(r))
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
    extra = {}
    if "static_Tz" in d:
        r0s = closure_radii(cfg)
        extra = {"closure_walls": np.array([walls_inside([d], r0) for r0 in r0s]), "closure_crossing": np.array([crossing_torque([d], r0) for r0 in r0s])}
    tmp = out_path + ".tmp"
    with open(tmp, "wb") as f:
        np.savez_compressed(f, rho=rho.astype(np.float32), j=j.astype(np.float32), sig_c=sig_c.astype(np.float32), S=S.astype(np.float32),
                            t=float(d["t"]), mechanical_per_particle=contacts["mechanical_per_particle"],
                            separated_bridges_per_particle=contacts["separated_bridges_per_particle"],
                            gap_n=gap_n.astype(np.int32), gap_f=gap_f.astype(np.float32), gap_outside=int((~inside).sum()), **extra)
    os.replace(tmp, out_path)


def analyse_reduced(rundir, gamma_dot_min=None, heights=5, outdir=None, run=None):
    """analyse() from the reduced snapshots cg_*.npz of rundir (reduce_snapshot) and its run.json:
    the same fits (mu, c and their variants, band centres and widths), profiles, contacts against the
    gap (fixed bins, see reduce_snapshot) and the torque balance of cylinders counted contact by contact;
    not the CG torque fluxes, which need every contact. The kinetic stress is taken relative to the mean
    velocity at the grid node (Weinhart et al. 2012: <S> - j U - U j + rho U U, U = omega r e_theta)
    instead of at each particle: the two differ by the kernel average of (omega(r_i) - omega(r))^2 r^2,
    second order in the kernel width. outdir: where fits.json and the profiles go (default rundir);
    run: the run's dict instead of rundir/run.json (interim)."""
    if run is None:
        with open(os.path.join(rundir, "run.json")) as f:
            run = json.load(f)
    outdir = rundir if outdir is None else outdir
    cfg = run["cfg"]
    files = sorted(glob.glob(os.path.join(rundir, "cg_*.npz")))
    if not files:
        raise ValueError("analyse_reduced: no reduced snapshots (cg_*.npz) in %s" % rundir)
    grid = analysis_grid(cfg)
    red = [dict(np.load(f)) for f in files]
    rho, f = _fit_reduced(grid, red, run, gamma_dot_min, heights)
    mech = [float(r["mechanical_per_particle"]) for r in red]
    out = dict(_fit_summary(run, f, len(red)),
               contact_numbers={"mechanical_per_particle": float(np.mean(mech)), "mechanical_std": float(np.std(mech)),
                                "separated_bridges_per_particle": float(np.mean([float(r["separated_bridges_per_particle"]) for r in red]))},
               conventions=dict(CONVENTIONS, kinetic_stress="relative to the mean velocity at the grid node (analyse_reduced)",
                                torque="torque_Nm: on the rotating walls from their contacts, mean of the second half of the run; "
                                       "torque_closure: contact by contact only (the CG flux needs every contact)",
                                contacts_vs_a="as analyse, in fixed bins of %g R from %g R to %g R; a contact is in the band by the "
                                              "share of band nodes in its coarse cell of %d x %d nodes" % (GAP_BIN_R, GAP_RANGE_R[0] * GAP_BIN_R,
                                                                                                     GAP_RANGE_R[1] * GAP_BIN_R, COARSE, COARSE)))
    if all("gap_n" in r for r in red):
        out.update(_reduced_contacts(outdir, grid, red, f["band"], f["bulk"], cfg))
    else:
        out["conventions"].pop("contacts_vs_a")
    if all("closure_walls" in r for r in red):
        walls = np.mean([r["closure_walls"] for r in red], axis=0)
        crossing = np.mean([r["closure_crossing"] for r in red], axis=0)
        out["torque_closure"] = [{"r0_m": float(r0), "walls_inside_Nm": float(w[0]), "walls_centre_inside_Nm": float(w[1]), "crossing_Nm": float(c),
                                  "crossing_over_walls": float(c / w[0]) if w[0] else None, "cg_w_over_walls": None, "cg_w4_over_walls": None}
                                 for r0, w, c in zip(closure_radii(cfg), walls, crossing)]
    with open(os.path.join(outdir, "fits.json"), "w") as fh:
        json.dump(out, fh, indent=1, default=float)
    _write_profiles(outdir, grid, rho, f, cfg)
    return out


def interim(keep, outdir=None, heights=5):
    """The fits of a run in segments before it ends (analyse_reduced of its reduced snapshots so far),
    from what run_segment keeps in `keep`: state.npz (configuration, progress), torque.csv and
    cg_*.npz. The torques are the means of the records since the first snapshot (those of the second
    half of the run when it ends; None before the first save after it). Writes fits.json, profiles and run.json to outdir (default
    keep/interim); heights: of the band fits (analyse_reduced). Returns the fits with done_steps, steps and t_s of the run so far."""
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
    out = analyse_reduced(keep, heights=heights, outdir=outdir, run=run)
    return dict(out, done_steps=meta["done_steps"], steps=steps, t_s=meta["time_s"])


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


def _fit_reduced(grid, red, run, gamma_dot_min=None, heights=5):
    """The fits of the reduced snapshots `red` (loaded cg_*.npz dicts) of a run (its run.json dict):
    their fields averaged, the kinetic stress relative to the mean velocity at the node (see
    analyse_reduced); returns (rho, the _fit_fields dict)."""
    rho, j, sig_c, S = (np.mean([r[k].astype(float) for r in red], axis=0) for k in ("rho", "j", "sig_c", "S"))
    omega = cg.angular_velocity(grid, rho, j)
    U = np.nan_to_num(omega) * grid.R
    sig_k = S.copy()
    sig_k[1] -= U * j
    sig_k[:, 1] -= j * U
    sig_k[1, 1] += rho * U * U
    return rho, _fit_fields(grid, rho, sig_c + sig_k, omega, run["cfg"], run["Omega_rad_s"], gamma_dot_min, heights)


def fit_variants(sigma, gdot, away, gamma_dot_min):
    """mu and c of tau = mu p + c under each convention of the fit, applied to the same CG fields
    (issue: separate the causes of the difference from Gladkyy): returns {name: fit dict}.

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
    fitted on its own (as analyse_reduced, from the block's reduced snapshots; each snapshot of rundir is
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
            reduce_snapshot(snap, run["cfg"], out)
    reduced = sorted(glob.glob(os.path.join(keep, "cg_*.npz")))
    if not 2 <= blocks <= len(reduced):
        raise ValueError("blocks: %r is outside [2, %d] (the run's %d snapshots)" % (blocks, len(reduced), len(reduced)))
    grid = analysis_grid(run["cfg"])
    red = [dict(np.load(r)) for r in reduced]
    out = {"blocks": []}
    for part in np.array_split(np.arange(len(red)), blocks):
        f = _fit_summary(run, _fit_reduced(grid, [red[i] for i in part], run)[1], len(part))
        out["blocks"].append({"snapshots": [int(i) + 1 for i in part], "mu": f["mu"], "c_Pa": f["c_Pa"],
                              "Rc_mean_m": float(np.mean(f["Rc_m"])), "W_mean_m": float(np.mean(f["W_m"])), "fit_variants": f["fit_variants"]})
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


def cylinder_flux(data, r0, w, omega_at):
    """Torque through the cylinder r = r0 [N m], from the CG stress of the snapshots `data`:
    2 pi r0^2 times the integral of the symmetrised sigma_r_theta over z, at every height the
    smoothed stress reaches (from 3 kernel widths w below the bottom, where the bottom contacts are
    smeared to, to 3 above the highest particle); contact and kinetic parts, averaged over the
    snapshots."""
    line = cg.Grid([r0], np.arange(-3 * w, max(d["x"][:, 2].max() for d in data) + 3 * w, w / 4), w)

    def near(*points):  # the kernel is negligible (< e^-18) beyond 6 w of the cylinder
        r = [np.hypot(q[:, 0], q[:, 1]) for q in points]
        return (np.minimum.reduce(r) < r0 + 6 * w) & (np.maximum.reduce(r) > r0 - 6 * w)

    s_line = 0
    for d in data:
        c, k = near(d["xP"], d["xI"]), near(d["x"])
        s_line = s_line + cg.contact_stress(line, d["xP"][c], d["xI"][c], d["F"][c]) + cg.kinetic_stress(line, d["x"][k], d["v"][k], d["m"][k], omega_at)
    s_line = s_line / len(data)
    return float(2 * np.pi * r0 ** 2 * np.trapz(0.5 * (s_line[0, 1, 0] + s_line[1, 0, 0]), line.z))


def crossing_torque(data, r0):
    """Torque about the axis on everything inside the cylinder r = r0 from the contacts that cross
    it [N m], counted contact by contact (no smoothing), averaged over the snapshots: a contact
    between a flowing particle P and a partner I (a flowing particle, or the contact point of a wall
    contact) crosses when exactly one of them lies inside; its force acts at the middle of the branch
    (the contact point of a wall contact)."""
    total = 0.0
    for d in data:
        xP, xI, F = d["xP"], d["xI"], d["F"]
        if len(F) == 0:
            continue
        inP, inI = np.hypot(xP[:, 0], xP[:, 1]) < r0, np.hypot(xI[:, 0], xI[:, 1]) < r0
        c = np.where(wall_contact_mask(d)[:, None], xI, (xP + xI) / 2)  # a wall contact's xI is its contact point
        tz = c[:, 0] * F[:, 1] - c[:, 1] * F[:, 0]  # torque of the force on P
        total += tz[inP & ~inI].sum() - tz[~inP & inI].sum()
    return total / len(data)


def wall_contact_mask(d):
    """Which contacts of snapshot d are with a wall sphere: their partner point xI is a contact point,
    not the (exactly copied) position of a flowing sphere."""
    if "_wall" not in d:  # cached in the snapshot's dict
        rows = np.dtype((np.void, 3 * np.dtype(float).itemsize))
        x, xI = (np.ascontiguousarray(d[k], dtype=float).reshape(-1, 3).view(rows).ravel() for k in ("x", "xI"))
        d["_wall"] = ~np.isin(xI, x)
    return d["_wall"]


def walls_inside(data, r0):
    """Torque about the axis on the wall spheres inside the cylinder r0 [N m], averaged over the
    snapshots, two ways: (by_contact) the torque of the wall contacts whose contact point lies at
    r < r0 -- the walls as the boundary forces at their contact points, as the coarse-graining sees
    them -- and (by_centre) the torque on the wall spheres with centres at r < r0 (static and
    rotating), as measured on the bodies. They differ by the wall spheres that straddle r0."""
    by_contact, by_centre = [], []
    for d in data:
        by_centre.append(d["static_Tz"][d["static_rz"][:, 0] < r0].sum() + d["rotating_Tz"][d["rotating_rz"][:, 0] < r0].sum())
        wall = wall_contact_mask(d) if len(d["F"]) else np.zeros(0, bool)
        c, F = d["xI"][wall], d["F"][wall]
        inside = np.hypot(c[:, 0], c[:, 1]) < r0
        by_contact.append(-(c[inside, 0] * F[inside, 1] - c[inside, 1] * F[inside, 0]).sum())  # F is on the flowing sphere
    return float(np.mean(by_contact)), float(np.mean(by_centre))


def torque_closure(data, cfg, w, omega_at, step_over_R=2.0):
    """Torque balance of everything inside a cylinder r0 (issue: the CG stress must carry the
    measured torque), for r0 from the inner wall to beyond the split in steps of `step_over_R` R.

    In a steady state the torque through the cylinder equals the torque on the walls inside it:
    the wall contacts with contact points at r < r0 (walls_inside, by_contact; the inner cylinder
    and the bottom, static and, for r0 > Rs, rotating). The torque through it is evaluated counted
    contact by contact (crossing_torque, exact up to the time derivative of the angular momentum
    inside) and from the CG stress (cylinder_flux, sign: the torque on the inside is minus the flux)
    with the analysis kernel width w and with w/4 (the flux of a smoothed stress is the smoothed
    flux, which falls short where the flux has a kink: at Rs, and where the static bottom takes up
    the torque). Returns a list of dicts, or [] for snapshots without the wall torques."""
    if not all("static_Tz" in d for d in data):
        return []
    out = []
    for r0 in closure_radii(cfg, step_over_R):
        measured, by_centre = walls_inside(data, r0)
        row = {"r0_m": float(r0), "walls_inside_Nm": measured, "walls_centre_inside_Nm": by_centre, "crossing_Nm": crossing_torque(data, r0),
               "cg_w_Nm": -cylinder_flux(data, r0, w, omega_at), "cg_w4_Nm": -cylinder_flux(data, r0, w / 4, omega_at)}
        for k in ("crossing", "cg_w", "cg_w4"):
            row[k + "_over_walls"] = row[k + "_Nm"] / measured if measured else None
        out.append(row)
    return out


def gap_classes(csv_path):
    """Gladkyy 2014 section 4.2, Fig. 9-10, from a run's contacts_vs_a.csv: the contacts per snapshot
    in classes of the surface separation a (a_crit = the centre of the last bin that holds contacts): in contact (bins
    entirely at a <= 0), the bin straddling a = 0 (touching contacts and the shortest bridges), short
    bridges (bins entirely at a >= 0, centre <= a_crit/2) and long bridges (centre > a_crit/2);
    the share of the short ones among the separated bridges (Gladkyy: "most of them have only short
    bridge lengths"); and, per class, the contact density in the shear band over that in the bulk
    outside it (Gladkyy Fig. 10: it differs only for a > a_crit/2). Returns a dict; NaN where a class
    is empty."""
    A = np.genfromtxt(csv_path, delimiter=",", names=True)
    missing = [c for c in ("a_m", "contacts_per_snapshot", "band_contacts_per_m3", "outside_contacts_per_m3") if c not in A.dtype.names]
    if missing:
        raise ValueError("gap_classes: %s has no column %s (written by an older analysis)" % (csv_path, ", ".join(missing)))
    a, n = np.atleast_1d(A["a_m"]), np.atleast_1d(A["contacts_per_snapshot"])
    held = a[n > 0]
    a_crit = max(float(held.max()), 0.0) if len(held) else 0.0
    half = float(np.median(np.diff(a))) / 2 if len(a) > 1 else 0.0  # half a bin
    # Bin edges are centre -+ half, computed: an edge at a = 0 comes out as +-1e-22 m or so, and must
    # not make its bin straddle a = 0.
    tol = 1e-6 * half
    # A bin that straddles a = 0 holds both touching contacts and the shortest bridges: its own class.
    classes = {"contact": a + half <= tol, "straddling": (a - half < -tol) & (a + half > tol),
               "short": (a - half >= -tol) & (a <= a_crit / 2), "long": (a - half >= -tol) & (a > a_crit / 2)}
    out = {"a_crit_m": a_crit}
    for name, m in classes.items():
        out[name + "_per_snapshot"] = float(np.nansum(n[m]))
        inside = float(np.nansum(np.atleast_1d(A["band_contacts_per_m3"])[m]))
        outside = float(np.nansum(np.atleast_1d(A["outside_contacts_per_m3"])[m]))
        out[name + "_band_over_outside"] = inside / outside if outside > 0 else float("nan")
    separated = out["short_per_snapshot"] + out["long_per_snapshot"]
    out["short_share"] = out["short_per_snapshot"] / separated if separated > 0 else float("nan")
    return out


def count_ratio_vs_gap(wet_csv, dry_csv, gaps_m):
    """Gladkyy 2014 section 4.2 counts "about 20 % more mechanical contacts" wet than dry without
    saying where a contact ends. This gives, for each threshold a_max in gaps_m [m], the wet run's pairs
    with surface separation a <= a_max over the dry run's (contacts per snapshot of their
    contacts_vs_a.csv, whole cell): at a_max = 0 the overlaps alone, above 0 the overlaps plus the
    bridges shorter than a_max. A threshold must fall on a bin edge of both files (same bins: same cell
    configuration), else ValueError. Returns a list of (a_max_m, wet_per_snapshot, dry_per_snapshot,
    ratio)."""
    W = np.genfromtxt(wet_csv, delimiter=",", names=True)
    D = np.genfromtxt(dry_csv, delimiter=",", names=True)
    a = np.atleast_1d(W["a_m"])
    if len(a) != len(np.atleast_1d(D["a_m"])) or not np.allclose(a, D["a_m"], rtol=0, atol=1e-9 * np.abs(a).max()):
        raise ValueError("count_ratio_vs_gap: %s and %s have different separation bins (another cell configuration)" % (wet_csv, dry_csv))
    half = float(np.median(np.diff(a))) / 2
    upper = a + half  # each bin's upper edge
    cw, cd = np.cumsum(np.atleast_1d(W["contacts_per_snapshot"])), np.cumsum(np.atleast_1d(D["contacts_per_snapshot"]))
    out = []
    for x in gaps_m:
        k = int(np.argmin(np.abs(upper - x)))
        if abs(upper[k] - x) > 1e-6 * half:
            raise ValueError("count_ratio_vs_gap: a_max = %g m is not a bin edge of %s (edges every %g m from %g m)" % (x, wet_csv, 2 * half, upper[0]))
        out.append((float(x), float(cw[k]), float(cd[k]), float(cw[k] / cd[k]) if cd[k] > 0 else float("nan")))
    return out


def force_against_model(csv_path, model, R, volume, gamma, theta=0.0):
    """Gladkyy 2014 Fig. 9 (bottom row): the mean force per separation bin of a run's contacts_vs_a.csv
    against the model's force between two spheres of radius R [m] at those separations (averaged
    over each bin), for the bins entirely at a > 0, where a contact is a bridge alone. Returns the
    ratios' median, their mean weighted by the contacts of each bin, and the number of bins."""
    from . import kernels

    A = np.genfromtxt(csv_path, delimiter=",", names=True)
    a, force, n = np.atleast_1d(A["a_m"]), np.atleast_1d(A["mean_force_N"]), np.atleast_1d(A["contacts_per_snapshot"])
    half = float(np.median(np.diff(a))) / 2 if len(a) > 1 else 0.0
    m = (a - half > 0) & (n > 0)
    if not m.any():
        return {"median": float("nan"), "weighted_mean": float("nan"), "bins": 0}
    expected = np.array([np.mean(kernels.force(model, np.linspace(x - half, x + half, 21), R1=R, R2=R, volume=volume, gamma=gamma, theta=theta))
                         for x in a[m]])
    ratio = force[m] / expected
    return {"median": float(np.median(ratio)), "weighted_mean": float(np.average(ratio, weights=n[m])), "bins": int(m.sum())}


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


def stress_parts(snap, cfg):
    """The stress of one snapshot (shearcell.snapshot's arrays, as a dict) split by where it comes from: the
    separated bridges (surface separation a > 0, the capillary force alone), the contacts (a <= 0: spring and
    dashpot, and F(0) only where forceInContact is on; Gladkyy 2014 eq. (4) has it off) and the kinetic stress
    (relative to the snapshot's own mean angular velocity at each particle, as analyse). Returns {"bridges",
    "contacts", "kinetic"}, each (3, 3, nr, nz) [Pa] on analysis_grid(cfg)."""
    grid = analysis_grid(cfg)
    apart = np.asarray(snap["gap"]) > 0
    part = lambda m: cg.contact_stress(grid, snap["xP"][m], snap["xI"][m], snap["F"][m]) if m.any() else np.zeros((3, 3) + grid.R.shape)
    rho, j = cg.density_and_momentum(grid, snap["x"], snap["v"], snap["m"])
    omega_at = _omega_lookup(grid, cg.angular_velocity(grid, rho, j))
    return {"bridges": part(apart), "contacts": part(~apart), "kinetic": cg.kinetic_stress(grid, snap["x"], snap["v"], snap["m"], omega_at)}


def run_band(rundir, heights=GLADKYY_HEIGHTS):
    """The band nodes (boolean (nr, nz) on analysis_grid) of a complete run's fit from its reduced snapshots
    (analyse_reduced's 'relative' selection, the one of mu and c)."""
    with open(os.path.join(rundir, "run.json")) as f:
        run = json.load(f)
    files = sorted(glob.glob(os.path.join(rundir, "cg_*.npz")))
    if not files:
        raise ValueError("run_band: no reduced snapshots (cg_*.npz) in %s" % rundir)
    return _fit_reduced(analysis_grid(run["cfg"]), [dict(np.load(f)) for f in files], run, heights=heights)[1]["band"]


def band_decomposition(parts, band, dry_line):
    """How the band's shear stress over the dry material's divides among the parts of the stress.

    parts: {name: sigma (3, 3, nr, nz) [Pa]} whose sum is the stress; band: boolean (nr, nz) of the band
    nodes; dry_line: (mu, c_Pa) of the dry material. At each band node the shear of every part is its
    (r theta, z theta) shear projected on the direction of the total's (so that the parts' shears add up
    to tau of cg.pressure_and_shear), p its tr/3. The excess tau - (c + mu p) then splits exactly into
    tau_k - mu p_k for every part but one, `contacts`, which also takes -c: for the contacts that is how
    far their own network departs from the dry line at their own pressure; for the bridges, their direct
    shear plus mu times their tension. Returns {"p_Pa", "tau_Pa", "excess_Pa", and per part "p_<k>_Pa",
    "tau_<k>_Pa", "excess_<k>_Pa"}, means over the band nodes."""
    mu, c = dry_line
    split = {k: cg.pressure_and_shear_components(s) for k, s in parts.items()}
    p = sum(p_k for p_k, _ in split.values())
    shear = sum(shear_k for _, shear_k in split.values())
    norm = np.hypot(shear[0], shear[1])
    u = np.divide(shear, norm, out=np.zeros_like(shear), where=norm > 0)
    out = {"p_Pa": float(p[band].mean()), "tau_Pa": float(norm[band].mean())}
    out["excess_Pa"] = out["tau_Pa"] - (c + mu * out["p_Pa"])
    for k, (p_k, shear_k) in split.items():
        p_k = float(p_k[band].mean())
        tau_k = float((u[0] * shear_k[0] + u[1] * shear_k[1])[band].mean())
        out.update({"p_%s_Pa" % k: p_k, "tau_%s_Pa" % k: tau_k, "excess_%s_Pa" % k: tau_k - mu * p_k - (c if k == "contacts" else 0.0)})
    return out
