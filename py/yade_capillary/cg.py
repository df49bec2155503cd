"""Axisymmetric coarse-graining (Goldhirsch; Weinhart et al.) for rotating flows, in numpy.

Fields live on an (r, z) grid around the z axis; compression is positive. The kernel is a
Gaussian of width w in (r, z), normalised over the volume element 2 pi r dr dz:

    K(r, z; r_i, z_i) = exp(-((r - r_i)^2 + (z - z_i)^2) / (2 w^2)) / (2 pi w^2 * 2 pi r),

so that the integral of rho over space equals the total mass (up to the part of a kernel that
crosses the axis, negligible for r_i > 3w). Vectors and tensors are projected on the local
cylindrical basis (e_r, e_theta, e_z) of each particle or contact before averaging; averaging
Cartesian components over theta would cancel them.

Contact stress: sigma_c = sum over contacts of F (x) l * integral_0^1 K(x_I + s l) ds, with l
the branch vector from I to P and F the force on P (Goldhirsch 2010); the line integral is
evaluated with Gauss-Legendre nodes. For a contact with a wall or a fixed particle, pass the
contact point as x_I: the integral then runs from the flowing particle to the contact point.
"""
import numpy as np

GAUSS_NODES = 8


def cylindrical_basis(x):
    """Unit vectors (e_r, e_theta, e_z) at points x (n, 3); returns three (n, 3) arrays."""
    x = np.atleast_2d(x)
    r = np.hypot(x[:, 0], x[:, 1])
    er = np.stack([x[:, 0] / r, x[:, 1] / r, np.zeros_like(r)], axis=1)
    et = np.stack([-x[:, 1] / r, x[:, 0] / r, np.zeros_like(r)], axis=1)
    ez = np.tile([0.0, 0.0, 1.0], (len(x), 1))
    return er, et, ez


def to_cylindrical(v, x):
    """Components (v_r, v_theta, v_z) of vectors v (n, 3) at points x (n, 3)."""
    er, et, ez = cylindrical_basis(x)
    return np.stack([np.sum(v * er, 1), np.sum(v * et, 1), np.sum(v * ez, 1)], axis=1)


class Grid:
    """Evaluation grid: r nodes [m], z nodes [m], kernel width w [m]."""

    def __init__(self, r, z, w):
        self.r, self.z, self.w = np.asarray(r, float), np.asarray(z, float), float(w)
        self.R, self.Z = np.meshgrid(self.r, self.z, indexing="ij")

    def kernel(self, ri, zi):
        """K at every grid node for points (ri, zi) of shape (n,): array (n, nr, nz) [1/m^3]."""
        w = self.w
        d2 = (self.R[None] - ri[:, None, None]) ** 2 + (self.Z[None] - zi[:, None, None]) ** 2
        return np.exp(-d2 / (2 * w * w)) / (2 * np.pi * w * w * 2 * np.pi * self.R[None])

    def volume_elements(self):
        """2 pi r dr dz of every node (trapezoid weights) [m^3], for sum rules."""
        wr = np.gradient(self.r) if len(self.r) > 1 else np.ones(1)
        wz = np.gradient(self.z) if len(self.z) > 1 else np.ones(1)
        return 2 * np.pi * self.R * wr[:, None] * wz[None, :]


def _chunks(n, size=256):
    for s in range(0, n, size):
        yield slice(s, min(n, s + size))


def density_and_momentum(grid, x, v, m):
    """rho [kg/m^3] and momentum density (j_r, j_theta, j_z) [kg/(m^2 s)] on the grid."""
    x, v, m = np.atleast_2d(x), np.atleast_2d(v), np.asarray(m, float)
    r, z = np.hypot(x[:, 0], x[:, 1]), x[:, 2]
    vc = to_cylindrical(v, x)
    rho = np.zeros_like(grid.R)
    j = np.zeros((3,) + grid.R.shape)
    for sl in _chunks(len(m)):
        K = grid.kernel(r[sl], z[sl])
        rho += np.einsum("i,ijk->jk", m[sl], K)
        j += np.einsum("i,ia,ijk->ajk", m[sl], vc[sl], K)
    return rho, j


def angular_velocity(grid, rho, j):
    """omega = j_theta / (rho r) [1/s], NaN where there is no mass."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(rho > 0, j[1] / (rho * grid.R), np.nan)


def contact_stress(grid, xP, xI, F):
    """Contact stress tensor in cylindrical components, shape (3, 3, nr, nz) [Pa].

    xP: positions of the particles P (n, 3); xI: positions of their partners, or contact points
    for boundary contacts (n, 3); F: force on P (n, 3). Components are projected on the
    cylindrical basis at the middle of each branch.
    """
    xP, xI, F = np.atleast_2d(xP), np.atleast_2d(xI), np.atleast_2d(F)
    l = xP - xI
    mid = (xP + xI) / 2
    Fc, lc = to_cylindrical(F, mid), to_cylindrical(l, mid)
    s, wq = np.polynomial.legendre.leggauss(GAUSS_NODES)
    s, wq = (s + 1) / 2, wq / 2
    sigma = np.zeros((3, 3) + grid.R.shape)
    for sl in _chunks(len(F), 64):
        line = np.zeros((sl.stop - sl.start,) + grid.R.shape)
        for sq, wgt in zip(s, wq):
            p = xI[sl] + sq * l[sl]
            line += wgt * grid.kernel(np.hypot(p[:, 0], p[:, 1]), p[:, 2])
        sigma += np.einsum("ia,ib,ijk->abjk", Fc[sl], lc[sl], line)
    return sigma


def kinetic_stress(grid, x, v, m, omega_at):
    """Kinetic stress sum m v' (x) v' K [Pa], v' = v - omega(r_i, z_i) r_i e_theta.

    omega_at(r, z): the mean angular velocity at the particles (e.g. interpolated CG field).
    """
    x, v, m = np.atleast_2d(x), np.atleast_2d(v), np.asarray(m, float)
    r, z = np.hypot(x[:, 0], x[:, 1]), x[:, 2]
    vc = to_cylindrical(v, x)
    vc[:, 1] -= omega_at(r, z) * r
    sigma = np.zeros((3, 3) + grid.R.shape)
    for sl in _chunks(len(m)):
        sigma += np.einsum("i,ia,ib,ijk->abjk", m[sl], vc[sl], vc[sl], grid.kernel(r[sl], z[sl]))
    return sigma


def pressure_and_shear(sigma):
    """p = tr(sigma)/3 and tau = sqrt(sigma_r_theta^2 + sigma_z_theta^2) (the stresses that
    carry the azimuthal shear), from a symmetrised cylindrical stress (3, 3, ...) [Pa]."""
    s = 0.5 * (sigma + np.swapaxes(sigma, 0, 1))
    return (s[0, 0] + s[1, 1] + s[2, 2]) / 3, np.hypot(s[0, 1], s[2, 1])


def strain_rate(grid, omega):
    """gamma_dot = sqrt((r d omega/dr)^2 + (r d omega/dz)^2) [1/s]: twice the norm of the
    (r theta, z theta) strain-rate components of an azimuthal flow (convention written into
    every output of the shear-cell analysis)."""
    dr = np.gradient(omega, grid.r, axis=0) if len(grid.r) > 1 else 0 * omega
    dz = np.gradient(omega, grid.z, axis=1) if len(grid.z) > 1 else 0 * omega
    return np.hypot(grid.R * dr, grid.R * dz)
