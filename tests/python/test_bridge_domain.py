"""Where the exact Young-Laplace solver follows the pendular bridge (docs/models.md, "Where the pendular
bridge exists"): at seeded cases of data/bridge_domain/limits.csv (written by scripts/bridge_domain.py) the
solver succeeds just inside the documented limit and refuses, naming the cause, beyond it; swapping the
two solids gives the same rupture gap."""
import csv
import math
import os
import random

import pytest

from yade_capillary import kernels

LIMITS = os.path.join(os.path.dirname(__file__), "..", "..", "data", "bridge_domain", "limits.csv")
R_SMALL = 1e-3   # [m]; the limits are in V* = V/R_small^3 and do not depend on it
GAMMA = 0.072    # [N/m]
RATIOS = {"1": 1.0, "1/2": 0.5, "1/4": 0.25, "wall": 0.0}
INSIDE, BEYOND = 0.9, 1.2  # factors on the documented limit (found to 1e-3 in ln V*, printed to 5 digits)


def read_limits():
    with open(LIMITS) as f:
        return list(csv.DictReader(f))


ROWS = read_limits()
# Two cases per geometry, drawn with fixed seeds among those where the solver stops below the scan's cap.
SEEDED = [r for i, g in enumerate(RATIOS) for r in random.Random(7 + i).sample(
    [q for q in ROWS if q["geometry"] == g and q["cause"] != "none up to the cap"], 2)]


def radii(geometry, small_first=True):
    ratio = RATIOS[geometry]
    large = math.inf if ratio == 0 else R_SMALL / ratio
    return (R_SMALL, large) if small_first else (large, R_SMALL)


def bridge(row, vstar, small_first=True):
    """The solver for a row of limits.csv at V*; the small solid as solid 1 or 2."""
    R1, R2 = radii(row["geometry"], small_first)
    ts, tl = math.radians(float(row["theta_small_deg"])), math.radians(float(row["theta_large_deg"]))
    t1, t2 = (ts, tl) if small_first else (tl, ts)
    return kernels.YoungLaplaceBridge(R1, R2, vstar * R_SMALL ** 3, t1, t2)


def ident(row):
    return "%s-%s-%s" % (row["geometry"], row["theta_small_deg"], row["theta_large_deg"])


def test_table_covers_the_grid_and_the_target_range():
    # 8 x 8 angle pairs per geometry; every limit above the target range of the exact table's successor
    # (V* up to 0.5). The documented limit is the smaller of the two orders of two spheres; both stop where
    # no bridge exists at contact, so they differ by the bisection's resolution only (1e-3 in ln V*, 5
    # printed digits).
    assert sorted({(r["geometry"]) for r in ROWS}) == sorted(RATIOS)
    for g in RATIOS:
        assert len([r for r in ROWS if r["geometry"] == g]) == 64
    assert min(float(r["vstar_limit"]) for r in ROWS) > 0.5
    for r in ROWS:
        if r["geometry"] == "wall":
            continue
        a, b = float(r["vstar_limit_small_first"]), float(r["vstar_limit_small_second"])
        assert float(r["vstar_limit"]) == min(a, b), ident(r)
        assert r["cause"] == "no bridge at contact" and abs(math.log(a / b)) < 1.1e-3, ident(r)


def orders(row):
    return (True,) if row["geometry"] == "wall" else (True, False)


@pytest.mark.parametrize("row", SEEDED, ids=ident)
def test_solves_inside_the_limit(row):
    # Inside, in either order: the constructor follows the branch to a positive rupture gap and solve()
    # returns the bridge at contact and at rupture with the input volume (the solver matches it to its
    # Newton tolerance, 1e-12 relative in the residual; 1e-8 leaves room).
    V = INSIDE * float(row["vstar_limit"])
    for small_first in orders(row):
        b = bridge(row, V, small_first)
        assert b.rupture_gap > 0
        for gap in (0.0, b.rupture_gap):
            assert b.solve(gap, GAMMA)["volume"] == pytest.approx(V * R_SMALL ** 3, rel=1e-8)


@pytest.mark.parametrize("row", SEEDED, ids=ident)
def test_refuses_beyond_the_limit(row):
    # Beyond, in either order: no bridge at contact, the documented cause (the continuation in volume at
    # contact ends where the meniscus turns vertical at a contact line, or at the largest volume at contact).
    for small_first in orders(row):
        with pytest.raises(RuntimeError, match="no pendular bridge at contact"):
            bridge(row, BEYOND * float(row["vstar_limit"]), small_first)


@pytest.mark.parametrize("row", [r for r in SEEDED if r["geometry"] != "wall"], ids=ident)
@pytest.mark.parametrize("vstar", (1e-5, 0.1))
def test_swapping_the_solids_keeps_the_rupture_gap(row, vstar):
    # The solver scales lengths by R1 and follows a different continuation path in each order; both end at
    # the same fold, located by golden section to 1e-9 in arc length where the gap is stationary, after Newton
    # to 1e-12 (measured differences up to 1e-11 over the whole grid): 1e-9 still catches a fold found on one
    # path only, which differs by percents.
    a = bridge(row, vstar, small_first=True).rupture_gap
    b = bridge(row, vstar, small_first=False).rupture_gap
    assert b == pytest.approx(a, rel=1e-9, abs=0)


@pytest.mark.parametrize("row", [r for r in SEEDED if r["cause"] == "no bridge at contact" and float(r["vertical_margin_extrapolated_rad"]) < 0.02],
                         ids=ident)
def test_meniscus_vertical_at_the_limit(row):
    # The documented reason: just below the limit (0.998 of it) the contact line on the sphere the table names
    # is nearly where the meniscus leaves it vertically, beta + theta = pi. The margin pi - theta - beta falls
    # like sqrt(1 - V/V_limit) (measured at most 0.027 rad at 0.998 over every such case of the table);
    # 0.04 rad still fails where the solver stops for another reason (the folds before vertical stay 0.03-0.07
    # rad away at the limit itself).
    s = bridge(row, 0.998 * float(row["vstar_limit"])).solve(0.0, GAMMA)
    small = row["margin_on"] in ("small sphere", "sphere")
    beta = s["beta1"] if small else s["beta2"]
    theta = math.radians(float(row["theta_small_deg"] if small else row["theta_large_deg"]))
    assert 0 < math.pi - theta - beta < 0.04


def test_less_wetting_solid_first_at_a_large_volume():
    # Equal spheres at V* = 9.47, 70 deg on solid 1 and 10 deg on solid 2: the filling angle on solid 1 grows as
    # the gap opens, and the continuation's first step, which decreased it, led to a negative rupture gap
    # (-1.7e-10 m) where the swapped order finds 2.2855e-3 m. The two orders are one bridge: the same rupture gap
    # to 1e-9 relative (the continuation's own accuracy, as in the swap test above).
    V = 9.47 * R_SMALL ** 3
    first = kernels.YoungLaplaceBridge(R_SMALL, R_SMALL, V, math.radians(70), math.radians(10))
    swapped = kernels.YoungLaplaceBridge(R_SMALL, R_SMALL, V, math.radians(10), math.radians(70))
    assert swapped.rupture_gap > 1e-3
    assert first.rupture_gap == pytest.approx(swapped.rupture_gap, rel=1e-9)
