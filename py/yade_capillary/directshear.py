"""Richefeu et al. 2008's direct shear test (section 3.2) inside yade: a split cylinder of glass beads with
the liquid shared over bonds (PendularMat.liquid = 'bonds'), its preparation, the shear at constant normal
stress, and the Mohr-Coulomb fit of the residual shear stress.

The cell: a cylinder of diameter D split at h_lower (the lower part fixed on a bottom wall, the upper ring
moving along x at the shear speed), closed by a lid that the normal stress presses down (a wall of weight
sigma A, free along z only, moving along x with the ring). Preparation (section 3.2.1): the spheres settle
under gravity without bonds and without friction; the liquid of the water content is shared over every
eligible pair (PendularBonds); the lid consolidates the sample without friction until the solid fraction
reaches phi (or stops); then the friction is set to mu and the upper part moves.

Every parameter lives in CONFIGS (what the paper leaves open is chosen there and in docs/richefeu.md);
scripts only choose names.
"""
import csv
import json
import math
import os
import random
import time

from . import glassbeads

# Richefeu 2008 section 3.2.1: Ø46 mm, upper part 10 mm, lower 15 mm; 7307 spheres of 2, 1.5 and 1 mm in
# proportions 50/30/20 % by number (they fill Ø46 x 20 mm at phi = 0.6, the sample of the experiments; by
# volume the same sample would need about 16 700 spheres). Glass: rho 2500 kg/m^3; water: gamma 0.073 N/m,
# theta = 0 (section 2.3). Chosen (not printed): kn = 2000 N/m per contact (stiffness level kn/(sigma d) >= 1500
# at 900 Pa), approach-only damping at 0.3 of critical for the lightest pair (eq. 3), a tangential spring of
# 2/7 kn (the viscous friction of eq. 12 would need a step 50 times smaller to reach its Coulomb cap at the shear
# speed), walls as frictional as the beads; the shear speed from the inertial number (docs/richefeu.md).
PAPER = dict(D=0.046, h_lower=0.015, h_upper=0.010, n=7307, diameters=(2e-3, 1.5e-3, 1e-3), fractions=(0.5, 0.3, 0.2), rho=2500.0,
             kn=2000.0, damping=0.3, mu=0.4, gamma=0.073, theta=0.0, phi=0.6, inertial=4e-3, shear=4e-3, residual_from=2e-3,
             fill_height=0.042, settle_s=0.35, consolidate_s=0.15, rest_tolerance=0.02, dt_safety=0.2, records=200, seed=1,
             sigmas=(300.0, 600.0, 900.0))
# The CI regression of c (tests/yade/test_direct_shear_ci.py): the same particles in a cell of 24 mm (as many
# spheres per area as the paper's, 1989), sheared five times faster (I = 2e-2) over 3 mm. Its lid stresses of 10
# and 300 Pa (about 80 and 370 Pa on the plane) put the lower one near the intercept, where c is least uncertain.
# A cell of 16 mm (884 spheres) did not separate wet from dry: its walls carry most of the shear force.
CI = dict(PAPER, D=0.024, n=1989, inertial=2e-2, shear=3e-3, residual_from=1e-3, records=100, sigmas=(10.0, 300.0))
CONFIGS = {"paper": PAPER, "ci": CI}
GRAVITY = glassbeads.GRAVITY


