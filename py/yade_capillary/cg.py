"""Axisymmetric coarse-graining (Goldhirsch; Weinhart et al.) for rotating flows, in numpy.

Fields live on an (r, z) grid around the z axis; compression is positive. The kernel is a
Gaussian of width w in (r, z), normalised over the volume element 2 pi r dr dz:

    K(r, z; r_i, z_i) = exp(-((r - r_i)^2 + (z - z_i)^2) / (2 w^2)) / (2 pi w^2 * 2 pi r),

so that the integral of rho over space equals the total mass (up to the part of a kernel that
crosses the axis, negligible for r_i > 3w). Vectors and tensors are projected on the local
cylindrical basis (e_r, e_theta, e_z) of each particle or contact before averaging; averaging
Cartesian components over theta would cancel them.

The kernel is cut at CUTOFF = 6 widths in r and in z (a square window: its factors in r and z stay separable).

Contact stress: sigma_c = sum over contacts of F (x) l * integral_0^1 K(x_I + s l) ds, with l
the branch vector from I to P and F the force on P (Goldhirsch 2010); the line integral is
evaluated with Gauss-Legendre nodes. For a contact with a wall or a fixed particle, pass the
contact point as x_I: the integral then runs from the flowing particle to the contact point.

Kinetic stress: sum m v' (x) v' K with v' = v - V the velocity fluctuation about the streaming
velocity V = j / rho at the field point (Goldhirsch 2010; Weinhart et al. 2012), computed as
K - j (x) j / rho from the momentum flux K = sum m v (x) v K (kinetic_stress).
"""
import numpy as np
from threadpoolctl import threadpool_limits

GAUSS_NODES = 8
# The kernel is cut at CUTOFF widths in r and in z (there it is at most e^-18 = 1.5e-8 of its peak): a point
# contributes to the nodes of a window around it only, so that the cost grows with the points, not with points
# times nodes (a Gladkyy-size snapshot has 3.5e5 contacts and 1.2e4 nodes).
CUTOFF = 6.0


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
        self.uniform = all(len(a) > 1 and np.allclose(np.diff(a), a[1] - a[0], rtol=1e-9, atol=0) for a in (self.r, self.z))

    def kernel(self, ri, zi):
        """K at every grid node for points (ri, zi) of shape (n,), 0 beyond CUTOFF w in r or in z: array (n, nr, nz) [1/m^3]."""
        w = self.w
        dr2, dz2 = (self.R[None] - ri[:, None, None]) ** 2, (self.Z[None] - zi[:, None, None]) ** 2
        cut = (dr2 <= (CUTOFF * w) ** 2) & (dz2 <= (CUTOFF * w) ** 2)
        return np.where(cut, np.exp(-(dr2 + dz2) / (2 * w * w)), 0.0) / (2 * np.pi * w * w * 2 * np.pi * self.R[None])

    def accumulate(self, ri, zi, weights):
        """sum_i weights[i, f] K(node; r_i, z_i) for every field f and node: array (nf, nr, nz).

        On a uniform grid only the window of nodes within CUTOFF w of each point (in r and in z) is
        evaluated, and the kernel's factors in r and z are combined by one matrix product per group of
        points with the same nearest node (the same numbers as with kernel(), summed in another order)."""
        ri, zi = np.asarray(ri, float), np.asarray(zi, float)
        weights = np.asarray(weights, float)
        weights = weights.reshape(len(weights), int(np.prod(weights.shape[1:]))) if weights.ndim > 1 else weights[:, None]
        nr, nz, nf = len(self.r), len(self.z), weights.shape[1]
        out = np.zeros((nf, nr, nz))
        if not self.uniform:
            for sl in _chunks(len(ri)):
                out += np.einsum("if,ijk->fjk", weights[sl], self.kernel(ri[sl], zi[sl]))
            return out
        w, dr, dz = self.w, self.r[1] - self.r[0], self.z[1] - self.z[0]
        hr, hz = int(np.ceil(CUTOFF * w / dr)), int(np.ceil(CUTOFF * w / dz))
        di, dk = np.arange(-hr, hr + 1), np.arange(-hz, hz + 1)
        i0, k0 = np.rint((ri - self.r[0]) / dr).astype(np.int64), np.rint((zi - self.z[0]) / dz).astype(np.int64)
        # Points whose window reaches the grid, grouped by their nearest node (i0, k0) (which may lie off
        # the grid, within a window of it): the nodes of a group's window are shared, so the kernel's
        # factors in r (n x window rows) and z (n x window columns) and the weights combine in one product.
        touch = np.flatnonzero((i0 >= -hr) & (i0 < nr + hr) & (k0 >= -hz) & (k0 < nz + hz))
        key = (i0[touch] + hr) * (nz + 2 * hz) + (k0[touch] + hz)
        order = np.argsort(key, kind="stable")
        touch, key = touch[order], key[order]
        starts = np.flatnonzero(np.r_[True, key[1:] != key[:-1]]) if len(key) else np.zeros(0, np.int64)
        padded = np.zeros((nr + 4 * hr, nz + 4 * hz, nf))  # node (i, k) at (i + 2 hr, k + 2 hz): every window fits
        # The products are small (window x points x window fields): BLAS threads would only wait for each
        # other; one thread also fixes the order of the sums.
        with threadpool_limits(limits=1, user_api="blas"):
            for a, b in zip(starts, np.r_[starts[1:], len(key)]):
                m = touch[a:b]
                i, k = i0[m[0]], k0[m[0]]
                ddr = self.r[0] + (i + di) * dr - ri[m, None]  # (n, window rows)
                ddz = self.z[0] + (k + dk) * dz - zi[m, None]
                gr = np.where(np.abs(ddr) <= CUTOFF * w, np.exp(-ddr * ddr / (2 * w * w)), 0.0)
                gz = np.where(np.abs(ddz) <= CUTOFF * w, np.exp(-ddz * ddz / (2 * w * w)), 0.0)
                block = gr.T @ (gz[:, :, None] * weights[m, None, :]).reshape(len(m), -1)
                padded[i + hr:i + 3 * hr + 1, k + hz:k + 3 * hz + 1] += block.reshape(2 * hr + 1, 2 * hz + 1, nf)
        inner = padded[2 * hr:2 * hr + nr, 2 * hz:2 * hz + nz] / (2 * np.pi * w * w * 2 * np.pi * self.r[:, None, None])
        return np.ascontiguousarray(inner.transpose(2, 0, 1))

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
    fields = grid.accumulate(r, z, np.column_stack([m, m[:, None] * vc]))
    return fields[0], fields[1:]


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
    Fl = np.einsum("ia,ib->iab", Fc, lc).reshape(len(F), 9)
    p = xI[None] + s[:, None, None] * l[None]  # (node, contact, 3)
    weights = wq[:, None, None] * Fl[None]
    return grid.accumulate(np.hypot(p[..., 0], p[..., 1]).ravel(), p[..., 2].ravel(), weights.reshape(-1, 9)).reshape((3, 3) + grid.R.shape)


