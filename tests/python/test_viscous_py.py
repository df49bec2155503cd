"""The viscous bridge kernels through Python: printed formulas (Elskamp 2018 eq. 25, 26, 28, 29, 33), signs, docstrings, errors."""
import math

import pytest

from yade_capillary import kernels

R, V, ETA, SIGMA = 4e-3, 5e-10, 0.1, 21e-3  # Pitois' validation case, Elskamp 2018 section 3.1


def reff(r1, r2):
    return r1 * r2 / (r1 + r2)  # reduced radius, Elskamp after eq. (25)


def test_names_and_exports():
    assert kernels.VISCOUS_NAMES == ["pitois", "adams_perchard"]
    for name in ("viscous_normal_force", "viscous_tangential", "dynamic_rupture_distance", "viscous_laws", "VISCOUS_NAMES"):
        assert name in kernels.__all__


def test_docstrings_state_units():
    for fn in (kernels.viscous_normal_force, kernels.viscous_tangential, kernels.dynamic_rupture_distance):
        assert "[m]" in fn.__doc__ and "[Pa s]" in fn.__doc__ and "ValueError" in fn.__doc__


@pytest.mark.parametrize("S", [0.0, 1e-6, 1e-4, 1e-3])
def test_normal_against_eq_25_26(S):
    r2 = 3e-3
    rs = reff(R, r2)
    Se = S + 0.001 * rs  # S_min added to S
    vn = 0.01
    adams = 6 * math.pi * ETA * rs ** 2 * vn / Se
    pitois = adams * (1 - 1 / math.sqrt(1 + V / (math.pi * rs * Se ** 2))) ** 2
    assert kernels.viscous_normal_force("adams_perchard", S, vn, R, r2, ETA) == pytest.approx(-adams, rel=1e-13)
    assert kernels.viscous_normal_force("pitois", S, vn, R, r2, ETA, volume=V) == pytest.approx(-pitois, rel=1e-10)
    assert kernels.viscous_normal_force("pitois", S, -vn, R, r2, ETA, volume=V) > 0  # separating: pulled back


def test_tangential_against_eq_28_29_and_wall():
    rs = R / 2
    for S, near in ((1e-5, True), (5e-4, False)):
        d = kernels.viscous_tangential(S, (0, 0, 1), (0.01, 0, 0.5), R, R, ETA)  # translation only, v_n ignored
        Se = S + 0.001 * rs
        assert d["near"] is near
        assert d["c_t"] == pytest.approx(6 * math.pi * ETA * rs * (8 / 15 * math.log(rs / Se) + 0.9588), rel=1e-12)
        assert d["force"][0] == pytest.approx(-d["c_t"] * 0.01, rel=1e-12) and d["force"][2] == 0
        cr = (6 * math.pi * ETA * rs * (2 / 15 * math.log(rs / Se) - 0.2526) if near else
              6 * math.pi * ETA * rs / 8 * (rs / (Se + rs)) ** 4 * (1 - 3 * rs / (8 * (Se + rs))))
        assert d["c_r"] == pytest.approx(cr, rel=1e-12)
    w = kernels.viscous_tangential(1e-5, (0, 0, 1), (0.01, 0, 0), R, float("inf"), ETA, omega1=(0, 3, 0))
    assert all(math.isfinite(x) for x in w["force"] + w["moment1"]) and w["moment2"] == [0, 0, 0]


def test_dynamic_rupture_eq_33():
    assert kernels.dynamic_rupture_distance(1e-3, 0.01, ETA, SIGMA) == pytest.approx(1e-3 * (1 + math.sqrt(0.01 * ETA / SIGMA)), rel=1e-15)
    assert kernels.dynamic_rupture_distance(1e-3, 0.01, 0.0, SIGMA) == 1e-3


def test_eta_zero_is_exactly_zero():
    assert kernels.viscous_normal_force("pitois", 0.0, 5.0, R, R, 0.0, volume=V) == 0
    d = kernels.viscous_tangential(0.0, (1, 0, 0), (1, 2, 3), R, R, 0.0, omega1=(1, 1, 1), omega2=(2, 2, 2))
    assert d["force"] == [0, 0, 0] and d["moment1"] == [0, 0, 0] and d["moment2"] == [0, 0, 0]


@pytest.mark.parametrize("call, name", [
    (lambda: kernels.viscous_normal_force("stokes", 1e-5, 0.1, R, R, ETA, volume=V), "pitois, adams_perchard"),
    (lambda: kernels.viscous_normal_force("pitois", 1e-5, 0.1, R, R, -1.0, volume=V), "eta"),
    (lambda: kernels.viscous_normal_force("pitois", 1e-5, 0.1, R, R, ETA), "V* = V/R^3"),
    (lambda: kernels.viscous_normal_force("pitois", float("nan"), 0.1, R, R, ETA, volume=V), "S ="),
    (lambda: kernels.viscous_normal_force("pitois", 1e-5, 0.1, -R, R, ETA, volume=V), "R1"),
    (lambda: kernels.viscous_normal_force("pitois", 1e-5, 0.1, R, R, ETA, volume=V, S_min_factor=0), "S_min_factor"),
    (lambda: kernels.viscous_tangential(1e-5, (1, 1, 0), (0, 0, 0), R, R, ETA), "|n|"),
    (lambda: kernels.viscous_tangential(1e-5, (1, 0, 0), (0, float("inf"), 0), R, R, ETA), "v_rel[1]"),
    (lambda: kernels.dynamic_rupture_distance(1e-3, 0.1, ETA, 0.0), "gamma"),
    (lambda: kernels.dynamic_rupture_distance(-1e-3, 0.1, ETA, SIGMA), "static_rupture"),
])
def test_bad_input_raises_value_error_naming_it(call, name):
    with pytest.raises(ValueError) as e:
        call()
    assert name in str(e.value)
