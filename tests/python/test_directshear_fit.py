"""The Mohr-Coulomb fit of the direct shear test (yade_capillary.directshear.mohr_coulomb): exact on points of a
line, the standard errors of a two-point line from the errors of tau by propagation, one normal stress refused."""
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
