"""Helpers of the in-YADE contact-law tests: a head-on binary collision, and the damping ratio of the
linear spring-dashpot for a restitution coefficient, computed here independently of the plugin."""
import math

from yade import O
from yade.utils import sphere

from yade_capillary.scene import engines


def through_contact(max_steps):
    """Steps until a contact has formed and ended (at most max_steps); returns whether one formed."""
    touched = False
    for _ in range(max_steps):
        O.step()
        touched = touched or O.interactions.countReal() > 0
        if touched and O.interactions.countReal() == 0:
            break
    return touched


def head_on(material, R, v0=0.05, fixed_partner=False, max_steps=20000):
    """Two spheres of radius R [m] and material id `material`, in the current scene (O.dt set), 1 um
    apart, meet head on at v0 [m/s] each (or the second against the first held fixed) until they part.
    Returns (touched, the relative speed after over the relative speed before)."""
    a = O.bodies.append(sphere((0, 0, 0), R, material=material, fixed=fixed_partner))
    b = O.bodies.append(sphere((2 * R + 1e-6, 0, 0), R, material=material))
    O.bodies[b].state.vel = (-v0, 0, 0)
    if not fixed_partner:
        O.bodies[a].state.vel = (v0, 0, 0)
    O.engines = engines()
    touched = through_contact(max_steps)
    before = v0 if fixed_partner else 2 * v0
    return touched, (O.bodies[b].state.vel[0] - O.bodies[a].state.vel[0]) / before


def damping_ratio(en, approach_only=False):
    """x = beta/omega (damping rate over damped frequency) for the restitution en, by bisection of
    -ln en = x (pi - 2 atan x) (Schwager & Poeschel 2007, the dashpot never attracts) or, approach_only
    (Richefeu2008 eq. 3), -ln en = x atan(1/x)."""
    def loss(x):
        return x * math.atan(1 / x) if approach_only else x * (math.pi - 2 * math.atan(x))
    lo, hi = 1e-12, 1e8
    for _ in range(300):
        x = 0.5 * (lo + hi)
        lo, hi = (x, hi) if loss(x) < -math.log(en) else (lo, x)
    return 0.5 * (lo + hi)
