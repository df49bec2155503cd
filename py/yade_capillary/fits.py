"""Fits of the shear-cell analysis, with standard errors from the covariance of least squares."""
import numpy as np
from scipy.optimize import curve_fit
from scipy.special import erf


def erf_profile(r, Rc, W):
    """omega(r)/Omega = 1/2 + 1/2 erf((r - Rc)/W) (Gladkyy 2014 eq. 13; Fenistein et al. 2004)."""
    return 0.5 + 0.5 * erf((r - Rc) / W)


def fit_band(r, omega_ratio, Rc0=None, W0=None):
    """Fit the erf profile to omega/Omega at one height; returns dict Rc_m, W_m, Rc_err_m, W_err_m."""
    r, y = np.asarray(r, float), np.asarray(omega_ratio, float)
    ok = np.isfinite(y)
    r, y = r[ok], y[ok]
    if len(r) < 4:
        raise ValueError("fit_band: %d finite points; at least 4 are needed" % len(r))
    Rc0 = r[np.argmin(np.abs(y - 0.5))] if Rc0 is None else Rc0
    W0 = 0.1 * (r.max() - r.min()) if W0 is None else W0
    p, cov = curve_fit(erf_profile, r, y, p0=[Rc0, W0])
    err = np.sqrt(np.diag(cov))
    return {"Rc_m": p[0], "W_m": abs(p[1]), "Rc_err_m": err[0], "W_err_m": err[1]}


def fit_yield(p, tau):
    """Fit tau = mu p + c (Gladkyy 2014 eq. 14) by least squares.

    Returns dict mu, mu_err, c_Pa, c_err_Pa (standard errors from the residual variance).
    """
    p, tau = np.asarray(p, float), np.asarray(tau, float)
    ok = np.isfinite(p) & np.isfinite(tau)
    p, tau = p[ok], tau[ok]
    if len(p) < 3:
        raise ValueError("fit_yield: %d finite points; at least 3 are needed" % len(p))
    A = np.stack([p, np.ones_like(p)], axis=1)
    coef, res, rank, _ = np.linalg.lstsq(A, tau, rcond=None)
    dof = len(p) - 2
    resid = tau - A @ coef
    s2 = resid @ resid / dof if dof > 0 else np.nan
    cov = s2 * np.linalg.inv(A.T @ A)
    return {"mu": coef[0], "mu_err": float(np.sqrt(cov[0, 0])), "c_Pa": coef[1], "c_err_Pa": float(np.sqrt(cov[1, 1]))}
