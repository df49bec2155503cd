"""Side-by-side speed measurements of our loop and law and YADE's built-in capillary law (inside yade; the
developer's benchmark module of bench/, imported by the bench/benchmark_*.py scripts).

packing(): n^3 spheres on a touching simple-cubic lattice with random velocities, no gravity,
every neighbour pair bridged at the first step (3 n^2 (n-1) bridges; 11 520 for n = 16). Every
variant runs the same scene with the same seed and time step in one process; the interaction-loop
time is read from YADE's engine timing and divided by the number of real interaction-steps.
shear_cell() compares the laws on the rotating shear cell (whole-run particle-steps per second),
thread_pairs() repeats one- and two-thread runs of our loop on it (the spread of the gain from the second
thread), memory() the bytes per bridge, gladkyy_probe() projects the cost of Gladkyy's full cell.
"""
import math
import os
import random
import statistics
import time

from yade import O
from yade.utils import sphere
from yade.wrapper import (Ig2_Sphere_Sphere_ScGeom, InteractionLoop, Ip2_ViscElCapMat_ViscElCapMat_ViscElCapPhys,
                          Law2_ScGeom_ViscElCapPhys_Basic, PendularMat, ViscElCapMat)

from yade_capillary import shearcell
from yade_capillary.scene import engines

# The validation cell for a short run: the speed of the shear cell at its full size (bench/benchmark_shear_cell.py).
shearcell.CONFIGS["validation_probe"] = dict(shearcell.VALIDATION, settle_s=0.2, run_s=0.2, snapshots=4, snapshot_dt_s=0.02)

# Gladkyy 2014 shear-cell particles (section 4.1) with the W11 bridge volume.
R, RHO, TC, EN, GAMMA, VB = 2.381e-3, 150.0, 5.4e-4, 0.83, 20.6e-3, 13.6e-12


# Film mode: the film that gives two equal spheres a bridge of VB (Shi & McCarthy, Elskamp 2018 eq. 8:
# each gives (1 - sqrt(0.75))/2 of its film).
FILM = VB / (1 - math.sqrt(0.75))


def build(material, n, seed, vel, film=0.0):
    """Fill O with the lattice; `material` a fresh material instance; `vel` [m/s] velocity scale;
    `film` [m^3] on every sphere (PendularMat.liquid = 'film')."""
    O.reset()
    mat = O.materials.append(material)
    rng = random.Random(seed)
    for i in range(n):
        for j in range(n):
            for k in range(n):
                b = O.bodies.append(sphere((2 * R * i, 2 * R * j, 2 * R * k), R, material=mat))
                O.bodies[b].state.vel = tuple(rng.gauss(0, vel) for _ in range(3))
                O.bodies[b].state.film = film
    O.dt = TC / 50


def measure(label, material, loop, n, steps, seed, vel, chunk=100, film=0.0, records=True, sort=True):
    """Run `steps` steps; return dict with ns per interaction-step of the interaction loop (and,
    for PendularLoop, its phases: gathering the bodies, the pass, the force hand-over).
    records: PendularLoop.keepRecords; sort: False sets PendularLoop.sortDisorder to 0."""
    build(material, n, seed, vel, film)
    O.engines = engines(loop=loop)
    end_stamp()
    if hasattr(O.engines[2], "keepRecords"):
        O.engines[2].keepRecords = records
        if not sort:
            O.engines[2].sortDisorder = 0
    O.step()  # first step: collider and interaction creation, not timed
    start_timing()
    intr_steps, wall = 0, 0.0
    done = 0
    while done < steps:
        count = O.interactions.countReal()
        wall += timed_steps(chunk)
        intr_steps += chunk * (count + O.interactions.countReal()) / 2
        done += chunk
    loop_ns = O.engines[2].execTime
    O.timingEnabled = False
    out = {"law": label, "interactions": O.interactions.countReal(), "ns_per_bridge_step": loop_ns / intr_steps,
           "particle_steps_per_s": len(O.bodies) * steps / wall, "wall_s": wall}
    phases = loop_phases(O.engines[2], intr_steps)
    if phases:
        out.update(phases)
        # What the memory of (c) is made of: recorded interactions, those of them with objects of their
        # own, and the sets of invariants (see PendularLoop.keepRecords).
        out.update(recorded=O.engines[2].nRecorded, with_objects=O.engines[2].nWithObjects, invariants=O.engines[2].nInvariants)
    return out


