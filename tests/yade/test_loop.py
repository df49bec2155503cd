# PendularLoop (the fused loop) against YADE's InteractionLoop with the same functors: wet packings
# in boxes of walls and of facets, frictional and frictionless, 2000 steps each; next to the box of
# walls, a dry FrictMat packing with YADE's Cundall-Strack law, which PendularLoop leaves to the
# dispatchers. Expected values: the standard loop's own run (same scene, same time step).
# - yade -j1: the fused pass does the operations of Ig2_Sphere_Sphere_ScGeom + the law in the
#   same order and sums the forces of a body in the same order: positions, velocities, normal
#   forces and liquid totals must be bit-identical.
#   A PyRunner reads every interaction's geometry and physics every 500 steps and, once, makes one
#   bridge inactive and one sphere 30 % larger from Python: PendularLoop keeps most interactions in its own records between
#   steps, so what Python reads and writes must go through them (yade_capillary.patches); the run
#   with records must be bit-identical to the one without. With records, between the collider's runs the
#   pass visits only its list of entries (PendularLoop.skipFar), without it every entry: so the run
#   with records is also the list's test, bit-identical to the full passes of the run without.
# - yade -j2 (ctest runs this file with -j1 and with -j2), loops on one and on two threads: a
#   body's forces are summed in another order (per thread, then across threads; the collider's
#   parallel insertion can also change the order of interactions), so round-off (1e-16 relative)
#   grows over 2000 steps of collisions to at most 2.4e-12 of the scale (measured; the standard
#   loop on two threads differs from itself on one as much). Bound: 1e-9 of the scale. Bridge
#   counts must be equal and liquid volumes equal to 1e-12 relative.
# - Sorting the interaction container (PendularLoop.sortDisorder; here whenever one entry is out of
#   order, also in the runs on two threads) changes only the order of the force sums: the same bound,
#   bit-identical with and without records; after it, erasing interactions from Python (through
#   their place in the container, linIx) erases exactly those.
import math

from yade import O
from yade.utils import sphere
from yade.wrapper import FrictMat, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Law2_ScGeom_FrictPhys_CundallStrack

import stress
from testing import Checker
from yade_capillary import scene

ck = Checker("test_loop")
STEPS = 2000
BOUND = 1e-9  # of the scale (RMIN, largest speed); measured: at most 2.4e-12 after 2000 steps
RMIN = 0.5e-3


def dry_neighbours():
    """Dry FrictMat spheres beside the wet box (x < -3 RMIN, z < -9 RMIN: away from its walls, which are
    infinite planes): two layers falling on a floor of fixed spheres. PendularLoop leaves their
    interactions to YADE's dispatchers and the Cundall-Strack law."""
    mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, frictionAngle=0.4, density=2500))
    for i in range(4):
        for j in range(4):
            x, y = -9 * RMIN + 2 * RMIN * i, 2 * RMIN + 2 * RMIN * j
            O.bodies.append(sphere((x, y, -15 * RMIN), RMIN, material=mat, fixed=True))
            for k, z in enumerate((-13 * RMIN, -10.8 * RMIN)):
                O.bodies.append(sphere((x + 0.1 * RMIN * (j - 1.5), y + 0.1 * RMIN * (i - 1.5), z - 0.05 * RMIN * k), RMIN, material=mat))


SNAPSHOT_EVERY = 500  # steps; a PyRunner reads every interaction mid-run (PendularLoop's records must be written first)


def snapshot():
    """Geometry and physics of every real interaction, read from Python inside the run (PyRunner),
    and, at the second snapshot, the first real sphere-sphere interaction made inactive from Python
    (its forces must stop acting in both loops) and the last wet sphere grown by 30 %."""
    rows = {}
    for i in O.interactions:
        g, p = i.geom, i.phys
        rows[(i.id1, i.id2)] = (tuple(g.normal), g.penetrationDepth, tuple(g.contactPoint), tuple(g.shearInc), tuple(p.normalForce),
                                tuple(p.shearForce), getattr(p, "Fcap", None), getattr(p, "active", None))
    SNAPSHOTS.append((O.iter, rows))
    if len(SNAPSHOTS) == 2:
        pair = min(k for k, v in rows.items() if v[7] is not None and O.bodies[k[0]].shape.__class__.__name__ == "Sphere"
                   and O.bodies[k[1]].shape.__class__.__name__ == "Sphere")
        O.interactions[pair].isActive = False
        # A sphere grows: potential pairs that PendularLoop found apart by the bound on their gap
        # must be checked again at once (the bound holds for the radii it was computed with).
        grow = max(b.id for b in O.bodies if b.dynamic and b.material.__class__.__name__ == "PendularMat")
        O.bodies[grow].shape.radius *= 1.3


SNAPSHOTS = []


