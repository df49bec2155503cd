"""The liquid shared over bonds (Richefeu2008 eq. 13-14 with the eligibility rule iii), kernels.share_liquid:
conservation, eligibility, a hand-computed case, the thresholds against the rupture rules, the dry pairs, bad input."""
import math

import numpy as np
import pytest

from yade_capillary import kernels


def candidates(n, seed=5):
    """n pairs of a polydisperse packing (radii of Richefeu's direct shear, 0.5-1 mm), gaps from overlap to 0.2 mm."""
    rng = np.random.default_rng(seed)
    R1, R2 = rng.choice([0.5e-3, 0.75e-3, 1e-3], n), rng.choice([0.5e-3, 0.75e-3, 1e-3], n)
    gaps = rng.uniform(-1e-5, 2e-4, n)
    return R1, R2, gaps


@pytest.mark.parametrize("rule", ["lian", "willett"])
def test_conservation_and_eligibility(rule):
    R1, R2, gaps = candidates(3000)
    theta = 0.2
    t = [kernels.bond_threshold(rule, a, b, g, theta) for a, b, g in zip(R1, R2, gaps)]
    c = [kernels.bond_cube(a, b) for a, b in zip(R1, R2)]
    liquid = 0.01 * sum(c) / 3  # alpha of order 0.01
    alpha, bonded = kernels.share_liquid(t, c, liquid)
    bonded = np.array(bonded)
    c, t = np.array(c), np.array(t)
    # eq. (13): all of the liquid is in bonds, V_b = alpha R^3 (eq. 14).
    assert abs(alpha * c[bonded].sum() / liquid - 1) < 1e-12
    # rule (iii): every bond is within the debonding distance of its own volume.
    for a, b, g in zip(R1[bonded], R2[bonded], gaps[bonded]):
        assert g <= kernels.rupture_distance(rule, a, b, alpha * kernels.bond_cube(a, b), theta) * (1 + 1e-9)
    # A dry pair is beyond reach at alpha, or would pull alpha below its own threshold by joining.
    S = c[bonded].sum()
    for ti, ci in zip(t[~bonded], c[~bonded]):
        assert ti > alpha or liquid / (S + ci) < ti
    assert bonded.sum() > (gaps <= 0).sum()  # bonds at a distance too


def test_hand_case():
    """Three pairs of 1 mm spheres, theta = 0 (lian: reach V^(1/3)): in contact, at 0.1 mm, at 0.5 mm."""
    R = 1e-3
    liquid = 2e-12  # alone on two pairs: alpha = 1e-3, V_b = 1e-12 m^3, reach 1e-4 m
    gaps = [0.0, 0.999e-4, 5e-4]
    t = [kernels.bond_threshold("lian", R, R, g) for g in gaps]
    c = [kernels.bond_cube(R, R)] * 3
    assert t[0] == 0
    assert t[1] == pytest.approx((0.999e-4 / R) ** 3, rel=1e-12)  # (gap / R)^3 with (1 + theta/2) = 1
    alpha, bonded = kernels.share_liquid(t, c, liquid)
    assert bonded == [True, True, False]
    assert alpha == pytest.approx(liquid / (2 * R ** 3), rel=1e-14)
    # At 0.1001 mm the second pair is out of reach of its would-be share: the contact alone holds the liquid.
    t[1] = kernels.bond_threshold("lian", R, R, 1.001e-4)
    alpha, bonded = kernels.share_liquid(t, c, liquid)
    assert bonded == [True, False, False] and alpha == pytest.approx(liquid / R ** 3, rel=1e-14)


@pytest.mark.parametrize("rule", ["lian", "willett", "willett_elskamp"])
def test_threshold_is_the_rupture_distance(rule):
    for R1, R2, gap, t1, t2 in ((1e-3, 0.6e-3, 5e-5, 0.1, 0.3), (1e-3, math.inf, 2e-5, 0.2, 0.2), (2e-3, 2e-3, 1e-4, 0.0, 0.0)):
        alpha = kernels.bond_threshold(rule, R1, R2, gap, t1, t2)
        assert kernels.rupture_distance(rule, R1, R2, alpha * kernels.bond_cube(R1, R2), t1, t2) == pytest.approx(gap, rel=1e-10)
    assert kernels.bond_cube(1e-3, math.inf) == pytest.approx((2e-3) ** 3, rel=1e-15)  # a wall: the pair of radius 2 R1
    assert kernels.bond_cube(1e-3, 0.25e-3) == pytest.approx((0.5e-3) ** 3, rel=1e-15)  # R = sqrt(R1 R2)


def test_kept_dry():
    n = 20000
    for fraction in (0.0, 0.5, 1.0):
        dry = [kernels.kept_dry(i, i + 1 + i % 7, fraction, 3) for i in range(n)]
        # binomial: 5 standard deviations
        assert abs(sum(dry) / n - fraction) <= 5 * math.sqrt(fraction * (1 - fraction) / n)
    pairs = [(i, 3 * i + 1) for i in range(2000)]
    a = [kernels.kept_dry(i, j, 0.5, 11) for i, j in pairs]
    assert a == [kernels.kept_dry(j, i, 0.5, 11) for i, j in pairs]  # the unordered pair
    assert a != [kernels.kept_dry(i, j, 0.5, 12) for i, j in pairs]  # another seed, other pairs


def test_bad_input():
    with pytest.raises(ValueError, match="liquid = -1e-12 m\\^3 is outside"):
        kernels.share_liquid([0.0], [1e-9], -1e-12)
    with pytest.raises(ValueError, match="reaches no pair"):
        kernels.share_liquid([1.0], [1e-9], 1e-15)  # alpha 1e-6 below the only threshold
    with pytest.raises(ValueError, match="dry fraction = 1.5"):
        kernels.kept_dry(1, 2, 1.5, 0)