def builtin_run(capillar_type, n, steps, seed, vel):
    """YADE's built-in law on the benchmark scene."""
    return measure("YADE Law2_ScGeom_ViscElCapPhys_Basic (%s)" % capillar_type,
                   ViscElCapMat(tc=TC, en=EN, et=EN, density=RHO, frictionAngle=0, Capillar=True, Vb=VB, gamma=GAMMA, theta=0,
                                CapillarType=capillar_type),
                   InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_ViscElCapMat_ViscElCapMat_ViscElCapPhys()],
                                   [Law2_ScGeom_ViscElCapPhys_Basic()]), n, steps, seed, vel)


def ours_run(model, loop, friction, n, steps, seed, vel, eta=0.0, rupture="willett", liquid="fixed", records=True, sort=True):
    """Our law on the benchmark scene, in `loop` ("standard": YADE's InteractionLoop, "fused":
    PendularLoop); friction: contact friction angle [rad] (0: no tangential spring); eta: liquid
    viscosity [Pa s] (0: no viscous term); rupture: rupture rule (e.g. "willett+pitois"); liquid:
    "fixed" (Vb per bridge) or "film" (every sphere carries FILM, bridges of about Vb from the films,
    formed by PendularCheck at the end of the step, returned to the films at rupture); records:
    PendularLoop.keepRecords (False: the loop reads and writes YADE's objects at every step); sort:
    PendularLoop sorts the interaction container (False: sortDisorder = 0)."""
    label = "yade-capillary %s, %s, friction %g" % (model, "PendularLoop" if loop == "fused" else "Law2 in InteractionLoop", friction)
    if loop == "fused" and not records:
        label += ", without records"
    if loop == "fused" and not sort:
        label += ", without sorting"
    if eta > 0:
        label += ", eta %g Pa s%s" % (eta, ", rupture %s" % rupture if rupture != "willett" else "")
    if liquid == "film":
        label += ", liquid on the particles (film)"
    return measure(label, PendularMat(tc=TC, en=EN, et=EN, density=RHO, frictionAngle=friction, wet=True, Vb=VB if liquid == "fixed" else 1e-6,
                                      gamma=GAMMA, theta=0, model=model, eta=eta, rupture=rupture, liquid=liquid),
                   loop, n, steps, seed, vel, film=FILM if liquid == "film" else 0.0, records=records, sort=sort)


def packing(n=16, steps=1000, seed=1, vel=0.005, model="willett_full", builtin_model="Willett_numeric", repeats=3):
    """Measure, on identical scenes: YADE's built-in law (the baseline), its zero-force variant, our
    Law2 in YADE's InteractionLoop, PendularLoop frictionless and with friction 0.5 rad, and
    PendularLoop frictionless with a viscous liquid (water, eta = 1 mPa s; Elskamp 2018 eq. 26, 28, 29),
    with and without Pitois' dynamic rupture distance (eq. 33): the cost of the viscous terms against
    the same scene with eta = 0, which evaluates none of them; PendularLoop frictionless with the
    liquid on the particles (liquid='film'): the cost of the film bookkeeping against fixed volumes;
    and PendularLoop frictionless without its records (keepRecords=False: the Interaction, ScGeom and
    PendularPhys objects read and written at every step).

    The zero-force variant (CapillarType "None": the built-in law with the same bookkeeping and a
    capillary force of 0) is the floor of YADE's interaction loop, geometry and dispatch, which no
    Law2 functor in that loop can go below. Each is measured `repeats` times, interleaved, and the
    fastest repetition is kept (noise on a shared machine only ever adds time). Returns the list
    of result dicts, baseline first.
    """
    variants = [lambda: builtin_run(builtin_model, n, steps, seed, vel), lambda: builtin_run("None", n, steps, seed, vel),
                lambda: ours_run(model, "standard", 0.0, n, steps, seed, vel), lambda: ours_run(model, "fused", 0.0, n, steps, seed, vel),
                lambda: ours_run(model, "fused", 0.5, n, steps, seed, vel),
                lambda: ours_run(model, "fused", 0.0, n, steps, seed, vel, eta=1e-3),
                lambda: ours_run(model, "fused", 0.0, n, steps, seed, vel, eta=1e-3, rupture="willett+pitois"),
                lambda: ours_run(model, "fused", 0.0, n, steps, seed, vel, liquid="film"),
                lambda: ours_run(model, "fused", 0.0, n, steps, seed, vel, records=False)]
    runs = [[] for _ in variants]
    for _ in range(repeats):
        for r, v in zip(runs, variants):
            r.append(v())
    return [min(r, key=lambda x: x["ns_per_bridge_step"]) for r in runs]