def recreate_far_pair():
    """A PyRunner's bare createInteraction (the name yade's launcher imported into __main__) on the
    potential pair of PendularMat spheres with the largest gap: YADE erases the potential interaction,
    which moves the container's last entry into its place, and appends the new one, so the container
    keeps its size while two entries change. PendularLoop's list of entries to visit (skipFar) must
    be dropped (the guard's wrapper) or the moved entry could sit in a place the list skips."""
    far = None
    for i in O.interactions.all(False):
        b1, b2 = O.bodies[i.id1], O.bodies[i.id2]
        if i.isReal or b1.shape.__class__.__name__ != "Sphere" or b2.shape.__class__.__name__ != "Sphere":
            continue
        if b1.material.__class__.__name__ != "PendularMat" or b2.material.__class__.__name__ != "PendularMat":
            continue
        gap = (b1.state.pos - b2.state.pos).norm() - b1.shape.radius - b2.shape.radius
        if far is None or gap > far[0]:
            far = (gap, i.id1, i.id2)
    if far is not None:
        createInteraction(far[1], far[2])  # noqa: F821 (yade's launcher imports it into __main__)
        RECREATED.append(far[1:])


RECREATED = []


def run(loop, box, friction, threads, snapshots=False, records=True, sort=0.0, skip_far=True, recreate=False):
    stress.box_packing(400, "willett_full", rmin=RMIN, ratio=2.0, box=box, porosity=0.7, speed=0.1, friction=friction)
    if box == "walls":
        dry_neighbours()
    functors = scene.interaction_loop(loop)
    functors.physDispatcher.functors = functors.physDispatcher.functors + [Ip2_FrictMat_FrictMat_FrictPhys()]
    functors.lawDispatcher.functors = functors.lawDispatcher.functors + [Law2_ScGeom_FrictPhys_CundallStrack()]
    O.engines = scene.engines(gravity=(0, 0, -9.81), loop=functors)
    O.dt = scene.stable_dt(0.1)
    engine = next(e for e in O.engines if isinstance(e, InteractionLoop))
    engine.ompThreads = threads
    if loop == "fused":
        engine.parallelBodies = 0 if threads > 1 else engine.parallelBodies  # the per-body phases on the threads too
        engine.keepRecords = records
        engine.sortDisorder = sort
        engine.skipFar = skip_far
    if recreate:
        from yade.wrapper import PyRunner
        del RECREATED[:]
        O.engines = O.engines + [PyRunner(command="recreate_far_pair()", iterPeriod=97)]
    if snapshots:
        from yade.wrapper import PyRunner
        del SNAPSHOTS[:]
        O.engines = O.engines + [PyRunner(command="snapshot()", iterPeriod=SNAPSHOT_EVERY)]
    O.run(STEPS, True)
    law = stress.capillary_law()
    state = [(tuple(b.state.pos), tuple(b.state.vel), tuple(b.state.angVel)) for b in O.bodies if b is not None and b.dynamic]
    if loop == "fused":
        # Read before anything below makes the recorded interactions' objects (see keepRecords).
        engine_counts.update(recorded=engine.nRecorded, with_objects=engine.nWithObjects, invariants=engine.nInvariants)
    fn = {(i.id1, i.id2): (i.isReal, i.iterMadeReal, type(i.phys).__name__, tuple(i.phys.normalForce) if i.isReal else None)
          for i in O.interactions.all(False)}
    return state, (law.nBridges, law.liquidVolume, law.liquidFormed, law.liquidReleased), fn, engine, list(SNAPSHOTS) if snapshots else None


engine_counts = {}


def every_attribute():
    """Every attribute of the ScGeom and PendularPhys of each real sphere-sphere PendularPhys interaction
    (Serializable.dict; repr, so that NaN compares), shearInc of separated pairs left out (see
    without_separated_shear_inc). With records, these objects are made from the records and their
    invariants' prototype physics (PendularLoop.keepRecords)."""
    rows = {}
    for i in O.interactions:
        if type(i.phys).__name__ != "PendularPhys" or type(i.geom).__name__ != "ScGeom":
            continue
        g = i.geom.dict()
        if g["penetrationDepth"] < 0:
            del g["shearInc"]
        rows[(i.id1, i.id2)] = repr(sorted(g.items())) + repr(sorted(i.phys.dict().items()))
    return rows


def container_consistent():
    """YADE's InteractionContainer keeps each interaction in its linear array and in both bodies' maps;
    the collider erases through the array place stored in the interaction (linIx), which a sort of
    the array must keep equal to the place: a wrong one moves or drops another interaction. True if
    the array holds each pair once and exactly the pairs of the bodies' maps."""
    listed = [(min(i.id1, i.id2), max(i.id1, i.id2)) for i in O.interactions.all(False)]
    mapped = {(min(i.id1, i.id2), max(i.id1, i.id2)) for b in O.bodies if b is not None for i in O.interactions.withBodyAll(b.id)}
    return len(listed) == len(set(listed)) and set(listed) == mapped


