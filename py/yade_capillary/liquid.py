"""Liquid carried by the particles (PendularMat.liquid = 'film'): where the liquid is, per particle and
per population, over time; VTK files for ParaView; the plot of a migration run.

The scene-facing functions (:func:`carried`, :func:`populations`, :func:`write_scene_vtk`) import
yade and run inside it; :func:`write_vtk_points`, :func:`write_vtk_lines` and :func:`plot_migration`
are plain Python.
"""
import csv
import math

# Columns of the time series written by a migration run (units in the names).
MIGRATION_COLUMNS = ("t_s", "films_m3", "bridges_m3", "removed_m3", "total_m3", "drift_rel", "n_bridges",
                     "wet_mean_film_m3", "dry_mean_film_m3", "wet_mean_carried_m3", "dry_mean_carried_m3",
                     "dry_with_liquid_frac", "walls_carried_m3")


def carried(law):
    """Liquid of each body [m^3] as {id: (film, in_bridges)}: its free film and, for each of its
    film-mode bridges, the share that would go back to it at rupture (PendularPhys.transfer1 for
    the sphere R1, the rest for the other body; all of it to the sphere when the other is a wall
    holding no film). Summed over the bodies this is films + bridges of ``law.liquidTotals()``."""
    from yade import O
    out = {b.id: [b.state.film if hasattr(b.state, "film") else 0.0, 0.0] for b in O.bodies if b}
    for I in O.interactions:
        p = I.phys
        if not (I.isReal and getattr(p, "film", False) and p.active):
            continue
        sphere, other = (I.id2, I.id1) if p.swapped else (I.id1, I.id2)
        holds = math.isfinite(p.R2) or O.bodies[other].state.filmArea > 0
        to_sphere = p.transfer1 * p.Vb if holds else p.Vb
        out[sphere][1] += to_sphere
        out[other][1] += p.Vb - to_sphere
    return {k: tuple(v) for k, v in out.items()}


def populations(law, groups, t, total0):
    """One row of MIGRATION_COLUMNS at time t [s]: the law's totals, the drift of the total from
    total0 (relative), and per population (``groups = {"wet": ids, "dry": ids}``) the mean film and
    the mean liquid carried (film + bridge shares, :func:`carried`), the fraction of the dry
    population that carries any liquid, and the liquid carried by all other bodies (walls, facets)."""
    tot = law.liquidTotals()
    per = carried(law)
    row = {"t_s": t, "films_m3": tot["films"], "bridges_m3": tot["bridges"], "removed_m3": tot["removed"],
           "total_m3": tot["total"], "drift_rel": (tot["total"] - total0) / total0, "n_bridges": int(law.nBridges)}
    for name in ("wet", "dry"):
        ids = [i for i in groups[name] if i in per]
        row[name + "_mean_film_m3"] = sum(per[i][0] for i in ids) / len(ids)
        row[name + "_mean_carried_m3"] = sum(per[i][0] + per[i][1] for i in ids) / len(ids)
    dry = [i for i in groups["dry"] if i in per]
    row["dry_with_liquid_frac"] = sum(1 for i in dry if per[i][0] + per[i][1] > 0) / len(dry)
    members = set(groups["wet"]) | set(groups["dry"])
    row["walls_carried_m3"] = sum(f + b for i, (f, b) in per.items() if i not in members)
    return row


def write_csv(rows, path):
    """Rows of MIGRATION_COLUMNS to a CSV file with a header line."""
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=MIGRATION_COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.17g" % r[k] if isinstance(r[k], float) else r[k]) for k in MIGRATION_COLUMNS})


def read_csv(path):
    """The rows of a CSV written by :func:`write_csv`, as dicts of floats."""
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def _fields(f, n, fields):
    for name, values in fields.items():
        if len(values) != n:
            raise ValueError("VTK field %r has %d values for %d items" % (name, len(values), n))
        f.write("SCALARS %s double 1\nLOOKUP_TABLE default\n" % name)
        f.write("\n".join("%.10g" % v for v in values) + "\n")


def write_vtk_points(path, positions, fields):
    """Legacy ASCII VTK polydata for ParaView: one vertex per particle at `positions` [m] (x, y, z
    triples), with point data `fields` ({name: values}, one value per particle; e.g. radius_m for
    ParaView's Glyph filter with a sphere scaled by it, film_m3)."""
    n = len(positions)
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 3.0\nyade-capillary particles\nASCII\nDATASET POLYDATA\n")
        f.write("POINTS %d double\n" % n)
        f.write("\n".join("%.10g %.10g %.10g" % tuple(p) for p in positions) + "\n")
        f.write("VERTICES %d %d\n" % (n, 2 * n))
        f.write("\n".join("1 %d" % i for i in range(n)) + "\n")
        f.write("POINT_DATA %d\n" % n)
        _fields(f, n, fields)