def records_effect(n=40, steps=200, seed=1, vel=0.005, model="willett_full", repeats=2):
    """PendularLoop frictionless with records and sorting (the defaults), without sorting, and without
    either, on a packing too large for the caches (n = 40: 64 000 spheres, about 169 000 bridges),
    interleaved `repeats` times; returns the fastest of each, in that order."""
    variants = ((True, True), (True, False), (False, False))
    runs = [[] for _ in variants]
    for _ in range(repeats):
        for r, (records, sort) in zip(runs, variants):
            r.append(ours_run(model, "fused", 0.0, n, steps, seed, vel, records=records, sort=sort))
    return [min(r, key=lambda x: x["ns_per_bridge_step"]) for r in runs]


def memory():
    """Bytes per bridge of our law and of YADE's built-in one (sizeof; each of Interaction, geometry
    and physics is one heap object held by a shared_ptr, identical for both laws except the physics)
    and the per-body arrays of PendularLoop."""
    from yade.wrapper import PendularLoop

    return dict(PendularLoop().memory())


# The label of the PyRunner that stamps the end of a timed run (see timed_steps).
END_STAMP = "benchmarkEndStamp"
_end = {"t": None}


def _stamp_end():
    """The wall time at the end of the last step of a timed run; called by the END_STAMP PyRunner, in YADE's
    simulation thread."""
    _end["t"] = time.perf_counter()


def end_stamp():
    """Append the END_STAMP PyRunner to O.engines (last) unless it is there; returns it. For timed_steps: the
    benchmarks call it right after they set O.engines, before their untimed steps, since assigning O.engines
    makes PendularLoop drop its records, which the next step rebuilds. It stays alive between timed runs
    (assigning Engine.dead would drop the records too); between them it runs no command (firstIterRun is past,
    no period) and costs a clock read per step. Its command binds no name in __main__, where PyRunner runs it."""
    from yade.wrapper import PyRunner

    for e in O.engines:
        if e.label == END_STAMP:
            return e
    stamp = PyRunner(command="__import__('%s', fromlist=['_stamp_end'])._stamp_end()" % __name__, initRun=False, label=END_STAMP)
    O.engines = O.engines + [stamp]
    return stamp


def timed_steps(n):
    """Run n steps of O (O.run, in YADE's simulation thread, then O.wait as O.run(n, True) does); returns the
    wall time [s] from O.run to the end of the n-th step, stamped by the END_STAMP PyRunner in that step
    (firstIterRun), which must be the last engine (end_stamp). Not the time at which the wait returns: O.wait
    polls every 40 ms, which would add 0-40 ms at random to every timed run. Not a poll of O.running every
    millisecond either: on two cores its 1000 wake-ups per second share them with the two threads of a
    two-thread run and slow it down (docs/performance.md). O.run, not O.step() in a loop: the steps run in
    YADE's simulation thread, as in the runs of users' scripts."""
    if n < 1 or O.iter + n - 1 < 1:
        raise ValueError("timed_steps: n = %d from iteration %d; needs n >= 1 and a last step after iteration 0 (PyRunner.firstIterRun > 0)"
                         % (n, O.iter))
    # Not appended here: that would drop PendularLoop's records inside the timed steps.
    engines_now = O.engines
    if not engines_now or engines_now[-1].label != END_STAMP or engines_now[-1].dead:
        raise RuntimeError("timed_steps: the last engine of O.engines must be the live %s PyRunner; call benchmark.end_stamp() right after "
                           "assigning O.engines" % END_STAMP)
    stamp = engines_now[-1]
    stamp.nDone, stamp.firstIterRun = 0, O.iter + n - 1
    _end["t"] = None
    t0 = time.perf_counter()
    try:
        O.run(n)
        O.wait()
    finally:
        stamp.nDone = 1  # disarmed, also after a run that stopped early: it never takes the GIL in a later step
    if _end["t"] is None:
        raise RuntimeError("timed_steps: the %s PyRunner did not run in the last of the %d steps" % (END_STAMP, n))
    return _end["t"] - t0