def without_separated_shear_inc(rows):
    return {k: v[:3] + (v[3] if v[1] >= 0 else None, ) + v[4:] for k, v in rows.items()}


def scaled_difference(a, b):
    """Largest difference of positions [in RMIN], velocities [in the largest speed of run a] and
    angular velocities [in that speed / RMIN: frictionless spheres spin only from round-off
    torques, so their own largest angular velocity is no scale]."""
    vmax = max(max(abs(x) for x in s[1]) for s in a) or 1.0
    wmax = vmax / RMIN
    worst = 0.0
    for sa, sb in zip(a, b):
        for k, scale in ((0, RMIN), (1, vmax), (2, wmax)):
            worst = max(worst, max(abs(x - y) for x, y in zip(sa[k], sb[k])) / scale)
    return worst


parallel = O.numThreads > 1
for box in ("walls", "facets"):
    for friction in (0.3, 0.0):
        tag = "%s, friction %g" % (box, friction)
        ref, ref_totals, ref_fn, _, ref_snaps = run("standard", box, friction, 1, snapshots=not parallel)
        ck.true(ref_totals[2] > ref_totals[1] > 0, "%s: bridges formed %g and broken, liquid now %g m^3" % (tag, ref_totals[2], ref_totals[1]))
        if not parallel:
            one, one_totals, one_fn, loop, snaps = run("fused", box, friction, 1, snapshots=True)
            one_attributes, one_counts = every_attribute(), dict(engine_counts)
            ck.true(loop.nFused > 0 and loop.nDispatched > 0, "%s: the fused pass (%d) and the dispatchers (%d, walls/facets) were both used"
                    % (tag, loop.nFused, loop.nDispatched))
            ck.true(loop.nRecorded > 0, "%s: %d interactions computed from PendularLoop's records in the last step" % (tag, loop.nRecorded))
            ck.true(loop.nBounded > 0, "%s: %d potential pairs found apart by the bound on their gap in the last step" % (tag, loop.nBounded))
            ck.true(loop.nFastPasses > 0, "%s: %d of %d steps visited only the list of entries (skipFar)" % (tag, loop.nFastPasses, STEPS))
            ck.true([s[0] for s in snaps] == [s[0] for s in ref_snaps] and len(snaps) >= 3,
                    "%s: %d snapshots read by a PyRunner in both loops" % (tag, len(snaps)))
            # PendularLoop updates shearInc in contact only, where the law reads it (documented).
            ck.true(all(without_separated_shear_inc(a[1]) == without_separated_shear_inc(b[1]) for a, b in zip(snaps, ref_snaps)),
                    "%s: geometry and physics read from Python inside the run (normal, penetrationDepth, contactPoint, shearInc in contact, "
                    "normalForce, shearForce, Fcap, active; %d interactions at step %d) bit-identical to InteractionLoop's"
                    % (tag, len(snaps[-1][1]), snaps[-1][0]))
            # Interactions erased and made from a PyRunner with the bare createInteraction of __main__.
            made, made_totals, _, made_loop, _ = run("fused", box, friction, 1, recreate=True)
            made_pairs = list(RECREATED)
            # Without Python holding any, no recorded interaction has objects of its own after a step; the
            # parameters of the bridges that broke are freed (a polydisperse packing: one set per pair of radii).
            ck.true(engine_counts["recorded"] > 0 and engine_counts["with_objects"] == 0 and 0 < engine_counts["invariants"] <= engine_counts["recorded"],
                    "%s: %d recorded interactions, %d of them with their own ScGeom and PendularPhys (the others hold the placeholders), "
                    "%d sets of invariants in use" % (tag, engine_counts["recorded"], engine_counts["with_objects"], engine_counts["invariants"]))
            full, full_totals, _, _, _ = run("fused", box, friction, 1, recreate=True, skip_far=False)
            ck.true(len(made_pairs) >= 10 and made_pairs == RECREATED and made_loop.nFastPasses > 0 and made == full and made_totals == full_totals,
                    "%s: %d far pairs made real from a PyRunner (createInteraction of __main__), %d steps on the list: positions, velocities "
                    "and totals bit-identical to the run without the list (skipFar=False)" % (tag, len(made_pairs), made_loop.nFastPasses))
            plain, plain_totals, _, _, plain_snaps = run("fused", box, friction, 1, snapshots=True, records=False)
            plain_attributes = every_attribute()
            ck.true(one_attributes == plain_attributes and len(one_attributes) > 0,
                    "%s: every attribute of the %d sphere-sphere ScGeom and PendularPhys after the run, made from the records, equal to "
                    "those of the run without records" % (tag, len(one_attributes)))
            ck.true(snaps == plain_snaps and one == plain and one_totals == plain_totals,
                    "%s: with and without PendularLoop's records, the snapshots read inside the run, positions, velocities and totals are "
                    "bit-identical" % tag)
            # Sorting the container (sortDisorder; here whenever an entry is out of order) changes the
            # order of the force sums only: round-off, bounded as for two threads below.
            ordered, ordered_totals, _, sorter, ordered_snaps = run("fused", box, friction, 1, snapshots=True, sort=1e-9)
            consistent = container_consistent()
            ck.true(sorter.nSorts > 10 and consistent, "%s: PendularLoop sorted the interaction container %d times; after 2000 steps of "
                    "the collider's insertions and erasures it holds each interaction once, as the bodies do" % (tag, sorter.nSorts))
            ordered_plain, ordered_plain_totals, _, _, _ = run("fused", box, friction, 1, snapshots=True, records=False, sort=1e-9)
            ck.true(ordered == ordered_plain and ordered_totals == ordered_plain_totals,
                    "%s: sorted, with and without records: positions, velocities and totals bit-identical" % tag)
            diff = scaled_difference(ref, ordered)
            ck.true(diff <= BOUND and len(ordered_snaps) == len(ref_snaps),
                    "%s: sorted container: scaled difference %.3g <= %g from InteractionLoop after %d steps" % (tag, diff, BOUND, STEPS))
            ck.true(one == ref, "%s: positions and velocities bit-identical to InteractionLoop (largest scaled difference %.3g)"
                    % (tag, scaled_difference(ref, one)))
            ck.true(one_totals == ref_totals, "%s: liquid totals identical %s vs %s" % (tag, one_totals, ref_totals))
            dry = sum(1 for v in ref_fn.values() if v[2] == "FrictPhys")
            ck.true(box != "walls" or dry > 0, "%s: %d interactions of the dry FrictMat packing (Cundall-Strack law)" % (tag, dry))
            ck.true(one_fn == ref_fn, "%s: the same real and potential interactions, made real at the same steps, with identical normal "
                    "forces (%d, %d real)" % (tag, len(ref_fn), sum(1 for v in ref_fn.values() if v[0])))
            continue
        for threads in (1, 2):
            state, totals, _, loop, _ = run("fused", box, friction, threads, sort=1e-9)
            diff = scaled_difference(ref, state)
            print("%s: fused loop on %d thread(s): scaled difference %.3g from InteractionLoop on one" % (tag, threads, diff))
            # On two threads, a step on the list of entries shares it out by parts of the bodies and hands
            # the forces over from each thread's part and borders only (PendularLoop.shareWork): covered here.
            ck.true(loop.nFastPasses > 0, "%s, %d threads: %d steps on the list of entries" % (tag, threads, loop.nFastPasses))
            # The parts follow the threads' measured paces (threadPace): none on one thread; on two, measured
            # (not the starting 1) and within the bounds [1/4, 4] that keep every part some of the work.
            pace = list(loop.threadPace)
            if threads == 1 or O.numThreads < 2:
                ck.true(pace == [], "%s, %d threads: no paces on one thread (%s)" % (tag, threads, pace))
            else:
                ck.true(len(pace) == 2 and all(0.25 <= p <= 4 for p in pace) and pace != [1.0, 1.0],
                        "%s, %d threads: paces measured, within [1/4, 4] (%s)" % (tag, threads, pace))
            # Each thread's busy time in traced passes on the list (PendularLoop.traceBusy, read by benchmark.thread_noise):
            # one positive time per thread of the pass and traced pass, nothing left unwritten (NaN).
            first, team = len(loop.busyTimes), min(threads, O.numThreads)
            loop.traceBusy = 10
            for _ in range(20):
                if loop.traceBusy > 0:
                    O.run(10, True)
            times = list(loop.busyTimes[first:])
            ck.true(loop.traceBusy == 0 and len(times) == 10 * team and all(0 < t < 1e9 for t in times),
                    "%s, %d threads: 10 traced passes, %d busy times of %d thread(s), all in (0, 1 s) (%s)" % (tag, threads, len(times), team, times[:4]))
            ck.true(diff <= BOUND, "%s, %d threads: scaled difference %.3g <= %g" % (tag, threads, diff, BOUND))
            ck.true(totals[0] == ref_totals[0], "%s, %d threads: nBridges %d == %d" % (tag, threads, totals[0], ref_totals[0]))
            for k, name in ((1, "liquidVolume"), (2, "liquidFormed"), (3, "liquidReleased")):
                ck.close(totals[k], ref_totals[k], 1e-12, "%s, %d threads: %s" % (tag, threads, name), "one-thread InteractionLoop")
ck.finish()
