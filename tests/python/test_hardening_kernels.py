"""Findings of the kernel stress campaign, one test each, through the Python API.

Each failed on the kernels before the hardening: the force was inf or NaN, the call hung, or the
error message lost the value. Expected behaviour: a ValueError naming the parameter (or the
dimensionless variable) with its value and allowed range, or a finite result with extrapolate.
"""
import math
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from yade_capillary import kernels

DEG = math.pi / 180


def test_outside_the_fit_is_refused_not_infinite():
    # Before: willett_full, R = 1 mm, V = 1e-19 m^3, theta = 70 deg gave F = inf inside the bridge
    # range. Gladkyy2014 section 2.3: Willett's fit holds for theta < 50 deg, V* < 0.1.
    with pytest.raises(ValueError) as e:
        kernels.force("willett_full", np.linspace(0, 1e-6, 50), 1e-3, 1e-3, 1e-19, 0.07, 70 * DEG)
    assert "V* = V/R^3 = 9.999999999999999e-11" in str(e.value) and "willett_full" in str(e.value)
    F = kernels.force("willett_full", np.linspace(0, 1e-6, 50), 1e-3, 1e-3, 1e-19, 0.07, 70 * DEG, extrapolate=True)
    assert np.all(np.isfinite(F)) and np.all(F >= 0) and np.all(np.diff(F) <= 1e-12 * F[0])


@pytest.mark.parametrize("kwargs,name", [
    (dict(R1=1e-150), "R1 = 1e-150"), (dict(R1=1e150), "R1 = 1e+150"), (dict(R2=1e150), "R2 = 1e+150"),
    (dict(volume=5e-324), "volume = 4.94065645841247e-324"), (dict(volume=1e300), "volume = 1e+300"),
    (dict(gamma=1e-300), "gamma = 1e-300"),
])
def test_absurd_input_names_the_parameter(kwargs, name):
    # Before: NaN or inf forces (radii 1e-150 / 1e150 m, volume 5e-324 m^3), or a bridge that
    # never breaks (volume 1e300 m^3: infinite rupture distance).
    args = dict(R1=1e-3, R2=1e-3, volume=1e-11, gamma=0.07, theta=0.1)
    args.update(kwargs)
    with pytest.raises(ValueError) as e:
        kernels.bridge("willett_reduced", **args)
    assert name in str(e.value) and "allowed range" in str(e.value)


def _returns_within(code, seconds):
    """Runs `code` in a fresh interpreter: a hang inside C++ cannot be interrupted in-process."""
    try:
        r = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=seconds)
    except subprocess.TimeoutExpired:
        return None
    return r


@pytest.mark.parametrize("call", [
    # Before: both hung (adaptive Simpson without a budget; the tolerance underflowed to 0).
    "kernels.bridge('linear_irreversible', 1e-3, 1e-3, 1e-11, 1e-300)",
    "kernels.bridge('linear_irreversible', 1e-3, 1e-3, 1e-19, 0.07, 70 * math.pi / 180)",
])
def test_calibration_never_hangs(call):
    r = _returns_within("""
        import math, sys
        from yade_capillary import kernels
        try:
            %s
        except ValueError as e:
            print("ValueError:", e)
    """ % call, 60)
    assert r is not None, "hung for 60 s: %s" % call
    assert r.returncode == 0 and "ValueError:" in r.stdout, r.stdout + r.stderr


def test_failed_calibration_names_what_failed():
    # Before: "linear_kc = -nan ..." although no linear_kc was given.
    with pytest.raises(ValueError) as e:
        kernels.bridge("linear_irreversible", 1e-3, 1e-3, 1e-19, 0.07, 70 * DEG)
    assert "linear_kc" not in str(e.value) and "nan" not in str(e.value)
    assert "theta1 = 1.22173047639603 rad" in str(e.value) or "V* = V/R^3" in str(e.value)
    # With extrapolation of the reference model the calibration succeeds.
    d = kernels.bridge("linear_irreversible", 1e-3, 1e-3, 1e-19, 0.07, 70 * DEG, extrapolate=True)
    assert math.isfinite(d["linear_kc"]) and d["linear_kc"] > 0 and d["rupture"] > 0


def test_messages_keep_the_value():
    # Before: "V* = 0.000000 is outside [1e-5, 0.1]" (std::to_string).
    with pytest.raises(ValueError) as e:
        kernels.bridge("young_laplace_table", 1e-3, 1e-3, 1e-16, 0.07)
    assert "1e-07" in str(e.value)


def test_strided_and_fortran_gap_arrays():
    # Before: a strided view (a[::2]) or a Fortran-ordered array was read as if contiguous, so the
    # forces belonged to other gaps, silently.
    args = ("willett_reduced",)
    kw = dict(R1=1e-3, R2=1e-3, volume=1e-11, gamma=0.07, theta=0.1)
    base = np.array([0.0, 9.0, 1e-5, 9.0, 2e-5, 9.0])
    expected = np.array([kernels.force(*args, float(g), **kw) for g in base[::2]])
    assert np.array_equal(kernels.force(*args, base[::2], **kw), expected)
    grid = np.asfortranarray(np.array([[0.0, 1e-5, 2e-5], [3e-5, 4e-5, 5e-5]]))
    F = kernels.force(*args, grid, **kw)
    assert F.shape == grid.shape
    assert all(F[i, j] == kernels.force(*args, float(grid[i, j]), **kw) for i in range(2) for j in range(3))


def test_unused_and_unknown_parameters_are_named():
    with pytest.raises(ValueError, match="calibrate_from = 'foo' is unknown"):
        kernels.bridge("linear_irreversible", 1e-3, 1e-3, 1e-11, 0.07, calibrate_from="foo")
    with pytest.raises(ValueError, match=r"linear_fmax = -5 N is outside the allowed range \{0\} \(not used by model willett_full\)"):
        kernels.bridge("willett_full", 1e-3, 1e-3, 1e-11, 0.07, linear_fmax=-5)
    with pytest.raises(ValueError, match=r"calibrate_from = young_laplace_table: theta2 = 1\.3 rad is outside the allowed range \[0, 1\.2217304763960306\]"):
        kernels.bridge("linear_irreversible", 1e-3, 1e-3, 1e-11, 0.07, 0.1, 1.3, calibrate_from="young_laplace_table")