class _Cell:
    """The prepared shear cell of `config` (made in `cache`, a file, if missing; a temporary file if None) with
    the liquid of `case`, as the benchmarks rebuild it for each law: the spheres, the time step and the
    materials of YADE's built-in law (Willett_numeric) and of ours (willett_full)."""

    def __init__(self, config, case, cache):
        import json
        import tempfile

        path = cache or os.path.join(tempfile.mkdtemp(), "cell.yade.gz")
        if not os.path.exists(path):
            shearcell.prepare(config, case, path, log=lambda *a: None)
        O.load(path)
        self.info = json.loads(O.tags["shearcell"])
        self.cfg, self.liquid = self.info["cfg"], shearcell.CASES[case]
        flowing = set(self.info["flowing"])
        self.bodies = [(b.state.pos, b.shape.radius, b.id in flowing) for b in O.bodies]
        self.dt = O.dt

    def builtin_material(self):
        cfg, liquid = self.cfg, self.liquid
        return ViscElCapMat(tc=cfg["tc"], en=cfg["en"], et=cfg["et"], density=cfg["rho"], frictionAngle=0, Capillar=True, Vb=liquid["Vb"],
                            gamma=liquid["gamma"], theta=math.degrees(liquid["theta"]), CapillarType="Willett_numeric")

    def our_material(self):
        cfg, liquid = self.cfg, self.liquid
        return PendularMat(tc=cfg["tc"], en=cfg["en"], et=cfg["et"], density=cfg["rho"], frictionAngle=0, wet=True, Vb=liquid["Vb"],
                           gamma=liquid["gamma"], theta=liquid["theta"], model=liquid["model"])

    def build(self, material, loop, nthreads, parallel_bodies=None, integrator=None):
        """A new scene of the cell with `material`, `loop` (as shearcell.run_engines takes it) and every engine
        on `nthreads` threads, run 100 steps (interactions and bridges in place before timing). YADE's own setup
        (NewtonIntegrator) for the built-in law and our Law2 in InteractionLoop; PendularLoop with
        PendularIntegrator, as scene.engines gives them by default."""
        O.reset()
        O.dt = self.dt
        mat = O.materials.append(material)
        for pos, radius, free in self.bodies:
            O.bodies.append(sphere(pos, radius, material=mat, fixed=not free))
        O.engines = shearcell.run_engines(self.info, loop, integrator=integrator or ("pendular" if loop == "fused" else "newton"))
        end_stamp()
        set_threads(nthreads, parallel_bodies)
        O.run(100, True)


def set_threads(nthreads, parallel_bodies=None):
    """Every engine of O.engines on `nthreads` OpenMP threads (ompThreads; yade must be started with -j at least
    that many), and parallelBodies, where an engine has it, set to `parallel_bodies` unless None."""
    for e in O.engines:
        e.ompThreads = nthreads
        if parallel_bodies is not None and hasattr(e, "parallelBodies"):
            e.parallelBodies = parallel_bodies