def build(config="ci", protocol="particles", dry_fraction=0.0, seed=None, loop="fused"):
    """The cell with its loose spheres (no liquid, no friction); returns the info dict of the scene."""
    from yade import O, geom
    from yade.utils import sphere, wall
    cfg = dict(CONFIGS[config])
    rng = random.Random(cfg["seed"] if seed is None else seed)
    O.reset()
    beads, walls = glassbeads.materials(cfg)
    R = cfg["D"] / 2
    # Each part's wall ends at the shear plane in a rim (an annulus of the shear distance and a largest diameter):
    # where the parts no longer overlap, the spheres of one part rest on the other part's rim instead of leaving
    # the cell through the opening between the two walls.
    rim = dict(radius=R + cfg["shear"] + max(cfg["diameters"]), height=0, radiusTopInner=R, segmentsNumber=48, material=walls)
    lower = O.bodies.append(geom.facetCylinder((0, 0, cfg["h_lower"] / 2), R, cfg["h_lower"], segmentsNumber=48, wallMask=4, material=walls)
                            + geom.facetCylinder((0, 0, cfg["h_lower"]), **rim))
    top = cfg["h_lower"] + 2 * cfg["fill_height"]  # the ring reaches above the loose fill; only its lowest h_upper meets the sample
    upper = O.bodies.append(geom.facetCylinder((0, 0, (cfg["h_lower"] + top) / 2), R, top - cfg["h_lower"], segmentsNumber=48, wallMask=4,
                                               material=walls) + geom.facetCylinder((0, 0, cfg["h_lower"]), **rim))
    bottom = O.bodies.append(wall(0, axis=2, sense=1, material=walls))
    spheres = [O.bodies.append(sphere(p, r, material=beads)) for p, r in glassbeads.fill(cfg, rng)]
    glassbeads.engines(cfg, protocol, dry_fraction, loop)
    return dict(config=config, cfg=cfg, lower=lower, upper=upper, bottom=bottom, lid=None, spheres=spheres, protocol=protocol,
                dry_fraction=dry_fraction)


def _solid(info):
    from yade import O
    return sum(4 / 3 * math.pi * O.bodies[i].shape.radius ** 3 for i in info["spheres"])


def solid_fraction(info):
    """The spheres' volume over the cylinder below the lid [-]."""
    from yade import O
    A = math.pi * info["cfg"]["D"] ** 2 / 4
    return _solid(info) / (A * O.bodies[info["lid"]].state.pos[2])


def settle(info, log=print):
    """Gravity settling without bonds and friction (settle_s)."""
    from yade import O
    n = int(info["cfg"]["settle_s"] / O.dt)
    O.run(n, True)
    log("settled: %d steps, highest sphere at %.2f mm" % (n, 1e3 * max(O.bodies[i].state.pos[2] + O.bodies[i].shape.radius for i in info["spheres"])))


def wet(info, w):
    """Shares the liquid of water content w over the eligible pairs (Richefeu 2008 eq. 13-14)."""
    from . import bonds
    if w > 0:
        bonds.share_water(w)


