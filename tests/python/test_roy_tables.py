"""Roy, Singh, Luding & Weinhart (micro-macro transition of wet granular flows), eq. (29) and (31):
the adhesive stiffnesses k_a of the linear irreversible model (Roy eq. 16, 17) equivalent to the liquid
bridge model for the volumes of Roy eq. (3), recomputed with our kernels.

Roy's liquid bridge model is our willett_reduced (Roy eq. 12 = Gladkyy eq. 8: 1 + 1.05 S + 2.5 S^2 with
S = s sqrt(r/V_b), the full separation s) with the rupture distance of Lian, S_c = (1 + theta/2) V_b^(1/3)
(Roy eq. 15, our rupture rule `lian`). Parameters (Roy table 1 and section 4): monodisperse
d_p = 2.20 mm, i.e. R1 = R2 = 1.1 mm and effective radius r = d_p/2 (Roy eq. 14), so that
F(0) = 2 pi r gamma cos(theta) = pi d_p gamma cos(theta) (Roy eq. 13); theta = 20 deg;
gamma = 0.020 N/m.

* eq. (29), equal maximum force and equal interaction distance (section 4.1):
  k_a = f_max / S_c, with f_max and S_c of the liquid bridge model;
* eq. (31), equal maximum force and equal adhesive energy (section 4.2): our calibrated
  linear_irreversible, k_a = f_max^2 / (2 E), E the integral of F over [0, S_c].

Roy prints two digits. Eq. (29) lists nine values for the ten volumes of eq. (3) (0 nl gives
infinity): they match 140, 75, 20, 14, 8, 4.2, 2, 1, 0 nl, i.e. 200 nl is not in eq. (29).
Eq. (31) lists all ten, in the same (decreasing volume) order.

Tolerance: 1.5 % (two printed digits round by up to 0.005/0.21 = 2.4 % at the smallest value).
Largest deviations accepted: eq. (29) 140 nl 0.2130 (printed 0.21, 1.4 %, rounding) and 8 nl 0.5530
(printed 0.56, 1.3 %: not a rounding of ours, small enough to leave unexplained); eq. (31) 2 nl 2.1198
(printed 2.11, 0.5 %).

The 20 nl entry of eq. (31) is printed 0.74 and we get 0.7151 (3.4 % lower, not a rounding: 0.72).
Explanation: 0.74 is what one gets when the adhesive energy of the 20 nl bridge is integrated up to
V_b^(1/3) instead of (1 + theta/2) V_b^(1/3), i.e. the rupture distance without Lian's contact-angle
factor (Roy eq. 15 with theta = 0) while keeping cos(theta) in the force: 0.7405, within 0.1 % of the
printed value. That k_a (= f_max^2 / 2E) scales with cos(theta) for this model (F and E are both
proportional to cos(theta), the shape does not depend on it), so it equals cos(20 deg) times our
calibrated k_a at theta = 0 with the lian rule, which the test checks to 0.2 %. No other entry matches
that variant (checked below), and Roy's eq. (29) value for 20 nl (0.41) uses the full Lian distance,
so the slip is in that one number of eq. (31). Other candidates do not explain it: the volume that
gives 0.74 with the full rule is 18.6 nl (not a volume of eq. 3), and r = d_p instead of d_p/2 gives 1.9.
"""
import math

import pytest

import numpy as np

from yade_capillary import kernels

D_P = 2.20e-3          # mean particle diameter [m] (Roy table 1)
R = D_P / 2            # sphere radius [m]; effective radius r = R (Roy eq. 14, monodisperse)
GAMMA = 0.020          # surface tension [N/m] (Roy sections 4.1, 4.2)
THETA = math.radians(20)  # contact angle (Roy table 1)
NL = 1e-12             # 1 nl in m^3
# Roy uses his eq. (12) up to 200 nl, V* = V/R^3 = 0.15, beyond Willett's range V* <= 0.1 (Gladkyy2014
# section 2.3): our kernels refuse the 140 and 200 nl bridges (V* = 0.105, 0.15), so those entries are
# checked with the formula itself, written out in literal_kc().
def outside_willett(volume_nl):
    return volume_nl * NL / R ** 3 > 0.1

# Roy eq. (29): k_a [N/m], equal maximum force and interaction distance; volume [nl] -> printed value.
EQ29 = {140: 0.21, 75: 0.26, 20: 0.41, 14: 0.46, 8: 0.56, 4.2: 0.69, 2: 0.88, 1: 1.11, 0: math.inf}
# Roy eq. (31): k_a [N/m], equal maximum force and adhesive energy; volume [nl] -> printed value.
EQ31 = {200: 0.25, 140: 0.29, 75: 0.39, 20: 0.74, 14: 0.84, 8: 1.10, 4.2: 1.49, 2: 2.11, 1: 2.95, 0: math.inf}
RTOL = 0.015           # two printed digits (see the module docstring)
RTOL_20NL_VARIANT = 0.002  # the explained 20 nl entry of eq. (31), reproduced with its variant


def liquid_bridge(volume_nl, theta=THETA):
    return kernels.bridge("willett_reduced", R, R, volume_nl * NL, GAMMA, theta, rupture="lian")


def equal_distance_kc(volume_nl):
    b = liquid_bridge(volume_nl)
    return b["force0"] / b["rupture"]  # Roy eq. (17): S_c = f_max / k_a


