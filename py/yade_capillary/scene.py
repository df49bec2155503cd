"""Engine lists and the stable time step for the yade-capillary functors (import inside yade only)."""
import os
import sys

from yade import O
from yade.wrapper import (Bo1_Facet_Aabb, Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, Ig2_Facet_Sphere_ScGeom,
                          Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom, InsertionSortCollider, InteractionLoop,
                          Ip2_PendularMat_PendularMat_PendularPhys, Law2_ScGeom_PendularPhys_Bridge, NewtonIntegrator,
                          PendularCheck, PendularForceResetter, PendularIntegrator, PendularLoop, PendularMat)

from . import patches

LOOPS = ("fused", "standard")


def interaction_loop(loop="fused", detection_factor=1.0, law_label="capillaryLaw", records=True):
    """The interaction loop with the yade-capillary functors.

    loop: "fused" (PendularLoop: sphere-sphere pairs of PendularMat bodies in one fused pass, the
    same numbers as YADE's loop) or "standard" (YADE's InteractionLoop with the same functors).
    detection_factor, law_label and records as in :func:`engines` (installs the patches as it does).
    """
    if loop not in LOOPS:
        raise ValueError("loop = %r is not one of %s (or an InteractionLoop instance)" % (loop, ", ".join(LOOPS)))
    patches.install(records)
    functors = ([Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=detection_factor), Ig2_Facet_Sphere_ScGeom(),
                 Ig2_Wall_Sphere_ScGeom()],
                [Ip2_PendularMat_PendularMat_PendularPhys(label="capillaryIp2")],
                [Law2_ScGeom_PendularPhys_Bridge(label=law_label)])
    if loop == "standard":
        return InteractionLoop(*functors, label="interactionLoop")
    return PendularLoop(*functors, label="interactionLoop", keepRecords=records)


def engines(gravity=(0, 0, 0), damping=0.0, extra=(), law_label="capillaryLaw", detection_factor=1.0, loop="fused", integrator="auto",
            records=True):
    """Return the usual engine list with the capillary law.

    gravity [m/s^2], damping: NewtonIntegrator's numerical damping [-] (0 for physical runs),
    extra: engines inserted before NewtonIntegrator, law_label: label of the Law2 functor so that
    its totals (nBridges, liquidVolume, ...) can be read as e.g. ``capillaryLaw.nBridges``.
    A bridge forms at contact, so no enlarged detection range is needed: once real, an interaction
    keeps its geometry until the law ends it at rupture. detection_factor > 1 (aabbEnlargeFactor and
    interactionDetectionFactor) creates interactions before contact, without bridges; the law
    resets them while the pair is apart, so they are removed when the spheres move away.
    loop: "fused" (default, PendularLoop), "standard" (YADE's InteractionLoop with our functors),
    or an InteractionLoop instance to use instead (e.g. YADE's built-in capillary law, for
    comparisons). With a PendularLoop the forces are reset by PendularForceResetter (a ForceResetter
    whose threads zero the bodies they handed forces over for), else by ForceResetter.
    The collider is labelled ``collider`` (yade.mpy looks it up by that label).
    integrator: "pendular": NewtonIntegrator(dead=True) holds gravity and damping and
    PendularIntegrator, after it, does its step (the same numbers, faster; NewtonIntegrator's own
    step for scenes it does not cover, see its docstring); "newton": YADE's NewtonIntegrator alone
    (needed for yade.mpy, which places its engines next to NewtonIntegrator); "auto" (default):
    "newton" under MPI (yade.mpy imported, or mpiexec with more than one process), else "pendular".
    records: True (default): PendularLoop keeps its records (PendularLoop.keepRecords, its largest speed
    gain), for which every patch of yade_capillary.patches is installed, including those that change
    how YADE's Python objects of every material behave (see docs/design.md). False: the fused loop
    (also one given as loop) keeps none, and only the patches of group ALWAYS are installed (the
    plugin's own error delivery, liquid accounting, PendularIntegrator's parameters and the release
    of a replaced scene's loop), which leave YADE's results and errors as they are; patches installed
    earlier in the process stay. The same numbers, slower (docs/user-guide.md).
    """
    if integrator not in ("auto", "pendular", "newton"):
        raise ValueError("integrator: %r is not one of 'auto', 'pendular', 'newton'" % (integrator,))
    if integrator == "auto":
        integrator = "newton" if under_mpi() else "pendular"
    patches.install(records)
    if isinstance(loop, str):
        loop = interaction_loop(loop, detection_factor, law_label, records)
    elif isinstance(loop, PendularLoop) and not records:
        loop.keepRecords = False
    newton = NewtonIntegrator(gravity=gravity, damping=damping, dead=integrator == "pendular")
    return [
        PendularForceResetter() if isinstance(loop, PendularLoop) else ForceResetter(),
        InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=detection_factor), Bo1_Facet_Aabb(), Bo1_Wall_Aabb()],
                              label="collider"),
        loop,
        PendularCheck(),
        *extra,
        newton,
    ] + ([PendularIntegrator()] if integrator == "pendular" else [])