def consolidate(info, sigma, log=print):
    """The lid of weight sigma A on the sample; without friction until phi is reached (or the lid stops),
    then friction mu on every contact (Ip2.updateContacts), and a last consolidate_s / 3 at rest."""
    from yade import O
    from yade.utils import wall
    cfg = info["cfg"]
    A = math.pi * cfg["D"] ** 2 / 4
    ztop = max(O.bodies[i].state.pos[2] + O.bodies[i].shape.radius for i in info["spheres"])
    walls = [m for m in O.materials if m.label == "walls"][0]
    lid = O.bodies.append(wall(ztop + 1e-4, axis=2, sense=-1, material=walls))
    b = O.bodies[lid]
    b.dynamic = True
    b.state.mass = sigma * A / GRAVITY  # its weight is the normal stress
    b.state.inertia = (1, 1, 1)
    b.state.blockedDOFs = "xyXYZ"
    info["lid"], info["sigma"] = lid, sigma
    chunk = max(1, int(2e-3 / O.dt))
    t_end = O.time + cfg["consolidate_s"]
    while O.time < t_end and solid_fraction(info) < cfg["phi"]:
        O.run(chunk, True)
    phi0 = solid_fraction(info)
    n = glassbeads.frictional(cfg)
    # At rest with friction: the lid's contact stress, sampled every chunk, averages to its weight. A heavy lid
    # rings longer on the sample: the rest lasts at least consolidate_s / 3 and goes on (up to consolidate_s)
    # until the mean of the last half of the samples is within rest_tolerance of sigma.
    samples, least, most = [], max(2, int(cfg["consolidate_s"] / 3 / (chunk * O.dt))), max(2, int(cfg["consolidate_s"] / (chunk * O.dt)))
    while len(samples) < most:
        O.run(chunk, True)
        samples.append(O.forces.f(lid)[2] / A)
        last = samples[len(samples) // 2:]
        if len(samples) >= least and abs(sum(last) / len(last) - sigma) < cfg["rest_tolerance"] * sigma:
            break
    info["sigma_rest_Pa"], info["rest_s"] = sum(last) / len(last), len(samples) * chunk * O.dt
    log("consolidated at %g Pa: phi %.4f without friction, %.4f with mu = %g (%d contacts updated), lid stress %.1f Pa after %.3f s at rest"
        % (sigma, phi0, solid_fraction(info), cfg["mu"], n, info["sigma_rest_Pa"], info["rest_s"]))
    return phi0


def plane_stresses(info):
    """Stresses on the shear plane z = h_lower [Pa], compression positive.

    weight_above: the weight of the spheres whose centre lies above the plane over the cell's area, the rho g h
    of the paper's normal stress sigma = N/S + rho g h (Richefeu2008 section 3.1.1).
    tau_contacts, sigma_contacts: the force that the spheres below the plane exert on those above it through
    their contacts and bridges (capillary attraction included), against the shear direction and upwards, over
    the area. Against the ring's force they tell what the cell's walls carry.
    capillary_stress: the mean stress of the capillary forces over the sample below the lid, sum of F_cap l over
    the bonds (l the distance between the centres) over 3 V (the Love-Weber mean stress): the cohesive stress
    that the bonds hold, which grows with their number and with the force each still carries at a distance."""
    from yade import O
    cfg = info["cfg"]
    A = math.pi * cfg["D"] ** 2 / 4
    z0 = cfg["h_lower"]
    above = {i: O.bodies[i].state.pos[2] > z0 for i in info["spheres"]}
    weight = sum(O.bodies[i].state.mass for i, up in above.items() if up) * GRAVITY
    fx = fz = fl = 0.0
    for I in O.interactions:
        a, b = above.get(I.id1), above.get(I.id2)
        if a is None or b is None or not I.isReal:
            continue
        if I.phys.Fcap > 0:
            fl += I.phys.Fcap * (O.bodies[I.id2].state.pos - O.bodies[I.id1].state.pos).norm()
        if a == b:
            continue
        f2 = I.phys.normalForce + I.phys.shearForce + I.phys.viscousShear  # on body 2 (YADE convention)
        sign = 1.0 if b else -1.0  # the force on the sphere above
        fx += sign * f2[0]
        fz += sign * f2[2]
    volume = A * O.bodies[info["lid"]].state.pos[2]
    return dict(weight_above_Pa=weight / A, tau_contacts_Pa=-fx / A, sigma_contacts_Pa=fz / A, capillary_stress_Pa=fl / (3 * volume))


def shear_speed(cfg, sigma):
    """The upper part's speed [m/s] for the configuration's inertial number I = (v / h_b) d sqrt(rho / sigma),
    with a shear band h_b of 10 mean diameters."""
    return cfg["inertial"] * 10 * math.sqrt(sigma / cfg["rho"])


def shear(info, outdir, v=None):
    """Moves the upper ring and the lid at v along x over cfg['shear']; writes shear.csv; returns the rows."""
    from yade import O
    from . import bonds
    cfg = info["cfg"]
    A = math.pi * cfg["D"] ** 2 / 4
    v = shear_speed(cfg, info["sigma"]) if v is None else v
    info["v"] = v
    upper = list(info["upper"]) + [info["lid"]]
    for i in info["upper"]:
        O.bodies[i].state.vel = (v, 0, 0)
    O.bodies[info["lid"]].state.vel = (v, 0, O.bodies[info["lid"]].state.vel[2])
    steps = int(cfg["shear"] / v / O.dt)
    law = glassbeads.law()
    rows, x0 = [], O.bodies[info["upper"][0]].state.pos[0]
    t0 = time.time()
    for chunk in glassbeads.chunks(steps, cfg["records"]):
        O.run(chunk, True)
        fx = sum(O.forces.f(i)[0] for i in upper)
        rows.append(dict(displacement_m=O.bodies[info["upper"][0]].state.pos[0] - x0, tau_Pa=-fx / A,
                         sigma_lid_Pa=O.forces.f(info["lid"])[2] / A, lid_z_m=O.bodies[info["lid"]].state.pos[2], **plane_stresses(info),
                         phi=solid_fraction(info), bond_coordination=bonds.coordination(), liquid_m3=law.liquidTotals()["total"]))
    info["wall_s"] = time.time() - t0
    info["steps"] = steps
    os.makedirs(outdir, exist_ok=True)
    glassbeads.write_csv(os.path.join(outdir, "shear.csv"), rows)
    return rows


def residual(rows, start, key="tau_Pa"):
    """Mean residual value of rows[key] (the shear stress [Pa] by default) from displacement `start` on, and its
    standard error from 5 block means."""
    taus = [r[key] for r in rows if r["displacement_m"] >= start]
    k = 5
    blocks = [taus[i * len(taus) // k:(i + 1) * len(taus) // k] for i in range(k)]
    means = [sum(b) / len(b) for b in blocks if b]
    mean = sum(means) / len(means)
    se = math.sqrt(sum((m - mean) ** 2 for m in means) / (len(means) - 1) / len(means))
    return mean, se


def prepare(config, path, seed=None, loop="fused", log=print):
    """Builds and settles a cell; saves it to `path` (a YADE state, .yade.gz) with its info (path + '.json'),
    so that the runs of a series start from the same packing."""
    from yade import O
    info = build(config, seed=seed, loop=loop)
    settle(info, log)
    O.save(path)
    with open(path + ".json", "w") as f:
        json.dump({k: v for k, v in info.items() if k != "cfg"}, f)
    return info


def load(path, protocol="particles", dry_fraction=0.0):
    """A cell saved by prepare, with the protocol and the fraction of dry pairs of this run."""
    from yade import O
    from . import patches
    O.load(path)
    patches.install()
    with open(path + ".json") as f:
        info = json.load(f)
    info["cfg"] = dict(CONFIGS[info["config"]])
    b = [e for e in O.engines if e.label == "bonds"][0]
    b.protocol, b.dryFraction = protocol, dry_fraction
    info["protocol"], info["dry_fraction"] = protocol, dry_fraction
    return info


def run(config, w, sigma, outdir, protocol="particles", dry_fraction=0.0, speed=1.0, seed=None, loop="fused", state=None, log=print):
    """One direct shear test: build and settle (or load `state`, saved by prepare), wet to water content w,
    consolidate under sigma [Pa], shear at `speed` times the speed of the configuration's inertial number.
    Writes shear.csv and summary.json to outdir; returns the summary."""
    from yade import O
    from . import bonds
    t0 = time.time()
    if state:
        info = load(state, protocol, dry_fraction)
    else:
        info = build(config, protocol, dry_fraction, seed, loop)
        settle(info, log)
    iter0 = O.iter
    wet(info, w)
    z0 = bonds.coordination()
    phi0 = consolidate(info, sigma, log)
    rows = shear(info, outdir, speed * shear_speed(info["cfg"], sigma))
    start = info["cfg"]["residual_from"]
    tau, se = residual(rows, start)
    above = residual(rows, start, "weight_above_Pa")[0]
    tau_c, se_c = residual(rows, start, "tau_contacts_Pa")
    summary = dict(config=config, w=w, sigma_Pa=sigma, sigma_plane_Pa=sigma + above, weight_above_Pa=above, protocol=protocol,
                   dry_fraction=dry_fraction, tau_residual_Pa=tau, tau_se_Pa=se, tau_contacts_Pa=tau_c, tau_contacts_se_Pa=se_c,
                   sigma_contacts_Pa=residual(rows, start, "sigma_contacts_Pa")[0], capillary_stress_start_Pa=rows[0]["capillary_stress_Pa"],
                   capillary_stress_Pa=residual(rows, start, "capillary_stress_Pa")[0], sigma_rest_Pa=info["sigma_rest_Pa"], rest_s=info["rest_s"],
                   phi_consolidated=phi0, phi_end=rows[-1]["phi"], bond_coordination_wet=z0, bond_coordination_end=rows[-1]["bond_coordination"],
                   shear_speed_m_s=info["v"], inertial_number=info["v"] / 10 * math.sqrt(info["cfg"]["rho"] / sigma),
                   dt_s=O.dt, spheres=len(info["spheres"]), particle_steps=len(info["spheres"]) * (O.iter - iter0), wall_s=time.time() - t0)
    with open(os.path.join(outdir, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    log("w %g, sigma %g Pa (on the plane %.1f Pa): tau %.2f +- %.2f Pa (contacts across the plane %.2f Pa), z %.2f, %.0f s"
        % (w, sigma, sigma + above, tau, se, tau_c, z0, summary["wall_s"]))
    return summary


def mohr_coulomb(sigmas, taus, errors):
    """Weighted least-squares line tau = c + sigma tan(phi) [Pa]: returns c, its standard error, phi [deg] and its
    standard error (from the errors of tau, at least their scatter about the line). Needs two normal stresses or more."""
    if len(set(sigmas)) < 2:
        raise ValueError("mohr_coulomb: sigmas = %r; the fit needs at least two different normal stresses" % (list(sigmas),))
    wts = [1 / e ** 2 for e in errors]
    S, Sx, Sy = sum(wts), sum(w * x for w, x in zip(wts, sigmas)), sum(w * y for w, y in zip(wts, taus))
    Sxx, Sxy = sum(w * x * x for w, x in zip(wts, sigmas)), sum(w * x * y for w, x, y in zip(wts, sigmas, taus))
    det = S * Sxx - Sx * Sx
    slope, c = (S * Sxy - Sx * Sy) / det, (Sxx * Sy - Sx * Sxy) / det
    chi2 = sum(w * (y - c - slope * x) ** 2 for w, x, y in zip(wts, sigmas, taus))
    scale = max(1.0, chi2 / (len(sigmas) - 2)) if len(sigmas) > 2 else 1.0
    se_c, se_slope = math.sqrt(Sxx / det * scale), math.sqrt(S / det * scale)
    return c, se_c, math.degrees(math.atan(slope)), math.degrees(se_slope / (1 + slope ** 2))


def series(config, ws, sigmas, outdir, protocol="particles", dry_fraction=0.0, speed=1.0, seed=None, packing=None, log=print):
    """Every water content of ws at every lid stress of sigmas [Pa], from one packing: runs the tests whose
    outdir/w<w>_sigma<sigma>/summary.json is missing (so an interrupted series goes on where it stopped), reads the
    others. The packing is `packing` (a state saved by prepare) or outdir/settled_<config>.yade.gz, prepared if
    missing and kept, so that later runs (other protocols, dry fractions, speeds) can start from it. Writes
    outdir/runs.csv and, with two lid stresses or more, outdir/mohr_coulomb.csv (c and phi of each water content
    fitted alone and with one phi for all, common_friction); returns the summaries and the fits of each alone."""
    os.makedirs(outdir, exist_ok=True)
    state = packing or os.path.join(outdir, "settled_%s.yade.gz" % config)
    runs = []
    for w in ws:
        for sigma in sigmas:
            where = os.path.join(outdir, "w%g_sigma%g" % (w, sigma))
            if os.path.exists(os.path.join(where, "summary.json")):
                with open(os.path.join(where, "summary.json")) as f:
                    runs.append(json.load(f))
                continue
            if not os.path.exists(state + ".json"):
                prepare(config, state, seed=seed, log=log)
            runs.append(run(config, w, sigma, where, protocol, dry_fraction, speed, state=state, log=log))
    glassbeads.write_csv(os.path.join(outdir, "runs.csv"), runs)
    fitted = fits(runs) if len(set(sigmas)) > 1 else {}
    if fitted:
        both = common_friction(runs)
        with open(os.path.join(outdir, "mohr_coulomb.csv"), "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["w", "c_Pa", "c_se_Pa", "phi_deg", "phi_se_deg", "c_one_phi_Pa", "c_one_phi_se_Pa", "one_phi_deg", "one_phi_se_deg"])
            for w, fit in fitted.items():
                out.writerow([w, fit["c_Pa"], fit["c_se_Pa"], fit["phi_deg"], fit["phi_se_deg"], both["c_Pa"][w], both["c_se_Pa"][w],
                              both["phi_deg"], both["phi_se_deg"]])
                log("w = %g: c = %.1f +- %.1f Pa, phi = %.1f +- %.1f deg; with one phi for all w: c = %.1f +- %.1f Pa"
                    % (w, fit["c_Pa"], fit["c_se_Pa"], fit["phi_deg"], fit["phi_se_deg"], both["c_Pa"][w], both["c_se_Pa"][w]))
        log("one phi for all w: %.1f +- %.1f deg" % (both["phi_deg"], both["phi_se_deg"]))
    return runs, fitted


def fits(runs):
    """The Mohr-Coulomb fit of each water content of runs (summaries of run) against the normal stress on the
    shear plane: {w: dict(c_Pa, c_se_Pa, phi_deg, phi_se_deg)}."""
    out = {}
    for w in sorted(set(r["w"] for r in runs)):
        mine = [r for r in runs if r["w"] == w]
        c, se_c, phi, se_phi = mohr_coulomb([r["sigma_plane_Pa"] for r in mine], [r["tau_residual_Pa"] for r in mine], [r["tau_se_Pa"] for r in mine])
        out[w] = dict(c_Pa=c, c_se_Pa=se_c, phi_deg=phi, phi_se_deg=se_phi)
    return out


def common_friction(runs):
    """The Mohr-Coulomb fit of every water content of runs at once with one friction angle, tau = c_w + sigma tan(phi)
    (Richefeu2008 section 3.2.2: phi does not depend on w), weighted by the residual stresses' errors (scaled up by
    the scatter about the lines when it is larger). Returns dict(phi_deg, phi_se_deg, c_Pa={w: c}, c_se_Pa={w: se},
    c_cov_Pa2={w: {w2: covariance}}); the difference of two cohesions has the variance
    cov[a][a] + cov[b][b] - 2 cov[a][b]. Needs two normal stresses for one water content or more."""
    import numpy as np
    ws = sorted(set(r["w"] for r in runs))
    X = np.array([[1.0 if r["w"] == w else 0.0 for w in ws] + [r["sigma_plane_Pa"]] for r in runs])
    y = np.array([r["tau_residual_Pa"] for r in runs])
    wt = np.array([1 / r["tau_se_Pa"] ** 2 for r in runs])
    if np.linalg.matrix_rank(X) < X.shape[1]:
        raise ValueError("common_friction: the runs %s need two different normal stresses for one water content or more"
                         % [(r["w"], r["sigma_plane_Pa"]) for r in runs])
    A = np.linalg.inv(X.T @ (wt[:, None] * X))
    beta = A @ X.T @ (wt * y)
    dof = len(runs) - X.shape[1]
    chi2 = float(np.sum(wt * (y - X @ beta) ** 2))
    cov = A * (max(1.0, chi2 / dof) if dof > 0 else 1.0)
    slope, se_slope = beta[-1], math.sqrt(cov[-1, -1])
    return dict(phi_deg=math.degrees(math.atan(slope)), phi_se_deg=math.degrees(se_slope / (1 + slope ** 2)),
                c_Pa={w: float(beta[i]) for i, w in enumerate(ws)}, c_se_Pa={w: math.sqrt(cov[i, i]) for i, w in enumerate(ws)},
                c_cov_Pa2={w: {w2: float(cov[i, j]) for j, w2 in enumerate(ws)} for i, w in enumerate(ws)})