def shear_cell(steps=2000, config="ci", case="wet13.6nl", repeats=2, cache=None, threads=(1,)):
    """The prepared shear cell rotating, with YADE's built-in law (Willett_numeric) and with ours
    (willett_full) in YADE's InteractionLoop and in PendularLoop, same positions, same time step,
    in one run: particle-steps per second of each (fastest of `repeats` interleaved runs; threads
    threads: the numbers of OpenMP threads to measure, interleaved in the same process (every engine's
    ompThreads; yade must be started with -j at least the largest): a shared machine's speed drifts within
    minutes, so thread counts are compared within one run. cache: file of the
    prepared cell, prepared there if missing. Returns {threads: (builtin, ours standard, ours
    fused, ours fused with parallelBodies = 20000 in PendularLoop and PendularIntegrator, ours fused
    with YADE's NewtonIntegrator instead of PendularIntegrator)} of dicts: the fourth tells what the
    per-body phases gain from threads at the ci cell's 2 200 bodies (the default, 1000, against 20000), the fifth what
    PendularIntegrator gains. Each dict also has "phases": ns per step of each engine and of PendularLoop's
    gathering, pass and force hand-over (O.timingEnabled), the per-phase timings of the run, and
    "round_trip_ns": core_round_trip() just before the run (the machine's mode), and "parallel":
    parallel_speed() just before it (whether the machine gave two cores' worth then)."""
    cell = _Cell(config, case, cache)
    flowing = len(cell.info["flowing"])

    def timed(material, loop, nthreads, parallel_bodies=None, integrator=None):
        cell.build(material, loop, nthreads, parallel_bodies, integrator)
        round_trip = core_round_trip()  # the machine's mode, just before the timed steps
        parallel = parallel_speed()
        start_timing()  # where the time goes (a clock read per engine and step, the same for every variant)
        out = {"particle_steps_per_s": flowing * steps / timed_steps(steps), "phases": engine_times(steps),
               "round_trip_ns": round_trip, "parallel": parallel}
        loop_engine = next(e for e in O.engines if isinstance(e, InteractionLoop))
        out["phases"].update({"  " + k: v for k, v in loop_phases(loop_engine, steps).items()})
        O.timingEnabled = False
        return out

    builtin_mat, ours_mat = cell.builtin_material, cell.our_material
    loop = lambda: InteractionLoop([Ig2_Sphere_Sphere_ScGeom()], [Ip2_ViscElCapMat_ViscElCapMat_ViscElCapPhys()],
                                   [Law2_ScGeom_ViscElCapPhys_Basic()])
    runs = {t: [[], [], [], [], []] for t in threads}
    for _ in range(repeats):
        for t in threads:
            runs[t][0].append(timed(builtin_mat(), loop(), t))
            runs[t][1].append(timed(ours_mat(), "standard", t))
            runs[t][2].append(timed(ours_mat(), "fused", t))
            runs[t][3].append(timed(ours_mat(), "fused", t, parallel_bodies=20000))
            runs[t][4].append(timed(ours_mat(), "fused", t, integrator="newton"))
    return {t: [max(r, key=lambda x: x["particle_steps_per_s"]) for r in runs[t]] for t in threads}


def thread_pairs(pairs=10, steps=1000, config="ci", case="wet13.6nl", cache=None, warmup=100):
    """Our law in PendularLoop on the prepared shear cell (as in shear_cell), `pairs` pairs of runs of `steps`
    steps, one thread then two, in turn on one scene going on (yade must be started with -j2 at least), each
    after `warmup` untimed steps on its thread count (the loop shares its work out again for it). One pair is
    as noisy as the machine (its two modes, see core_round_trip, and its stretches of half speed, see
    parallel_speed): the pairs give the spread of the gain from the second thread and its median. Returns a list
    of {threads: {"particle_steps_per_s", "round_trip_ns", "parallel"}} (the round trip and parallel speed
    measured just before that run)."""
    cell = _Cell(config, case, cache)
    flowing = len(cell.info["flowing"])
    cell.build(cell.our_material(), "fused", 1)
    out = []
    for _ in range(pairs):
        pair = {}
        for nthreads in (1, 2):
            set_threads(nthreads)
            O.run(warmup, True)
            round_trip, parallel = core_round_trip(), parallel_speed()
            pair[nthreads] = {"particle_steps_per_s": flowing * steps / timed_steps(steps), "round_trip_ns": round_trip, "parallel": parallel}
        out.append(pair)
    return out


