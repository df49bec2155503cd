"""The glass beads of Richefeu et al. 2008's scenarios (yade_capillary.directshear, yade_capillary.compression):
the sizes of a number distribution, a random loose fill of a cylinder, and the materials of the beads (the liquid
shared over bonds, the richefeu force with the lian rupture distance, approach-only damping) and of the dry walls.

A configuration is a dict with n, diameters, fractions (by number), D and fill_height [m], rho [kg/m^3], kn [N/m per
contact], damping (of critical, for the lightest pair), gamma [N/m], theta [rad], and optionally mass_scale (the
densities times mass_scale, for a larger time step in a quasi-static test; 1 if absent) and extrapolate.
"""
import math


def sizes(cfg):
    """Diameters [m] of the n spheres in the number fractions, largest first."""
    n = cfg["n"]
    counts = [int(round(f * n)) for f in cfg["fractions"]]
    counts[-1] = n - sum(counts[:-1])
    out = []
    for d, c in sorted(zip(cfg["diameters"], counts), reverse=True):
        out += [d] * c
    return out


def fill(cfg, rng):
    """Random positions without overlap in the cylinder of diameter D (largest spheres first), up to fill_height:
    a list of (centre, radius) [m]."""
    R, H = cfg["D"] / 2, cfg["fill_height"]
    cell = max(cfg["diameters"])
    grid, placed = {}, []
    near = [(dx, dy, dz) for dx in (-1, 0, 1) for dy in (-1, 0, 1) for dz in (-1, 0, 1)]

    def overlaps(p, r, key):
        return any((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2 < (r + rq) ** 2
                   for dx, dy, dz in near for q, rq in grid.get((key[0] + dx, key[1] + dy, key[2] + dz), ()))

    for d in sizes(cfg):
        r = d / 2
        for _ in range(100000):
            rho, phi = (R - r) * math.sqrt(rng.random()), 2 * math.pi * rng.random()
            p = (rho * math.cos(phi), rho * math.sin(phi), r + (H - 2 * r) * rng.random())
            key = tuple(int(math.floor(c / cell)) for c in p)
            if not overlaps(p, r, key):
                grid.setdefault(key, []).append((p, r))
                placed.append((p, r))
                break
        else:
            raise ValueError("glassbeads.fill: no room for sphere %d in a fill of fill_height = %g m; raise fill_height" % (len(placed), H))
    return placed


def materials(cfg):
    """Appends the beads' and the walls' PendularMat (labels beads and walls, both without friction: the
    scenarios set it after their preparation); returns their ids."""
    from yade import O
    from yade.wrapper import PendularMat
    rho = cfg["rho"] * cfg.get("mass_scale", 1.0)
    d_min = min(cfg["diameters"])
    m_pair = rho * math.pi / 6 * d_min ** 3 / 2  # the lightest pair's reduced mass
    cn = cfg["damping"] * 2 * math.sqrt(m_pair * cfg["kn"])
    # Material values combine in series: twice the pair's.
    contact = dict(kn=2 * cfg["kn"], cn=2 * cn, ks=2 * cfg["kn"] * 2 / 7, cs=0.0, density=rho, frictionAngle=0.0, normalDamping="approach")
    beads = PendularMat(Vb=1e-6, gamma=cfg["gamma"], theta=cfg["theta"], model="richefeu", rupture="lian", liquid="bonds",
                        extrapolate=cfg.get("extrapolate", False), label="beads", **contact)
    beads.wet = True
    walls = PendularMat(label="walls", **contact)
    return O.materials.append(beads), O.materials.append(walls)


GRAVITY = 9.81


def engines(cfg, protocol, dry_fraction, loop):
    """The engines of a scenario with its PendularBonds (label bonds) under gravity; the collider lists every pair
    within a quarter of the largest diameter, longer than the debonding distance of the sharing up to w of a few
    percent (PendularBonds refuses a shorter one); the time step from the stiffness (dt_safety)."""
    from yade import O
    from yade.wrapper import PendularBonds
    from .scene import engines as scene_engines, stable_dt
    bonds = PendularBonds(protocol=protocol, dryFraction=dry_fraction, seed=cfg["seed"], label="bonds")
    O.engines = scene_engines(gravity=(0, 0, -GRAVITY), loop=loop, extra=[bonds])
    [e for e in O.engines if e.label == "collider"][0].verletDist = max(cfg["diameters"]) / 4
    O.dt = stable_dt(cfg["dt_safety"])


def law():
    """The scene's Law2_ScGeom_PendularPhys_Bridge."""
    from yade import O
    return [f for e in O.engines if hasattr(e, "lawDispatcher") for f in e.lawDispatcher.functors][0]


def frictional(cfg):
    """Friction mu on the beads and walls and on every existing contact (Ip2.updateContacts); returns the number
    of contacts updated."""
    from yade import O
    for m in O.materials:
        if m.label in ("beads", "walls"):
            m.frictionAngle = math.atan(cfg["mu"])
    return [f for e in O.engines if hasattr(e, "physDispatcher") for f in e.physDispatcher.functors][0].updateContacts()


def chunks(steps, records):
    """The step counts of `records` runs that together make `steps` (at least one each): a loading of a given
    travel recorded `records` times ends at its travel, not short of it by the remainder."""
    return [max(1, (k + 1) * steps // records - k * steps // records) for k in range(records)]


def write_csv(path, rows):
    """Rows (dicts) to a CSV file with a header of every key in order of appearance: the summaries of older runs,
    read back into a series, lack the keys added since."""
    import csv
    with open(path, "w", newline="") as f:
        out = csv.DictWriter(f, fieldnames=list(dict.fromkeys(k for r in rows for k in r)))
        out.writeheader()
        out.writerows(rows)
