"""Contacts against the surface separation in the shear cell (Gladkyy 2014 section 4.2, Fig. 9-10), from the
contacts_vs_a.csv of analysed runs (cellanalysis): classes of the gap, wet over dry counts against where a
contact is taken to end, the mean force against the model's. Plain numpy."""
import numpy as np

from yade_capillary import kernels


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
