# yade_capillary.patches, the patches of YADE's Python objects, and records=False of scene.engines():
# - importing the package (yade_capillary, scene, patches, objects) replaces no attribute of YADE's classes
#   and modules;
# - before patches.install(records=True), a PendularLoop keeps no records (PendularLoop.readersGuarded),
#   whatever its keepRecords;
# - engines(records=False) replaces exactly the attributes that the patches of group ALWAYS list (none of
#   group RECORDS), its PendularLoop keeps no records, and the ALWAYS patches work (erasing a wet body
#   breaks its bridges in the law's totals);
# - engines(records=True) then replaces exactly those of every patch, and its loop keeps records;
# - the same wet packing run with records=False and records=True: positions, velocities and forces after
#   300 steps bit for bit equal (on one thread the loop is bit-identical with and without records,
#   test_loop; this file runs with -j1).
# "Replaces" is judged by identity: every attribute of every class of yade.wrapper, of yade._utils and
# yade.utils, and the names of yade._utils' functions in __main__, before and after.
import random
import sys

import yade._utils
import yade.utils
import yade.wrapper
from yade import O


def snapshot():
    """(owner, attribute name) -> the attribute's object, for every attribute the patches could replace."""
    out = {}
    for cls in vars(yade.wrapper).values():
        if isinstance(cls, type):
            out.update(((cls, k), v) for k, v in vars(cls).items())
    for module in (yade._utils, yade.utils):
        out.update(((module, k), v) for k, v in vars(module).items())
    main = sys.modules["__main__"]
    out.update(((main, k), vars(main)[k]) for k in vars(yade._utils) if k in vars(main))
    return out


def replaced(before, after):
    missing = object()
    return {k for k in set(before) | set(after) if before.get(k, missing) is not after.get(k, missing)}


def named(pairs):
    return sorted("%s.%s" % (getattr(owner, "__name__", owner), name) for owner, name in pairs)


original = snapshot()

from yade.wrapper import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom, InsertionSortCollider,  # noqa: E402
                          Ip2_PendularMat_PendularMat_PendularPhys, Law2_ScGeom_PendularPhys_Bridge, NewtonIntegrator, PendularForceResetter,
                          PendularLoop, PendularMat)

import yade_capillary  # noqa: E402, F401
from yade_capillary import patches, scene  # noqa: E402, F401
from testing import Checker  # noqa: E402

ck = Checker("test_patches")
always, every = set(patches.targets(patches.ALWAYS)), set(patches.targets())  # named while all are YADE's
ck.true(not replaced(original, snapshot()) and patches.installed() == [],
        "importing yade_capillary, its scene and patches replaces none of YADE's attributes (%s)" % named(replaced(original, snapshot())))
# What records=False leaves patched, as docs/design.md and the user guide list it.
ALWAYS = ["BodyContainer.clear", "BodyContainer.erase", "InteractionContainer.clear", "InteractionContainer.erase", "NewtonIntegrator.damping",
          "NewtonIntegrator.dampGravity", "NewtonIntegrator.exactAsphericalRot", "NewtonIntegrator.gravity", "NewtonIntegrator.mask", "Omega.load",
          "Omega.loadTmp", "Omega.reset", "Omega.run", "Omega.wait"]
ck.true(named(always) == sorted(ALWAYS) and len(every) > 100 and always < every,
        "the patches list %d attributes, those of group ALWAYS %s" % (len(every), named(always)))

R, STEPS = 1e-3, 300


def packing():
    """64 wet spheres (radii 0.99-1 R) on a jittered 4x4x4 lattice of spacing 1.98 R in a closed box of walls,
    with velocities of 0.1 m/s in random directions: bridges form at the contacts and some break."""
    O.reset()
    rng = random.Random(5)
    mat = O.materials.append(PendularMat(tc=1e-4, en=0.5, et=0.5, density=2500, frictionAngle=0.3, Vb=0.02 * R ** 3, gamma=0.0206,
                                         model="willett_full", wet=True))
    a, n = 1.98 * R, 4
    for i in range(n):
        for j in range(n):
            for k in range(n):
                c = tuple((m + 0.5) * a + 0.01 * R * rng.uniform(-1, 1) for m in (i, j, k))
                b = O.bodies.append(yade.utils.sphere(c, R * rng.uniform(0.99, 1.0), material=mat))
                d = [rng.gauss(0, 1) for _ in range(3)]
                s = sum(v * v for v in d) ** 0.5
                O.bodies[b].state.vel = tuple(0.1 * v / s for v in d)
    for axis in range(3):
        for pos, sense in ((0, 1), (n * a, -1)):
            O.bodies.append(yade.utils.wall(pos, axis=axis, sense=sense, material=mat))