def thread_noise(passes=1000, config="ci", case="wet13.6nl", cache=None, warmup=200):
    """How each thread's time in PendularLoop's pass varies from step to step, on the prepared shear cell (as in
    thread_pairs): `passes` passes on the list (see PendularLoop.skipFar) traced with PendularLoop.traceBusy after
    `warmup` steps, on two threads, then on one. A static share of the work (fixed between two full passes) waits
    at each step's join for the slower thread: this is what that costs on the machine. Returns {threads: dict}
    with, per thread of the pass, "percentiles" (10th, 50th, 90th, 99th of its busy time [us]) and "lag1" (the
    correlation of its busy time with that of the step before: 1 for a slow drift, which the measured paces
    follow, 0 for noise from step to step), and on two threads "between" (the correlation of the two threads'
    times in a step) and "join_us" (the mean of the slower thread's time less the mean of the two [us]: what
    each step of the pass loses to the spread, with every step's share equal on average)."""
    cell = _Cell(config, case, cache)
    cell.build(cell.our_material(), "fused", 1)
    loop = next(e for e in O.engines if isinstance(e, InteractionLoop))
    out = {}
    for nthreads in (2, 1):
        set_threads(nthreads)
        O.run(warmup, True)
        first = len(loop.busyTimes)
        loop.traceBusy = passes
        while loop.traceBusy > 0:  # passes on the list are most steps (the full ones come at the collider's runs)
            left = loop.traceBusy
            O.run(passes, True)
            if loop.traceBusy == left:  # none in as many steps: the loop keeps no list (see PendularLoop.skipFar)
                break
        loop.traceBusy = 0
        flat = [t / 1e3 for t in loop.busyTimes[first:]]
        if len(flat) < 2 * nthreads:
            raise RuntimeError("thread_noise: %d passes on the list in the traced steps of the %s cell on %d thread(s); PendularLoop keeps a list only "
                               "with keepRecords and skipFar" % (len(flat) // nthreads, config, nthreads))
        series = [flat[k::nthreads] for k in range(nthreads)]
        stats = {"passes": len(series[0]), "percentiles": [], "lag1": []}
        for x in series:
            ordered = sorted(x)
            stats["percentiles"].append([ordered[min(len(x) - 1, int(q * len(x)))] for q in (0.1, 0.5, 0.9, 0.99)])
            stats["lag1"].append(_correlation(x[:-1], x[1:]))
        if nthreads == 2:
            stats["between"] = _correlation(series[0], series[1])
            stats["join_us"] = sum(max(a, b) - (a + b) / 2 for a, b in zip(*series)) / len(series[0])
        out[nthreads] = stats
    return out


def _correlation(x, y):
    """Pearson's correlation of two equally long sequences (statistics.correlation; nan if one is constant)."""
    try:
        return statistics.correlation(x, y)
    except statistics.StatisticsError:
        return float("nan")


def _core_latency(*args):
    """What build/core_latency prints with `args`, as a float; None if it is not built."""
    import subprocess

    build = os.environ.get("BUILD_DIR") or os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "build")
    exe = os.path.join(build, "core_latency")
    if not os.path.exists(exe):
        return None
    return float(subprocess.run([exe, *args], capture_output=True, text=True, check=True).stdout)


def core_round_trip():
    """The round trip of a cache line between two threads [ns] (build/core_latency, median of 7 batches),
    None if it is not built. A virtual machine's vCPUs may share a cache or not, and switch between the two
    (docs/performance.md): two threads gain much less in the slow mode, so a ratio of thread counts means
    something only with the round trips of its runs."""
    return _core_latency()


def parallel_speed():
    """The machine's parallel speed just now [-] (build/core_latency --parallel, about 20 ms): the time per
    record of one thread updating its own records alone over that of each of two threads doing as much at
    once; 1 when two cores' worth is there, 0.5 when each thread runs at half speed (a virtual machine does
    at times, at any round trip). None if it is not built."""
    return _core_latency("--parallel")


# PendularLoop's phases: gathering the bodies, the pass over the interactions, the force hand-over.
LOOP_PHASES = ("gather", "pass", "flush")


def start_timing():
    """Turn YADE's engine timing on (O.timingEnabled) and zero every engine's execTime and PendularLoop's
    phase times, before a timed run (read with engine_times and loop_phases)."""
    O.timingEnabled = True
    for e in O.engines:
        e.execTime = 0
        if hasattr(e, "passTime"):
            for k in LOOP_PHASES:
                setattr(e, k + "Time", 0)


def loop_phases(loop, per):
    """PendularLoop's phase times [ns] since start_timing, divided by `per` (steps or interaction-steps);
    {} for another interaction loop."""
    return {k: getattr(loop, k + "Time") / per for k in LOOP_PHASES} if hasattr(loop, "passTime") else {}


def engine_times(steps):
    """ns per step of each engine of O.engines over the last `steps` steps (O.timingEnabled must have
    been on, with execTime reset before them)."""
    return {"%s%s" % (e.__class__.__name__, "(%s)" % e.label if e.label else ""): e.execTime / steps for e in O.engines if e.label != END_STAMP}


def gladkyy_probe(steps=1000, case="wet13.6nl", loop="fused", run_s=5.0, chunk=100, state=None):
    """Speed probe of a Gladkyy-size cell (shearcell.GLADKYY_SIZE: about 170 000 flowing spheres plus
    the rough walls), rotating. The flowing spheres are built touching (ring lattice of 2 R, filled
    to 1.2 H: about 166 000 flowing spheres), so that contacts and bridges exist from the first steps, as in a settled cell; 100 steps
    untimed, then `steps` timed, in chunks of `chunk` steps in turn with PendularLoop's defaults, without
    its list of entries to visit (skipFar) and without its records (keepRecords, and so without the
    list), so that all three are measured on the same cell at the same time.
    Returns a dict: numbers of spheres and interactions, wall time per step in each mode, the projected wall time [h] of `run_s` seconds of rotation at the configuration's time
    step with records, ns per step of each engine (where the time goes; both modes) and the
    PendularLoop counts of the last step (real, recorded, apart, apart by the gap bound, out of order,
    sorts so far) and the time spent sorting the interaction container per step.
    state: a state saved by shearcell.save_state (a Gladkyy-size run under way: the sheared packing with
    its bridges, `case` ignored) to probe instead of the lattice. A lattice built touching is still
    collapsing in the timed steps: its spheres move faster than in a settled, sheared cell, so the collider
    runs more often (collider_runs_per_step tells)."""
    if state is None:
        cfg = shearcell.GLADKYY_SIZE
        ids = shearcell.build(cfg, case, spacing=2.0, fill=1.2)
        O.engines = shearcell.run_engines({"rotating": ids["rotating"], "cfg": cfg}, loop)
        O.dt = cfg["dt_over_tc"] * cfg["tc"]
    else:
        ids = shearcell.load_state(state, loop=loop)
    end_stamp()
    O.run(100, True)
    collider = next(e for e in O.engines if e.label == "collider")
    runs0 = collider.numAction
    start_timing()
    fused = next((e for e in O.engines if hasattr(e, "keepRecords")), None)
    # (keepRecords, skipFar) in turn, chunk by chunk: the default first.
    modes = [(True, True), (True, False), (False, False)] if fused is not None else [(True, True)]
    wall = dict.fromkeys(modes, 0.0)
    done = dict.fromkeys(modes, 0)
    k = 0
    while sum(done.values()) < steps:
        n = min(chunk, steps - sum(done.values()))
        mode = modes[k % len(modes)]
        if fused is not None:
            fused.keepRecords, fused.skipFar = mode
        wall[mode] += timed_steps(n)
        done[mode] += n
        k += 1
    O.timingEnabled = False
    per_step = wall[(True, True)] / done[(True, True)]
    out = {"spheres": len(O.bodies), "flowing": len(ids["flowing"]), "real_interactions": O.interactions.countReal(),
           "interactions": len(O.interactions), "s_per_step": per_step, "particle_steps_per_s": len(ids["flowing"]) / per_step,
           "projected_h": per_step * run_s / O.dt / 3600, "run_s": run_s, "dt": O.dt, "threads": O.numThreads,
           "engines_ns_per_step": engine_times(steps), "collider_runs_per_step": (collider.numAction - runs0) / steps,
           "start": "state %s (t = %.3f s)" % (state, ids["t_offset_s"]) if state else "lattice built touching"}
    if fused is not None and done[(False, False)] and done[(True, False)]:
        out["s_per_step_without_records"] = wall[(False, False)] / done[(False, False)]
        out["s_per_step_without_skip"] = wall[(True, False)] / done[(True, False)]
        out["counts"] = {k: getattr(fused, k) for k in ("nFused", "nRecorded", "nWithObjects", "nInvariants", "nApart", "nBounded", "nSkipped", "nDispatched", "nDisorder", "nSorts")}
        out["sort_ms_per_step"] = fused.sortTime / 1e6 / (steps + 100)
    return out