def equal_energy_kc(volume_nl, theta=THETA):
    lin = kernels.bridge("linear_irreversible", R, R, volume_nl * NL, GAMMA, theta, rupture="lian",
                         calibrate_from="willett_reduced")
    return lin["linear_kc"]


def literal_kc(volume_nl, equal_energy, theta=THETA, n=200001):
    """Roy eq. (31) (equal_energy) or (29) from his eq. (12), (13), (15) written out here: kc = fmax^2 / (2 E),
    E the integral of the force up to the rupture distance (trapezoid rule on n points), or fmax / S_c."""
    V = volume_nl * NL
    fmax = math.pi * D_P * GAMMA * math.cos(theta)                     # Roy eq. (13)
    s = np.linspace(0, (1 + theta / 2) * V ** (1 / 3), n)               # Roy eq. (15)
    S = s * math.sqrt(R / V)
    F = fmax / (1 + 1.05 * S + 2.5 * S * S)                              # Roy eq. (12)
    E = float(np.sum((F[1:] + F[:-1]) / 2 * np.diff(s)))
    return fmax * fmax / (2 * E) if equal_energy else fmax / s[-1]


def test_literal_energy_integration_agrees_with_the_kernels():
    assert literal_kc(75, True) == pytest.approx(equal_energy_kc(75), rel=1e-8)
    assert literal_kc(75, False) == pytest.approx(equal_distance_kc(75), rel=1e-12)
    for v in (140, 200):
        with pytest.raises(ValueError, match=r"V\* = V/R\^3 = 0.1.*willett_reduced"):
            liquid_bridge(v)


def test_reference_model_is_roy_eq_12_13_15():
    b = liquid_bridge(20)
    assert b["force0"] == pytest.approx(math.pi * D_P * GAMMA * math.cos(THETA), rel=1e-14)  # Roy eq. (13)
    assert b["rupture"] == pytest.approx((1 + THETA / 2) * (20 * NL) ** (1 / 3), rel=1e-14)  # Roy eq. (15)
    s = 0.4 * b["rupture"]
    S = s * math.sqrt(R / (20 * NL))
    F = kernels.force("willett_reduced", s, R, R, 20 * NL, GAMMA, THETA, rupture="lian")
    assert F == pytest.approx(math.pi * D_P * GAMMA * math.cos(THETA) / (1 + 1.05 * S + 2.5 * S * S), rel=1e-13)  # Roy eq. (12)


def test_calibration_keeps_max_force_and_energy():
    lin = kernels.bridge("linear_irreversible", R, R, 20 * NL, GAMMA, THETA, rupture="lian", calibrate_from="willett_reduced")
    ref = liquid_bridge(20)
    assert lin["linear_fmax"] == pytest.approx(ref["force0"], rel=1e-14)
    assert lin["energy"] == pytest.approx(ref["energy"], rel=1e-9)


@pytest.mark.parametrize("volume_nl", sorted(EQ29))
def test_eq29_equal_interaction_distance(volume_nl):
    printed = EQ29[volume_nl]
    if volume_nl == 0:  # a 0 nl bridge has no range: k_a = infinity (our kernels refuse volume 0)
        with pytest.raises(ValueError, match="volume"):
            liquid_bridge(0)
        return
    kc = literal_kc(volume_nl, False) if outside_willett(volume_nl) else equal_distance_kc(volume_nl)
    print("eq. (29) %5g nl: ours %.4f N/m, Roy %.2f (%+.2f %%)" % (volume_nl, kc, printed, 100 * (kc / printed - 1)))
    assert kc == pytest.approx(printed, rel=RTOL)


@pytest.mark.parametrize("volume_nl", sorted(EQ31))
def test_eq31_equal_adhesive_energy(volume_nl):
    printed = EQ31[volume_nl]
    if volume_nl == 0:
        with pytest.raises(ValueError, match="volume"):
            equal_energy_kc(0)
        return
    kc = literal_kc(volume_nl, True) if outside_willett(volume_nl) else equal_energy_kc(volume_nl)
    print("eq. (31) %5g nl: ours %.4f N/m, Roy %.2f (%+.2f %%)" % (volume_nl, kc, printed, 100 * (kc / printed - 1)))
    if volume_nl == 20:
        # The documented exception (module docstring): 3.4 % below the printed 0.74 with the full Lian rule ...
        assert kc / printed - 1 == pytest.approx(-0.034, abs=0.002)
        # ... and reproduced by the rupture distance V^(1/3) (Lian without (1 + theta/2)), cos(theta) kept:
        variant = math.cos(THETA) * equal_energy_kc(20, theta=0.0)
        print("eq. (31)    20 nl with S_c = V^(1/3): %.4f N/m" % variant)
        assert variant == pytest.approx(printed, rel=RTOL_20NL_VARIANT)
    else:
        assert kc == pytest.approx(printed, rel=RTOL)


def test_20nl_variant_matches_no_other_entry():
    # The V^(1/3) variant is specific to the 20 nl entry: for every other volume it misses Roy's value.
    for v, printed in EQ31.items():
        if v in (0, 20):
            continue
        variant = math.cos(THETA) * literal_kc(v, True, theta=0.0)
        assert abs(variant / printed - 1) > 0.02, v
