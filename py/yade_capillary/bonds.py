"""Liquid shared over bonds (PendularMat.liquid = 'bonds', Richefeu et al. 2008 section 2.4), inside yade:
the liquid of a water content, its sharing, and the bond coordination number.

The engine is :yref:`PendularBonds` (after PendularCheck, e.g. ``engines(extra=[PendularBonds()])``); its
``share(added)`` shares all the liquid of the bonds-mode bodies. :func:`share_water` brings that liquid to
a water content first.
"""
import math


def _bonds_spheres():
    from yade import O
    from yade.wrapper import PendularMat, Sphere
    return [b for b in O.bodies if b and isinstance(b.material, PendularMat) and b.material.liquid == "bonds"
            and isinstance(b.shape, Sphere)]


def water_volume(w, liquid_density=1000.0):
    """Liquid volume [m^3] of the water content w [-] (liquid mass over solid mass, Richefeu 2008 section
    3.1.2) of the bonds-mode spheres of the current scene, for a liquid of density liquid_density [kg/m^3]
    (water: 1000). The solid mass is the spheres' ``state.mass``."""
    if not (isinstance(w, (int, float)) and math.isfinite(w) and w >= 0):
        raise ValueError("water_volume: w = %r is outside the allowed range [0, inf) (liquid mass over solid mass)" % (w,))
    if not (isinstance(liquid_density, (int, float)) and math.isfinite(liquid_density) and liquid_density > 0):
        raise ValueError("water_volume: liquid_density = %r kg/m^3 is outside the allowed range (0, inf)" % (liquid_density,))
    spheres = _bonds_spheres()
    if not spheres:
        raise ValueError("water_volume: the scene has no sphere of a PendularMat with liquid='bonds'")
    return w * sum(b.state.mass for b in spheres) / liquid_density


def liquid_now():
    """The liquid of the bonds-mode bodies of the current scene [m^3]: their free liquid and their bonds."""
    from yade import O
    from yade.wrapper import PendularMat
    free = sum(b.state.film for b in O.bodies
               if b and isinstance(b.material, PendularMat) and b.material.liquid == "bonds")
    held = sum(I.phys.Vb for I in O.interactions if I.isReal and getattr(I.phys, "bonds", False) and I.phys.active)
    return free + held


def engine():
    """The PendularBonds engine of the current scene (ValueError if none)."""
    from yade import O
    from yade.wrapper import PendularBonds
    found = [e for e in O.engines if isinstance(e, PendularBonds)]
    if not found:
        raise ValueError("no PendularBonds engine in O.engines (engines(extra=[PendularBonds()]) adds one after PendularCheck)")
    return found[0]


def share_water(w, liquid_density=1000.0):
    """Bring the liquid of the bonds-mode bodies to the water content w [-] and share it over the pairs within
    the debonding distance (PendularBonds.share); returns the engine (its alpha, nShared, reach). Liquid is
    only added: a w below the liquid present is refused."""
    target, present = water_volume(w, liquid_density), liquid_now()
    if target < present * (1 - 1e-12):
        raise ValueError("share_water: w = %g gives %.6g m^3 of liquid, less than the %.6g m^3 the bonds-mode bodies hold; "
                         "liquid is not removed" % (w, target, present))
    e = engine()
    e.share(max(target - present, 0.0))
    return e


def coordination():
    """Bond coordination number z [-]: twice the bonds between two bonds-mode spheres over the number of
    those spheres (Richefeu 2008 section 3.2.2)."""
    from yade import O
    spheres = {b.id for b in _bonds_spheres()}
    if not spheres:
        raise ValueError("coordination: the scene has no sphere of a PendularMat with liquid='bonds'")
    n = sum(1 for I in O.interactions if I.isReal and getattr(I.phys, "bonds", False) and I.phys.active
            and I.id1 in spheres and I.id2 in spheres)
    return 2.0 * n / len(spheres)
