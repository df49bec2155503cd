"""Case tables, kept in one place.

GLADKYY2014_TABLE1: the 13 single-bridge cases of Gladkyy & Schwarze (2014), Table 1, based on
Willett et al. (2000) and Rabinovich et al. (2005) experiments. Converted to SI: radii [m],
surface tension [N/m], contact angle [rad], bridge volume [m^3] (1 nl = 1e-12 m^3,
1e8 nm^3 = 1e-19 m^3).
"""
import math
from collections import namedtuple

Case = namedtuple("Case", "code R1_m R2_m gamma_N_m theta_rad volume_m3")

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


def case(code):
    """Return the Table 1 case with the given code (e.g. 'W11')."""
    for c in GLADKYY2014_TABLE1:
        if c.code == code:
            return c
    raise ValueError("case = %r is unknown; allowed: %s" % (code, ", ".join(c.code for c in GLADKYY2014_TABLE1)))
