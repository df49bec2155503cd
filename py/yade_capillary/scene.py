"""Engine lists for the yade-capillary functors (import inside yade only)."""
from yade.wrapper import (Bo1_Facet_Aabb, Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, Ig2_Facet_Sphere_ScGeom,
                          Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                          Ip2_PendularMat_PendularMat_PendularPhys, Law2_ScGeom_PendularPhys_Bridge, NewtonIntegrator,
                          PendularCheck)


def engines(gravity=(0, 0, 0), damping=0.0, extra=(), law_label="capillaryLaw", detection_factor=1.0, loop=None):
    """Return the usual engine list with the capillary law.

    gravity [m/s^2], damping: NewtonIntegrator's numerical damping [-] (0 for physical runs),
    extra: engines inserted before NewtonIntegrator, law_label: label of the Law2 functor so that
    its totals (nBridges, liquidVolume, ...) can be read as e.g. ``capillaryLaw.nBridges``.
    A bridge forms at contact, so no enlarged detection range is needed: once real, an interaction
    keeps its geometry until the law ends it at rupture. detection_factor > 1 (aabbEnlargeFactor and
    interactionDetectionFactor) creates interactions before contact, without bridges; the law
    resets them while the pair is apart, so they are removed when the spheres move away. loop: an
    InteractionLoop to use instead of ours (e.g. YADE's built-in capillary law, for comparisons).
    """
    return [
        ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=detection_factor), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()]),
        loop if loop is not None else InteractionLoop(
            [Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=detection_factor), Ig2_Facet_Sphere_ScGeom(),
             Ig2_Wall_Sphere_ScGeom()],
            [Ip2_PendularMat_PendularMat_PendularPhys()],
            [Law2_ScGeom_PendularPhys_Bridge(label=law_label)],
        ),
        PendularCheck(),
        *extra,
        NewtonIntegrator(gravity=gravity, damping=damping),
    ]
