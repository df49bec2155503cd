"""Axisymmetric coarse-graining and the shear-cell fits, against closed-form sum rules and
synthetic data with known answers."""
import math

import numpy as np
import pytest

from yade_capillary import cg, fits

RNG = np.random.default_rng(4)


def annulus_particles(n, r0=0.03, r1=0.07, z0=0.01, z1=0.03):
    r = np.sqrt(RNG.uniform(r0 ** 2, r1 ** 2, n))
    t = RNG.uniform(0, 2 * np.pi, n)
    z = RNG.uniform(z0, z1, n)
    return np.stack([r * np.cos(t), r * np.sin(t), z], axis=1)


GRID = cg.Grid(np.linspace(0.005, 0.1, 191), np.linspace(-0.01, 0.05, 121), 2e-3)


def test_windowed_kernel_equals_full_kernel():
    # On a uniform grid accumulate() evaluates only the nodes within CUTOFF w of each point; the
    # same sums over every node (kernel(), cut at CUTOFF w too) must agree to round-off, for points
    # inside, at the edges and outside the grid.
    x = annulus_particles(400, r0=0.0, r1=0.11, z0=-0.02, z1=0.06)
    r, z = np.hypot(x[:, 0], x[:, 1]), x[:, 2]
    weights = RNG.normal(size=(len(r), 3))
    assert GRID.uniform
    windowed = GRID.accumulate(r, z, weights)
    full = cg.Grid(GRID.r, GRID.z, GRID.w)
    full.uniform = False
    dense = full.accumulate(r, z, weights)
    assert np.abs(windowed - dense).max() <= 1e-12 * np.abs(dense).max()
    # and the cut is where the Gaussian is below 2e-8 of its peak
    assert math.exp(-cg.CUTOFF ** 2 / 2) < 2e-8


def test_mass_sum_rule():
    # integral of rho over space = total mass (kernel normalised over 2 pi r dr dz)
    x = annulus_particles(300)
    m = RNG.uniform(1e-4, 2e-4, len(x))
    rho, _ = cg.density_and_momentum(GRID, x, np.zeros_like(x), m)
    assert np.sum(rho * GRID.volume_elements()) == pytest.approx(m.sum(), rel=1e-4)


def test_solid_body_rotation():
    # v = Omega e_z x X: omega = Omega inside the material, up to the kernel average of r_i/r,
    # which differs from 1 by O(w^2/r^2) (< 1e-3 for r >= 0.04 m, w = 1 mm). Particles on a
    # regular (r, z) lattice with random azimuths, so that no sampling noise enters.
    grid = cg.Grid(np.linspace(0.04, 0.06, 11), np.linspace(0.015, 0.025, 5), 1e-3)
    rr, zz = np.meshgrid(np.arange(0.03, 0.07, 2e-4), np.arange(0.01, 0.03, 2e-4), indexing="ij")
    t = RNG.uniform(0, 2 * np.pi, rr.size)
    x = np.stack([rr.ravel() * np.cos(t), rr.ravel() * np.sin(t), zz.ravel()], axis=1)
    Omega = 0.3
    v = Omega * np.stack([-x[:, 1], x[:, 0], np.zeros(len(x))], axis=1)
    rho, j = cg.density_and_momentum(grid, x, v, np.ones(len(x)))
    assert np.allclose(cg.angular_velocity(grid, rho, j), Omega, rtol=1e-3)
    assert np.allclose(j[0], 0, atol=1e-9 * np.abs(j[1]).max()) and np.allclose(j[2], 0, atol=1e-9 * np.abs(j[1]).max())


def test_virial_sum_rule():
    # integral of sigma_c over space = sum of F (x) l in the cylindrical basis of each branch
    n = 200
    xI = annulus_particles(n)
    l = RNG.normal(0, 2e-3, (n, 3))
    F = RNG.normal(0, 1e-3, (n, 3))
    sigma = cg.contact_stress(GRID, xI + l, xI, F)
    mid = xI + l / 2
    expected = np.einsum("ia,ib->ab", cg.to_cylindrical(F, mid), cg.to_cylindrical(l, mid))
    integral = np.einsum("abjk,jk->ab", sigma, GRID.volume_elements())
    assert np.allclose(integral, expected, rtol=1e-4, atol=1e-4 * np.abs(expected).max())