def momentum_flux(grid, x, v, m):
    """Kinetic momentum flux density K = sum m v (x) v K(r; r_i) [Pa], cylindrical components, shape (3, 3, nr, nz)."""
    x, v, m = np.atleast_2d(x), np.atleast_2d(v), np.asarray(m, float)
    vc = to_cylindrical(v, x)
    return grid.accumulate(np.hypot(x[:, 0], x[:, 1]), x[:, 2], np.einsum("i,ia,ib->iab", m, vc, vc).reshape(len(m), 9)).reshape((3, 3) + grid.R.shape)


def kinetic_stress(rho, j, K):
    """Kinetic stress [Pa] from the density rho, momentum density j and momentum flux K of the same kernel:
    sum m v' (x) v' K(r; r_i) with v' = v_i - V(r) the fluctuation about the streaming velocity V = j / rho at
    the field point (Goldhirsch2010, Weinhart2012), which is K - j (x) j / rho; 0 where there is no mass.
    Given time-averaged rho, j and K, V is the streaming velocity of the averaged flow and the kinetic stress
    holds the temporal fluctuations about it as well, the one that closes the averaged momentum balance."""
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = np.where(rho > 0, 1.0 / np.where(rho > 0, rho, 1.0), 0.0)
    return K - np.einsum("a...,b...->ab...", j, j) * inv


def pressure_and_shear_components(sigma):
    """p = tr(sigma)/3 and the two components that carry the azimuthal shear, stacked as
    (sigma_r_theta, sigma_z_theta), of the symmetrised cylindrical stress (3, 3, ...) [Pa]."""
    s = 0.5 * (sigma + np.swapaxes(sigma, 0, 1))
    return (s[0, 0] + s[1, 1] + s[2, 2]) / 3, np.stack([s[0, 1], s[2, 1]])


def pressure_and_shear(sigma):
    """p = tr(sigma)/3 and tau = sqrt(sigma_r_theta^2 + sigma_z_theta^2) (the stresses that
    carry the azimuthal shear), from a symmetrised cylindrical stress (3, 3, ...) [Pa]."""
    p, shear = pressure_and_shear_components(sigma)
    return p, np.hypot(shear[0], shear[1])


def strain_rate(grid, omega):
    """gamma_dot = sqrt((r d omega/dr)^2 + (r d omega/dz)^2) [1/s]: twice the norm of the
    (r theta, z theta) strain-rate components of an azimuthal flow (convention written into
    every output of the shear-cell analysis)."""
    dr = np.gradient(omega, grid.r, axis=0) if len(grid.r) > 1 else 0 * omega
    dz = np.gradient(omega, grid.z, axis=1) if len(grid.z) > 1 else 0 * omega
    return np.hypot(grid.R * dr, grid.R * dz)
