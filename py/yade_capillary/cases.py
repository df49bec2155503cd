"""Case tables, kept in one place.

GLADKYY2014_TABLE1: the 13 single-bridge cases of Gladkyy & Schwarze (2014), Table 1, based on
Willett et al. (2000) and Rabinovich et al. (2005) experiments. Converted to SI: radii [m],
surface tension [N/m], contact angle [rad], bridge volume [m^3] (1 nl = 1e-12 m^3,
1e8 nm^3 = 1e-19 m^3).

ELSKAMP2018_FIG5A: the two sphere-wall configurations of Elskamp & Kruggel-Emden (2018), Fig. 5a
caption (after Rabinovich et al. 2005 experiments): conf. 1 r = 12 um, V = 7e-19 m^3, theta = 0;
conf. 2 r = 25 um, V = 170e-19 m^3, theta = 10 deg (sphere and wall); sigma = 26 mN/m in both.
A wall is a Case with R2_m = inf (the sphere is R1_m); the contact angle is the same on both.

ELSKAMP2018_FIG5B: the viscous pull-off of Elskamp & Kruggel-Emden (2018), section 3.1 and Fig. 5b
caption, after the experiments of Pitois, Moucheront & Chateau (2001) with ruby spheres: r1 = r2
= 4 mm, V = 5e-10 m^3, theta = 10 deg on both, sigma = 21 mN/m, eta = 0.1 Pa s (printed as
"0.1 kg/ms^2", a slip for kg/(m s)), one sphere fixed and the other pulled away from contact at
0.1, 1 and 10 mm/s. A ViscousCase has the fields of Case plus eta_Pa_s [Pa s] and speeds_m_s [m/s].
"""
import math
from collections import namedtuple

Case = namedtuple("Case", "code R1_m R2_m gamma_N_m theta_rad volume_m3")  # R2_m = inf: a wall (plane)
ViscousCase = namedtuple("ViscousCase", Case._fields + ("eta_Pa_s", "speeds_m_s"))  # + viscosity, pulling speeds

_NL = 1e-12
_W = [  # code, R_i [mm], R_j [mm], V [nl]; gamma = 20.6 mN/m, theta = 0
    ("W11", 2.381, 2.381, 13.6), ("W12", 2.381, 2.381, 31.3), ("W13", 2.381, 2.381, 74.2),
    ("W21", 2.381, 1.588, 9.6), ("W22", 2.381, 1.588, 13.2), ("W23", 2.381, 1.588, 24.7),
    ("W24", 2.381, 1.588, 59.3), ("W31", 2.381, 1.191, 25.3), ("W32", 2.381, 1.191, 61.8),
    ("W33", 2.381, 1.191, 127.8),
]
_R = [  # code, R_i [um], R_j [um], gamma [mN/m], V [1e8 nm^3]; theta = 10 deg
    ("R1", 19, 35, 27, 2), ("R2", 19, 32.5, 24, 12), ("R3", 19, 27.5, 28, 36),
]

GLADKYY2014_TABLE1 = (
    [Case(c, ri * 1e-3, rj * 1e-3, 20.6e-3, 0.0, v * _NL) for c, ri, rj, v in _W]
    + [Case(c, ri * 1e-6, rj * 1e-6, g * 1e-3, math.radians(10), v * 1e-19) for c, ri, rj, g, v in _R]
)

ELSKAMP2018_FIG5A = [  # Elskamp 2018 Fig. 5a caption; sigma = 26 mN/m
    Case("conf1", 12e-6, math.inf, 26e-3, 0.0, 7e-19),
    Case("conf2", 25e-6, math.inf, 26e-3, math.radians(10), 170e-19),
]

# Elskamp 2018 section 3.1 and Fig. 5b caption (Pitois et al. 2001 experiments)
ELSKAMP2018_FIG5B = ViscousCase("fig5b", 4e-3, 4e-3, 21e-3, math.radians(10), 5e-10, 0.1, (1e-4, 1e-3, 1e-2))


def case(code):
    """Return the case with the given code from any table above (e.g. 'W11', 'conf1', 'fig5b')."""
    every = GLADKYY2014_TABLE1 + ELSKAMP2018_FIG5A + [ELSKAMP2018_FIG5B]
    for c in every:
        if c.code == code:
            return c
    raise ValueError("case = %r is unknown; allowed: %s" % (code, ", ".join(c.code for c in every)))