def test_three_sphere_stack_under_gravity():
    # Three spheres (mass m, radius R) stacked on a floor: contact forces m g, 2 m g, 3 m g with
    # branch lengths 2R, 2R, R (the floor contact integrates to the contact point), so the
    # integral of sigma_zz is (2 + 4 + 3) R m g (static equilibrium, compression positive).
    R, m, g, r0 = 2e-3, 1e-4, 9.81, 0.05
    c = np.array([[r0, 0, R], [r0, 0, 3 * R], [r0, 0, 5 * R]])
    xP = np.array([c[2], c[1], c[0]])
    xI = np.array([c[1], c[0], [r0, 0, 0]])
    F = np.array([[0, 0, m * g], [0, 0, 2 * m * g], [0, 0, 3 * m * g]])
    sigma = cg.contact_stress(GRID, xP, xI, F)
    assert np.sum(sigma[2, 2] * GRID.volume_elements()) == pytest.approx(9 * R * m * g, rel=1e-4)
    p, tau = cg.pressure_and_shear(sigma)
    assert np.all(tau == 0) and np.all(p >= 0)


def test_line_integral_against_fine_quadrature():
    # Gauss-Legendre line integral of the kernel equals a 4001-point trapezoid of the same kernel,
    # within 1e-6, and within the level of the cut (e^-18 of the peak) at the nodes near CUTOFF w,
    # where the cut kernel jumps.
    xI, xP = np.array([[0.05, 0.01, 0.02]]), np.array([[0.053, 0.012, 0.0215]])
    F = np.array([[1.0, 0.0, 0.0]])
    grid = cg.Grid(np.linspace(0.045, 0.06, 16), np.linspace(0.015, 0.027, 13), 1.5e-3)
    sigma = cg.contact_stress(grid, xP, xI, F)
    s = np.linspace(0, 1, 4001)
    pts = xI + s[:, None] * (xP - xI)
    K = grid.kernel(np.hypot(pts[:, 0], pts[:, 1]), pts[:, 2])
    line = np.trapz(K, s, axis=0)
    mid = (xP + xI) / 2
    Fc, lc = cg.to_cylindrical(F, mid)[0], cg.to_cylindrical(xP - xI, mid)[0]
    expected = Fc[0] * lc[0] * line
    assert np.allclose(sigma[0, 0], expected, rtol=1e-6, atol=2e-8 * np.abs(expected).max())


def test_erf_fit_recovers_band():
    r = np.linspace(0.02, 0.1, 60)
    y = fits.erf_profile(r, 0.071, 0.009) + RNG.normal(0, 0.01, len(r))
    f = fits.fit_band(r, y)
    assert abs(f["Rc_m"] - 0.071) < 4 * f["Rc_err_m"] and abs(f["W_m"] - 0.009) < 4 * f["W_err_m"]
    assert f["Rc_err_m"] < 1e-3


def test_yield_fit_recovers_mu_c_and_errors():
    # tau = mu p + c with Gaussian noise s: the standard errors equal the textbook formulas.
    mu, c, s = 0.13, 1.3, 0.2
    p = np.linspace(5, 60, 200)
    tau = mu * p + c + RNG.normal(0, s, len(p))
    f = fits.fit_yield(p, tau)
    Sxx = np.sum((p - p.mean()) ** 2)
    assert abs(f["mu"] - mu) < 4 * f["mu_err"] and abs(f["c_Pa"] - c) < 4 * f["c_err_Pa"]
    assert f["mu_err"] == pytest.approx(s / math.sqrt(Sxx), rel=0.25)
    assert f["c_err_Pa"] == pytest.approx(s * math.sqrt(1 / len(p) + p.mean() ** 2 / Sxx), rel=0.25)


def test_fits_refuse_too_few_points():
    with pytest.raises(ValueError, match="at least 4"):
        fits.fit_band([0.1, 0.2], [0.1, 0.9])
    with pytest.raises(ValueError, match="at least 3"):
        fits.fit_yield([1.0, 2.0], [0.1, 0.2])
