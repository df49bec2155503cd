"""The Mohr-Coulomb fits of the direct shear test (yade_capillary.directshear): mohr_coulomb exact on points of a
line, the standard errors of a two-point line from the errors of tau by propagation, one normal stress refused;
common_friction (one friction angle for every water content) exact on parallel lines, the error of a cohesion
difference by propagation, and refused without two normal stresses."""
import math

import pytest

from yade_capillary import directshear as ds


def test_line_is_exact():
    c, phi = 120.0, 25.0
    sigmas = [300.0, 600.0, 900.0]
    taus = [c + s * math.tan(math.radians(phi)) for s in sigmas]
    fc, se_c, fphi, se_phi = ds.mohr_coulomb(sigmas, taus, [5.0, 5.0, 5.0])
    assert fc == pytest.approx(c, rel=1e-12) and fphi == pytest.approx(phi, rel=1e-12)


def test_two_points_propagate_the_errors():
    # tau1 = c + s1 m, tau2 = c + s2 m: c = (s2 tau1 - s1 tau2)/(s2 - s1), var c = (s2^2 e1^2 + s1^2 e2^2)/(s2 - s1)^2.
    s1, s2, e1, e2 = 300.0, 900.0, 10.0, 20.0
    _, se_c, _, _ = ds.mohr_coulomb([s1, s2], [250.0, 500.0], [e1, e2])
    assert se_c == pytest.approx(math.sqrt(s2 ** 2 * e1 ** 2 + s1 ** 2 * e2 ** 2) / (s2 - s1), rel=1e-12)


def test_one_stress_refused():
    with pytest.raises(ValueError, match="two different normal stresses"):
        ds.mohr_coulomb([300.0, 300.0], [200.0, 210.0], [5.0, 5.0])


def _runs(points):
    return [dict(w=w, sigma_plane_Pa=s, tau_residual_Pa=t, tau_se_Pa=e) for w, s, t, e in points]


def test_parallel_lines_are_exact():
    m = math.tan(math.radians(30.0))
    runs = _runs([(0.0, 80.0, 10 + 80 * m, 5.0), (0.0, 370.0, 10 + 370 * m, 30.0), (0.01, 81.0, 90 + 81 * m, 8.0), (0.01, 372.0, 90 + 372 * m, 20.0)])
    f = ds.common_friction(runs)
    assert f["phi_deg"] == pytest.approx(30.0, rel=1e-12)
    assert f["c_Pa"][0.0] == pytest.approx(10.0, rel=1e-9) and f["c_Pa"][0.01] == pytest.approx(90.0, rel=1e-9)


def test_difference_at_equal_stresses():
    # Two water contents at the same two stresses s1, s2 with equal errors e: each c is its mean tau less m times
    # the mean stress, so the difference is the difference of the mean taus, free of the slope's error: var = e^2
    # (against 2 e^2 (s1^2 + s2^2)/(s2 - s1)^2 for two lines fitted alone). The points lie on parallel lines
    # (chi2 = 0, no rescaling).
    s1, s2, e, m = 100.0, 400.0, 7.0, 0.8
    runs = _runs([(0.0, s1, 5 + s1 * m, e), (0.0, s2, 5 + s2 * m, e), (0.01, s1, 70 + s1 * m, e), (0.01, s2, 70 + s2 * m, e)])
    f = ds.common_friction(runs)
    cov = f["c_cov_Pa2"]
    var = cov[0.0][0.0] + cov[0.01][0.01] - 2 * cov[0.0][0.01]
    assert var == pytest.approx(e ** 2, rel=1e-9)


def test_common_friction_needs_two_stresses():
    with pytest.raises(ValueError, match="two different normal stresses"):
        ds.common_friction(_runs([(0.0, 300.0, 200.0, 5.0), (0.01, 300.0, 260.0, 5.0)]))