def loop_of():
    return next(e for e in O.engines if isinstance(e, PendularLoop))


def law_of():
    return loop_of().lawDispatcher.functors[0]


def state():
    return [tuple(b.state.pos) + tuple(b.state.vel) + tuple(O.forces.f(b.id)) + tuple(O.forces.t(b.id)) for b in O.bodies]


def erase_wet_body():
    """Erase the sphere with the most bridges; returns (its bridges, the law's nBridges before, after)."""
    law = law_of()
    counts = {}
    for i in O.interactions:
        if i.isReal and getattr(i.phys, "active", False):
            for id_ in (i.id1, i.id2):
                counts[id_] = counts.get(id_, 0) + 1
    body = max((k for k in counts if isinstance(O.bodies[k].shape, yade.wrapper.Sphere)), key=lambda k: counts[k])
    before = law.nBridges
    O.bodies.erase(body)
    return counts[body], before, law.nBridges


# 1. A PendularLoop built by hand, before any install: no records.
packing()
O.engines = [PendularForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
             PendularLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [Ip2_PendularMat_PendularMat_PendularPhys()],
                          [Law2_ScGeom_PendularPhys_Bridge()]),
             NewtonIntegrator()]
O.dt = scene.stable_dt(0.1)
O.run(100, True)
loop = loop_of()
ck.true(loop.keepRecords and loop.nFused > 50 and loop.nRecorded == 0 and not replaced(original, snapshot()),
        "a PendularLoop (keepRecords %s) before patches.install: %d fused interactions, %d recorded; no attribute replaced"
        % (loop.keepRecords, loop.nFused, loop.nRecorded))

# 2. records=False: the ALWAYS group only; no records.
results = {}
for records in (False, True):
    packing()
    O.engines = scene.engines(records=records)
    O.dt = scene.stable_dt(0.1)
    O.run(STEPS, True)
    loop = loop_of()
    results[records] = (state(), law_of().nBridges, loop.nFused, loop.nRecorded, loop.keepRecords)
    changed = replaced(original, snapshot())
    if not records:
        ck.true(changed == always and patches.installed() == [patches.ALWAYS],
                "engines(records=False) replaces the %d attributes of group ALWAYS and no other: %s; not replaced: %s"
                % (len(always), named(changed - always), named(always - changed)))
        ck.true(not loop.keepRecords and loop.nFused > 50 and loop.nRecorded == 0,
                "engines(records=False): keepRecords %s, %d fused interactions, %d recorded" % (loop.keepRecords, loop.nFused, loop.nRecorded))
    else:
        ck.true(changed == every and patches.installed() == [patches.ALWAYS, patches.RECORDS],
                "engines(records=True) then replaces the %d attributes of every patch and no other: %s; not replaced: %s"
                % (len(every), named(changed - every), named(every - changed)))
        ck.true(loop.keepRecords and loop.nRecorded > 50, "engines(records=True): %d of %d fused interactions recorded" % (loop.nRecorded, loop.nFused))
    bridges, before, after = erase_wet_body()
    ck.true(bridges > 0 and after == before - bridges,
            "records=%s: O.bodies.erase of a sphere with %d bridges lowers the law's nBridges from %d to %d (the ALWAYS patch)"
            % (records, bridges, before, after))

ck.true(results[False][1] > 20, "records=False: %d bridges after %d steps" % (results[False][1], STEPS))
ck.true(results[False][:3] == results[True][:3],
        "records=False and records=True: positions, velocities, forces and torques of the %d bodies, the bridge count (%d, %d) and "
        "the fused interactions after %d steps bit for bit equal" % (len(results[True][0]), results[False][1], results[True][1], STEPS))
ck.finish()