def under_mpi():
    """True under yade.mpy (imported) or under mpiexec with more than one process (Open MPI's or a
    PMI launcher's size variable), where PendularIntegrator cannot be used."""
    if "yade.mpy" in sys.modules:
        return True
    for name in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE"):
        try:
            if int(os.environ.get(name, "1")) > 1:
                return True
        except ValueError:  # not a count: not a launcher's
            pass
    return False


def newton_only(engine_list):
    """engine_list with PendularIntegrator's step given back to its NewtonIntegrator (alive again), as
    engines(integrator="newton") makes it: for yade.mpy, which places its engines next to NewtonIntegrator."""
    out = [e for e in engine_list if not isinstance(e, PendularIntegrator)]
    for e in out:
        if isinstance(e, NewtonIntegrator):
            e.dead = False
    return out


def stable_dt(safety=0.1):
    """Stable time step [s] for the PendularMat bodies of the current scene, as YADE's PWaveTimeStep
    for its materials: safety times the smallest two-body critical time step over the pairs that
    can touch (Ip2_PendularMat_PendularMat_PendularPhys.criticalDt: stability limit of YADE's
    leapfrog for the pair's normal and tangential linear spring-dashpot, dt_c = (2/w0)(sqrt(1+z^2) - z),
    w0^2 = k/m, z = c/(2 sqrt(k m)); 2/w0 undamped). With tc, en, et, dt_c depends on tc and the
    restitution coefficients only (0.60 tc at en = et = 0.83); with kn, cn, ks, cs on the masses:
    the lightest bodies of every pair of materials are taken, a body that is not dynamic (wall,
    facet, fixed sphere) as an infinitely heavy partner.

    dt_c is necessary, not sufficient: a sphere with z contacts can oscillate up to sqrt(z) times
    faster than one pair (PendularCheck warns beyond dtSafety = 0.3 of dt_c), and a collision
    needs enough steps to give the restitution coefficient. safety = 0.1 is about tc/17 at
    en = 0.83 (our scripts use tc/20) and gives the restitution of a binary collision within
    1 % (tests/yade/test_timestep.py); at dt = tc/2 a collision at en = 0.83 gains energy (e = 1.18).
    """
    if not safety > 0:
        raise ValueError("stable_dt: safety = %r must be > 0" % safety)
    ip2 = next((f for e in O.engines if isinstance(e, InteractionLoop) for f in e.physDispatcher.functors
                if isinstance(f, Ip2_PendularMat_PendularMat_PendularPhys)), None) or Ip2_PendularMat_PendularMat_PendularPhys()
    light, heavy = {}, {}  # material id -> two lightest dynamic bodies; one body that does not move
    for b in O.bodies:
        if b is None or not isinstance(b.material, PendularMat):
            continue
        mid = b.material.id
        if b.dynamic and b.state.mass > 0:
            light[mid] = sorted(light.get(mid, []) + [(b.state.mass, b.id)])[:2]
        else:
            heavy.setdefault(mid, b.id)
    pairs = set()
    for a in light:
        if len(light[a]) == 2:
            pairs.add((light[a][0][1], light[a][1][1]))
        for b in light:
            if a < b:
                pairs.add((light[a][0][1], light[b][0][1]))
        for b in heavy:
            pairs.add((light[a][0][1], heavy[b]))
    if not pairs:
        raise ValueError("stable_dt: no two bodies with PendularMat that can touch, one of them dynamic")
    return safety * min(ip2.criticalDt(i, j) for i, j in pairs)
