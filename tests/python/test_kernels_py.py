"""The pybind11 module in plain python3: API, vectorisation, docstrings, errors, case table."""
import math
import os
import re

import numpy as np
import pytest

from yade_capillary import cases, kernels

MODELS_DOC = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "models.md")
W11 = cases.case("W11")
ARGS = dict(R1=W11.R1_m, R2=W11.R2_m, volume=W11.volume_m3, gamma=W11.gamma_N_m, theta=W11.theta_rad)


def documented_models():
    """The names in the model table of docs/models.md (section "The models"), in their order."""
    with open(MODELS_DOC) as f:
        section = f.read().split("\n## The models", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"^\| `([a-z_]+)` \|", section, flags=re.M)


def test_model_and_rule_names_as_documented():
    # The compiled list (CAPILLARY_MODELS) and the users' table must name the same models in the same order.
    assert kernels.MODEL_NAMES == documented_models()
    assert kernels.RUPTURE_NAMES == ["lian", "willett", "willett_elskamp"]


def test_docstrings_state_units():
    for fn in (kernels.force, kernels.bridge, kernels.rupture_distance):
        assert "[m]" in fn.__doc__ and "ValueError" in fn.__doc__


@pytest.mark.parametrize("model", kernels.MODEL_NAMES)
def test_vectorised_equals_scalar(model):
    ac = kernels.bridge(model, **ARGS)["rupture"]
    a = np.linspace(-0.1 * ac, 1.2 * ac, 57)
    F = kernels.force(model, a, **ARGS)
    assert F.shape == a.shape
    assert all(F[i] == kernels.force(model, float(a[i]), **ARGS) for i in range(len(a)))
    assert np.all(F[a > ac] == 0.0)  # zero beyond rupture


def test_derjaguin_limit_through_python():
    # Gladkyy eq. (8) at a = 0: 2 pi R gamma cos(theta), R = harmonic mean (eq. 1)
    R = 2 * W11.R1_m * W11.R2_m / (W11.R1_m + W11.R2_m)
    assert kernels.force("willett_reduced", 0.0, **ARGS) == pytest.approx(2 * math.pi * R * W11.gamma_N_m, rel=1e-14)


@pytest.mark.parametrize("kwargs,words", [
    (dict(volume=-1e-12), ["volume", "allowed range"]),
    (dict(gamma=0.0), ["gamma"]),
    (dict(theta=math.pi / 2), ["theta1", "pi/2"]),
    (dict(theta=float("nan")), ["theta1"]),
    (dict(R1=0.0), ["R1"]),
])
def test_bad_input_names_parameter(kwargs, words):
    with pytest.raises(ValueError) as e:
        kernels.force("willett_full", 1e-5, **dict(ARGS, **kwargs))
    assert all(w in str(e.value) for w in words)


def test_bad_names_and_nan_gap():
    with pytest.raises(ValueError, match="model = 'Willett_numeric' is unknown; allowed: weigert"):
        kernels.force("Willett_numeric", 0.0, **ARGS)
    with pytest.raises(ValueError, match="rupture = 'pitois'"):
        kernels.rupture_distance("pitois", 1e-3, 1e-3, 1e-11)
    with pytest.raises(ValueError, match="gap is NaN"):
        kernels.force("willett_full", np.array([0.0, float("nan")]), **ARGS)


def test_wall_is_infinite_radius():
    d = kernels.bridge("willett_reduced", 1e-3, float("inf"), 1e-11, 0.07)
    assert d["R"] == 2e-3 and d["force0"] == pytest.approx(4 * math.pi * 1e-3 * 0.07, rel=1e-14)


def test_table1_has_13_cases_in_si():
    t = cases.GLADKYY2014_TABLE1
    assert len(t) == 13 and [c.code for c in t][:3] == ["W11", "W12", "W13"]
    assert W11.volume_m3 == pytest.approx(13.6e-12) and cases.case("R1").volume_m3 == pytest.approx(2e-19)
    assert cases.case("R3").theta_rad == pytest.approx(math.radians(10))
    with pytest.raises(ValueError, match="allowed: W11"):
        cases.case("W99")