def write_vtk_lines(path, segments, fields):
    """Legacy ASCII VTK polydata: one line per bridge between the two points of each segment
    ((x1, y1, z1), (x2, y2, z2)) [m], with cell data `fields` (one value per bridge, e.g.
    volume_m3, force_N)."""
    n = len(segments)
    with open(path, "w") as f:
        f.write("# vtk DataFile Version 3.0\nyade-capillary bridges\nASCII\nDATASET POLYDATA\n")
        f.write("POINTS %d double\n" % (2 * n))
        for a, b in segments:
            f.write("%.10g %.10g %.10g\n%.10g %.10g %.10g\n" % (tuple(a) + tuple(b)))
        f.write("LINES %d %d\n" % (n, 3 * n))
        f.write("\n".join("2 %d %d" % (2 * i, 2 * i + 1) for i in range(n)) + "\n")
        f.write("CELL_DATA %d\n" % n)
        _fields(f, n, fields)


def write_scene_vtk(prefix, law, groups):
    """The current scene as two VTK files: ``<prefix>_particles.vtk`` (spheres: radius_m, film_m3,
    carried_m3, wet_population 1/0) and ``<prefix>_bridges.vtk`` (film-mode bridges between sphere
    centres, or from a sphere to its contact point on a wall: volume_m3, force_N, transfer1)."""
    from yade import O
    from yade.wrapper import Sphere
    per = carried(law)
    wet = set(groups["wet"])
    spheres = [b for b in O.bodies if b and isinstance(b.shape, Sphere)]
    write_vtk_points(prefix + "_particles.vtk", [tuple(b.state.pos) for b in spheres],
                     {"radius_m": [b.shape.radius for b in spheres], "film_m3": [b.state.film for b in spheres],
                      "carried_m3": [sum(per[b.id]) for b in spheres], "wet_population": [1.0 if b.id in wet else 0.0 for b in spheres]})
    segs, vol, force, share = [], [], [], []
    for I in O.interactions:
        p = I.phys
        if not (I.isReal and getattr(p, "film", False) and p.active):
            continue
        b1, b2 = O.bodies[I.id1], O.bodies[I.id2]
        a = tuple(b1.state.pos) if isinstance(b1.shape, Sphere) else tuple(I.geom.contactPoint)
        b = tuple(b2.state.pos) if isinstance(b2.shape, Sphere) else tuple(I.geom.contactPoint)
        segs.append((a, b))
        vol.append(p.Vb)
        force.append(p.Fcap)
        share.append(p.transfer1)
    write_vtk_lines(prefix + "_bridges.vtk", segs, {"volume_m3": vol, "force_N": force, "transfer1": share})


def plot_migration(rows, png, title):
    """Two panels over time: the mean liquid carried per particle of the wet and the dry population
    (film + bridge shares) and the liquid in films vs bridges vs carried by the walls, with the
    bridge count."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    t = [r["t_s"] for r in rows]
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    a.plot(t, [r["wet_mean_carried_m3"] * 1e12 for r in rows], label="wet population: film + bridge shares")
    a.plot(t, [r["dry_mean_carried_m3"] * 1e12 for r in rows], label="dry population: film + bridge shares")
    a.plot(t, [r["wet_mean_film_m3"] * 1e12 for r in rows], "--", label="wet population: free film")
    a.plot(t, [r["dry_mean_film_m3"] * 1e12 for r in rows], "--", label="dry population: free film")
    a.set_xlabel("t [s]")
    a.set_ylabel("mean liquid per particle [nl = 1e-12 m^3]")
    a.legend(fontsize=8)
    b.plot(t, [r["films_m3"] * 1e12 for r in rows], label="in films")
    b.plot(t, [r["bridges_m3"] * 1e12 for r in rows], label="in bridges")
    b.plot(t, [r["walls_carried_m3"] * 1e12 for r in rows], label="carried by walls and facets")
    b.set_xlabel("t [s]")
    b.set_ylabel("liquid [nl]")
    c = b.twinx()
    c.plot(t, [r["n_bridges"] for r in rows], "k:", label="bridges")
    c.set_ylabel("bridges [-]")
    b.legend(loc="center left", fontsize=8)
    c.legend(loc="center right", fontsize=8)
    worst = max(abs(r["drift_rel"]) for r in rows)
    fig.suptitle("%s\nlargest drift of films + bridges + removed: %.1e (relative)" % (title, worst), fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
