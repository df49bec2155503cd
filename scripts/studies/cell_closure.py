"""Torque balance of the shear cell (the stress-closure experiment of the cause analysis): in a steady
state the torque through a cylinder r0 equals the torque on the walls inside it. The torque through it
is counted contact by contact (crossing_torque) and from the coarse-grained stress (cylinder_flux);
the walls inside are taken at their contact points and at their centres (walls_inside). Plain numpy,
on snapshots as shearcell.snapshot writes them (dicts of their arrays)."""
import numpy as np

from yade_capillary import cellanalysis, cg


def closure_radii(cfg, step_over_R=2.0):
    """The cylinders r0 [m] of the torque balance: from the inner wall to beyond the split, step_over_R R apart."""
    return np.arange(cfg["Ri"] + step_over_R * cfg["R"], cfg["Rs"] + 3 * cfg["R"], step_over_R * cfg["R"])


def cylinder_flux(data, r0, w):
    """Torque through the cylinder r = r0 [N m], from the CG stress of the snapshots `data`:
    2 pi r0^2 times the integral of the symmetrised sigma_r_theta over z, at every height the
    smoothed stress reaches (from 3 kernel widths w below the bottom, where the bottom contacts are
    smeared to, to 3 above the highest particle); the contact part and the kinetic part of the
    time-averaged fields on that line (cellanalysis.stress)."""
    line = cg.Grid([r0], np.arange(-3 * w, max(d["x"][:, 2].max() for d in data) + 3 * w, w / 4), w)

    def near(*points):  # the kernel is negligible (< e^-18) beyond 6 w of the cylinder
        r = [np.hypot(q[:, 0], q[:, 1]) for q in points]
        return (np.minimum.reduce(r) < r0 + 6 * w) & (np.maximum.reduce(r) > r0 - 6 * w)

    fields = []
    for d in data:
        c, k = near(d["xP"], d["xI"]), near(d["x"])
        fields.append(cellanalysis.snapshot_fields(line, {"x": d["x"][k], "v": d["v"][k], "m": d["m"][k], "xP": d["xP"][c], "xI": d["xI"][c], "F": d["F"][c]}))
    s_line = cellanalysis.stress(cellanalysis.average_fields(fields))
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
        c = np.where(cellanalysis.wall_contact_mask(d)[:, None], xI, (xP + xI) / 2)  # a wall contact's xI is its contact point
        tz = c[:, 0] * F[:, 1] - c[:, 1] * F[:, 0]  # torque of the force on P
        total += tz[inP & ~inI].sum() - tz[~inP & inI].sum()
    return total / len(data)


def walls_inside(data, r0):
    """Torque about the axis on the wall spheres inside the cylinder r0 [N m], averaged over the
    snapshots, two ways: (by_contact) the torque of the wall contacts whose contact point lies at
    r < r0 -- the walls as the boundary forces at their contact points, as the coarse-graining sees
    them -- and (by_centre) the torque on the wall spheres with centres at r < r0 (static and
    rotating), as measured on the bodies. They differ by the wall spheres that straddle r0."""
    by_contact, by_centre = [], []
    for d in data:
        by_centre.append(d["static_Tz"][d["static_rz"][:, 0] < r0].sum() + d["rotating_Tz"][d["rotating_rz"][:, 0] < r0].sum())
        wall = cellanalysis.wall_contact_mask(d) if len(d["F"]) else np.zeros(0, bool)
        c, F = d["xI"][wall], d["F"][wall]
        inside = np.hypot(c[:, 0], c[:, 1]) < r0
        by_contact.append(-(c[inside, 0] * F[inside, 1] - c[inside, 1] * F[inside, 0]).sum())  # F is on the flowing sphere
    return float(np.mean(by_contact)), float(np.mean(by_centre))


def torque_closure(data, cfg, w, step_over_R=2.0):
    """Torque balance of everything inside a cylinder r0, for r0 from the inner wall to beyond the split
    in steps of `step_over_R` R: the torque on the walls inside it (walls_inside, by contact point and by
    centre) against the torque through it, counted contact by contact (crossing_torque, exact up to the
    time derivative of the angular momentum inside) and from the CG stress (cylinder_flux, sign: the
    torque on the inside is minus the flux) with the kernel width w and with w/4 (the flux of a smoothed
    stress is the smoothed flux, which falls short where the flux has a kink: at Rs, and where the static
    bottom takes up the torque). Returns a list of dicts, or [] for snapshots without the wall torques."""
    if not all("static_Tz" in d for d in data):
        return []
    out = []
    for r0 in closure_radii(cfg, step_over_R):
        measured, by_centre = walls_inside(data, r0)
        row = {"r0_m": float(r0), "walls_inside_Nm": measured, "walls_centre_inside_Nm": by_centre, "crossing_Nm": crossing_torque(data, r0),
               "cg_w_Nm": -cylinder_flux(data, r0, w), "cg_w4_Nm": -cylinder_flux(data, r0, w / 4)}
        for k in ("crossing", "cg_w", "cg_w4"):
            row[k + "_over_walls"] = row[k + "_Nm"] / measured if measured else None
        out.append(row)
    return out


def reduced_closure(d, cfg):
    """The torque balance of one snapshot d counted contact by contact, for the cylinders closure_radii(cfg):
    {closure_walls: (walls_inside by contact point, by centre) per cylinder, closure_crossing: crossing_torque
    per cylinder}, to keep in its reduced snapshot (cellanalysis.reduce_snapshot(..., more=reduced_closure));
    {} for a snapshot without the wall torques."""
    if "static_Tz" not in d:
        return {}
    r0s = closure_radii(cfg)
    return {"closure_walls": np.array([walls_inside([d], r0) for r0 in r0s]), "closure_crossing": np.array([crossing_torque([d], r0) for r0 in r0s])}


def closure_of_reduced(red, cfg):
    """torque_closure's contact-by-contact columns averaged over reduced snapshots `red` that keep them
    (reduced_closure), the CG columns None (the CG flux needs every contact); [] if any lacks them."""
    if not red or not all("closure_walls" in r for r in red):
        return []
    walls = np.mean([r["closure_walls"] for r in red], axis=0)
    crossing = np.mean([r["closure_crossing"] for r in red], axis=0)
    return [{"r0_m": float(r0), "walls_inside_Nm": float(w[0]), "walls_centre_inside_Nm": float(w[1]), "crossing_Nm": float(c),
             "crossing_over_walls": float(c / w[0]) if w[0] else None, "cg_w_over_walls": None, "cg_w4_over_walls": None}
            for r0, w, c in zip(closure_radii(cfg), walls, crossing)]
