"""Split-bottom ring shear cell (inside yade): configurations, preparation, run, snapshots.

The cell: spheres between an inner cylinder (radius Ri) and an outer one (Ro) on a bottom split at
Rs. The outer cylinder and the bottom ring beyond Rs rotate about z with the set period; the inner
cylinder and the inner bottom stay. All walls are rough: a layer of fixed spheres of the flowing
radius (with particle friction 0, smooth walls would drag nothing). The full 360 degrees are
simulated (YADE has no angular periodicity).

Every parameter lives in CONFIGS and CASES; scripts only choose names (or add configurations to CONFIGS).
"""
import json
import math
import os
import random

import numpy as np

# Gladkyy 2014 materials (section 4.1) in the Luding/Roy cell (Roy et al.: Ro = 110, Ri = 14.7,
# Rs = 85, H = 40 mm); period 100 s.
VALIDATION = dict(R=2.381e-3, rho=150.0, tc=5.4e-4, en=0.83, et=0.83, friction=0.0, Ro=0.110, Ri=0.0147, Rs=0.085, H=0.040,
                  period=100.0, dt_over_tc=0.05, settle_s=0.5, run_s=5.0, snapshots=15, snapshot_dt_s=0.25, seed=1)
# Same physics scaled for CI (one core, minutes): the cell shrunk to 0.45 of its size (about 1/11
# of the particles), the same particles, liquid volumes (V/R^3) and hence capillary force to
# weight; rotation 10x faster and a short run, so the inertial number is about 10x larger than in
# the validation configuration. A regression check, not a physical prediction.
CI = dict(VALIDATION, Ro=0.0495, Ri=0.0066, Rs=0.0383, H=0.018, period=10.0, settle_s=0.25, run_s=0.6, snapshots=20,
          snapshot_dt_s=0.015)
# Gladkyy's cell size: "nearly 200 000" spheres of R = 2.381 mm, about 168 000 flowing, i.e. the
# validation cell (about 15 000 flowing) enlarged 2.2 times linearly.
# Filled to 1.62 H instead of 1.4 H (see build): about 168 000 flowing spheres, which settle to about H;
# with 1.4 H, 145 000 would settle to about 0.86 H (the validation cell settles to 37 of its 40 mm).
GLADKYY_SIZE = dict(VALIDATION, Ro=2.2 * VALIDATION["Ro"], Ri=2.2 * VALIDATION["Ri"], Rs=2.2 * VALIDATION["Rs"], H=2.2 * VALIDATION["H"],
                    fill=1.62)
# Gravity of every cell [m/s^2] unless its configuration sets g.
GRAVITY = 9.81
# The configurations by name, as prepare() and run() take them. Add your own under a new name (a dict
# like VALIDATION with some values changed, e.g. CONFIGS["mine"] = dict(VALIDATION, run_s=2.0)): one that
# differs from a prepared cell's configuration in RUN_KEYS only runs from that cell (run(..., config=)).
CONFIGS = {"ci": CI, "validation": VALIDATION, "gladkyy_size": GLADKYY_SIZE}
# Keys that only control the run; all others describe the cell, its materials and its preparation.
RUN_KEYS = ("run_s", "snapshots", "snapshot_dt_s")


def preparation_of(config):
    """The configuration whose prepared cell `config` runs from: `validation` when they differ in
    RUN_KEYS only (one packing for all the validation runs), else `config` itself."""
    if config not in CONFIGS:
        raise ValueError("config: %r is not one of %s" % (config, ", ".join(CONFIGS)))
    cell = lambda c: {k: v for k, v in CONFIGS[c].items() if k not in RUN_KEYS}
    return "validation" if cell(config) == cell("validation") else config

# Liquid cases: Gladkyy's volumes (W11 and W13 of Table 1), gamma of that table.
CASES = {
    "dry": dict(wet=False),
    "wet13.6nl": dict(wet=True, Vb=13.6e-12, gamma=20.6e-3, theta=0.0, model="willett_full"),
    "wet74.2nl": dict(wet=True, Vb=74.2e-12, gamma=20.6e-3, theta=0.0, model="willett_full"),
}
# Gladkyy's test of model independence (section 4.2, Fig. 6-8: his four models give the same mu, c,
# shear band and torque): his other three models at 13.6 nl. Not part of the CI regression.
MODEL_CASES = {"wet13.6nl_" + m: dict(CASES["wet13.6nl"], model=m) for m in ("weigert", "willett_reduced", "rabinovich_lambert")}
ALL_CASES = dict(CASES, **MODEL_CASES)


def _liquid(case):
    """PendularMat attributes of a liquid case, `wet` last (a wet material must already have Vb, gamma)."""
    attrs = {k: v for k, v in ALL_CASES[case].items() if k != "wet"}
    return dict(attrs, **({"wet": True} if ALL_CASES[case]["wet"] else {}))


def _material(cfg, case):
    from yade.wrapper import PendularMat

    return PendularMat(tc=cfg["tc"], en=cfg["en"], et=cfg["et"], density=cfg["rho"], frictionAngle=math.atan(cfg["friction"]),
                       **_liquid(case))


def _ring(radius, z, spacing):
    n = max(3, int(round(2 * math.pi * radius / spacing)))
    return [(radius * math.cos(2 * math.pi * k / n), radius * math.sin(2 * math.pi * k / n), z) for k in range(n)]


def wall_positions(cfg):
    """Centres of the wall spheres: {'static': [...], 'rotating': [...]} (rotating: r > Rs bottom and outer cylinder)."""
    R, d = cfg["R"], 2 * cfg["R"]
    static, rotating = [], []
    nz = int(math.ceil(1.3 * cfg["H"] / d)) + 1
    for k in range(nz):  # cylinders, surfaces at Ri and Ro
        z = R + k * d
        static += _ring(cfg["Ri"] - R, z, d)
        rotating += _ring(cfg["Ro"] + R, z, d)
    r = cfg["Ri"] - R
    while r < cfg["Ro"] + R:  # bottom, centres at z = -R (surface at z = 0)
        (rotating if r > cfg["Rs"] else static).extend(_ring(r, -R, d))
        r += d * math.sqrt(3) / 2
    return {"static": static, "rotating": rotating}


def build(cfg, case, spacing=2.2, fill=None):
    """O.reset(), then the cell of configuration dict `cfg` with the liquid of `case`: wall spheres and
    flowing spheres on a ring lattice of `spacing` radii (slightly jittered) filling the annulus to
    fill H (default: the configuration's fill, else 1.4). Returns {'flowing', 'static', 'rotating'} lists of ids."""
    if fill is None:
        fill = cfg.get("fill", 1.4)
    from yade import O
    from yade.utils import sphere

    O.reset()
    mat = O.materials.append(_material(cfg, case))
    walls = wall_positions(cfg)
    ids = {}
    for kind, pts in walls.items():
        ids[kind] = [O.bodies.append(sphere(p, cfg["R"], material=mat, fixed=True)) for p in pts]
    rng = random.Random(cfg["seed"])
    R, d = cfg["R"], spacing * cfg["R"]
    flowing = []
    z = 1.5 * R
    while z < fill * cfg["H"]:
        r = cfg["Ri"] + 1.2 * R
        while r < cfg["Ro"] - 1.2 * R:
            for p in _ring(r, z, d):
                q = (p[0] + rng.uniform(-0.05, 0.05) * R, p[1] + rng.uniform(-0.05, 0.05) * R, p[2])
                flowing.append(O.bodies.append(sphere(q, R, material=mat)))
            r += d
        z += d
    ids["flowing"] = flowing
    return ids


def prepare(config, case, path, seed=None, log=print, checkpoint=None, save_every_s=1200.0):
    """Build the cell, fill it to about H, settle under gravity, O.save to path (None: no O.save);
    returns info dict.

    seed: overrides the configuration's seed of the random filling (for seed-to-seed scatter).
    checkpoint: a save_state file written every `save_every_s` of wall time while the cell settles; if it
    exists, settling continues from it (for cells whose settling takes longer than one sitting)."""
    import time

    from yade import O

    from .scene import engines

    cfg = dict(CONFIGS[config], **({} if seed is None else {"seed": seed}))
    settling = engines(gravity=(0, 0, -cfg.get("g", GRAVITY)), damping=0.3)
    dt = cfg["dt_over_tc"] * cfg["tc"]
    steps = int(cfg["settle_s"] / dt)
    if checkpoint is not None and os.path.exists(checkpoint):
        info = load_state(checkpoint)
        if (info["config"], info["case"], info["cfg"]) != (config, case, cfg):
            raise ValueError("checkpoint: %s holds %s/%s, not the asked %s/%s" % (checkpoint, info["config"], info["case"], config, case))
        O.engines = settling
        log("prepare %s/%s: continuing %s at step %d of %d" % (config, case, checkpoint, info["settled_steps"], steps))
    else:
        # Flowing spheres on a loose lattice filling the annulus to 1.4 H (settles to ~H; see build).
        ids = build(cfg, case)
        O.engines = settling
        O.dt = dt
        info = {"config": config, "case": case, "flowing": ids["flowing"], "static": ids["static"], "rotating": ids["rotating"], "cfg": cfg,
                "settled_steps": 0}
        log("prepare %s/%s: %d flowing + %d wall spheres, settling %d steps" % (config, case, len(ids["flowing"]), len(ids["static"]) + len(ids["rotating"]), steps))
    last, chunk = time.time(), 500
    while info["settled_steps"] < steps:
        n = min(chunk, steps - info["settled_steps"])
        O.run(n, True)
        info["settled_steps"] += n
        if checkpoint is not None and time.time() - last > save_every_s and info["settled_steps"] < steps:
            save_state(checkpoint, info)
            last = time.time()
            log("  saved %s at step %d of %d" % (checkpoint, info["settled_steps"], steps))
    info.pop("settled_steps")
    if path is not None:
        O.tags["shearcell"] = json.dumps({k: v for k, v in info.items() if k in ("config", "case", "flowing", "static", "rotating", "cfg")})
        O.save(path)
    return info


def run_engines(info, loop="fused", integrator="pendular"):
    """Engines of the running cell: gravity, no numerical damping, the rotating walls turned about z
    with the configured period; `loop` and `integrator` as in scene.engines (loop: "fused", "standard" or an
    InteractionLoop, e.g. another law; integrator: "pendular" or "newton", the latter for yade.mpy)."""
    from yade.wrapper import PendularRotationEngine, RotationEngine

    from .scene import engines

    # With our loop and integrator, PendularRotationEngine (RotationEngine's velocities, bit for bit, with one
    # rotation per step); else YADE's own engines, as its users set them up.
    ours = loop == "fused" and (integrator or "pendular") == "pendular"
    rotation = (PendularRotationEngine if ours else RotationEngine)(ids=info["rotating"], rotationAxis=(0, 0, 1),
                                                                    angularVelocity=2 * math.pi / info["cfg"]["period"],
                                                                    rotateAroundZero=True, zeroPoint=(0, 0, 0))
    return engines(gravity=(0, 0, -info["cfg"].get("g", GRAVITY)), damping=0.0, loop=loop, extra=[rotation], integrator=integrator)


def _set_config(info, config):
    """Take the run parameters (RUN_KEYS) of `config` for a cell prepared with another configuration;
    ValueError naming the parameters if the cell or its preparation differ."""
    if config not in CONFIGS:
        raise ValueError("config: %r is not one of %s" % (config, ", ".join(CONFIGS)))
    want = dict(CONFIGS[config], seed=info["cfg"]["seed"])
    differ = sorted(k for k in set(want) | set(info["cfg"]) if k not in RUN_KEYS and want.get(k) != info["cfg"].get(k))
    if differ:
        raise ValueError("config: %r differs from the prepared cell's %r in %s" % (config, info["config"], ", ".join(differ)))
    info["config"], info["cfg"] = config, want


def _set_case(info, case):
    """Give the loaded cell the liquid of `case`: the material changes in place and all interactions
    are dropped, so the next step re-detects every contact of the settled packing with the new
    material (each one gets a bridge when wet)."""
    from yade import O

    if case not in ALL_CASES:
        raise ValueError("case: %r is not one of %s" % (case, ", ".join(ALL_CASES)))
    if info["case"] == case:
        return
    if ALL_CASES[info["case"]]["wet"]:
        raise ValueError("case: only a dry prepared cell can be given a liquid (prepared: %r, asked: %r)" % (info["case"], case))
    for key, value in _liquid(case).items():
        setattr(O.materials[0], key, value)
    O.interactions.clear()
    info["case"] = case


def run(path_in, outdir, config=None, case=None, log=print):
    """Load a prepared cell, rotate the outer parts, record torques and snapshots in outdir; save the
    final state to outdir/final.yade.gz.

    config: take the run parameters (RUN_KEYS) from this configuration instead of the one the cell
    was prepared with; every other parameter must be equal (ValueError otherwise).
    case: run a dry prepared cell with the liquid of this case (all cases then start from the same
    packing; the bridges form at the contacts of the first step).
    Returns a dict with particle-steps per second and the mean torques [N m] of the second half.
    """
    from yade import O

    O.load(path_in)
    info = json.loads(O.tags["shearcell"])
    if config is not None:
        _set_config(info, config)
    if case is not None:
        _set_case(info, case)
    O.tags["shearcell"] = json.dumps(info)
    cfg = info["cfg"]
    eng = run_engines(info)
    os.makedirs(outdir, exist_ok=True)
    steps = int(cfg["run_s"] / O.dt)
    info["done_steps"] = info["next_snapshot"] = 0  # a run of its own, also when it continues another one's final state
    rec = _Recorder(info, outdir, steps, log)
    eng.append(rec.engine())
    O.engines = eng
    O.run(steps + 1, True)
    T = np.array(rec.torques)
    out = _finish(info, outdir, T, steps, rec.wall())
    np.savetxt(os.path.join(outdir, "torque.csv"), T, delimiter=",", header=TORQUE_HEADER, comments="")
    O.save(os.path.join(outdir, "final.yade.gz"))
    return out


TORQUE_HEADER = "time_s,torque_rotating_Nm,torque_static_Nm"


class _Recorder:
    """What a run records (run, run_segment): the torques on the rotating and static walls 20 times per
    snapshot interval, the snapshots of the last `snapshots` intervals of a run of `steps` steps, and
    the progress. info["done_steps"] and info["next_snapshot"] carry a run over segments."""

    def __init__(self, info, outdir, steps, log, reduce_dir=None, reduce_more=None):
        import time

        from yade import O

        self.info, self.outdir, self.steps, self.log, self.reduce_dir, self.reduce_more = info, outdir, steps, log, reduce_dir, reduce_more
        cfg = info["cfg"]
        self.every = max(1, int(cfg["snapshot_dt_s"] / O.dt))
        self.snap_iters = snapshot_steps(cfg, O.dt)
        self.done0 = info.setdefault("done_steps", 0)
        info.setdefault("next_snapshot", 0)
        self.progress = [steps * k // 10 for k in range(1, 10) if steps * k // 10 > self.done0]
        self.torques = []
        self.start, self.t0 = O.iter, time.time()

    def done(self):
        """Steps of the run done so far."""
        from yade import O

        return self.done0 + O.iter - self.start

    def wall(self):
        import time

        return time.time() - self.t0

    def engine(self, first=False):
        """The PyRunner that calls this recorder (PyRunner executes a string in yade's global namespace:
        the recorder is published there); first: also at the first step (segments, which follow each
        other without a gap in the records)."""
        import builtins

        from yade.wrapper import PyRunner

        builtins.shearcellRecord = self
        return PyRunner(command="shearcellRecord()", iterPeriod=max(1, self.every // 20), initRun=first)

    def __call__(self):
        from yade import O

        info, done = self.info, self.done()
        rot = sum(_torque_z(b) for b in info["rotating"])
        sta = sum(_torque_z(b) for b in info["static"])
        self.torques.append((_now(info), rot, sta))
        if self.progress and done >= self.progress[0]:
            self.progress.pop(0)
            self.log("  %d %% at t = %.3f s, %.3g particle-steps/s, torque rotating %.3e N m" % (
                100 * done // self.steps, _now(info), len(info["flowing"]) * (O.iter - self.start) / self.wall(), rot))
        k = info["next_snapshot"]
        if k < len(self.snap_iters) and done >= self.snap_iters[k]:
            info["next_snapshot"] = k + 1
            path = os.path.join(self.outdir, "snap_%03d.npz" % (k + 1))
            snapshot(path, info)
            if self.reduce_dir is not None:  # its CG fields, kept where the next segment finds them
                from . import cellanalysis

                cellanalysis.reduce_snapshot(path, info["cfg"], os.path.join(self.reduce_dir, "cg_%03d.npz" % (k + 1)), more=self.reduce_more)
            self.log("  t = %.3f s, snapshot %d, torque rotating %.3e N m, static %.3e N m" % (_now(info), k + 1, rot, sta))


def snapshot_steps(cfg, dt):
    """Steps of a run (from its start) at which its snapshots are taken: over the last `snapshots`
    intervals of `snapshot_dt_s`."""
    steps, every = int(cfg["run_s"] / dt), max(1, int(cfg["snapshot_dt_s"] / dt))
    return [steps - every * k for k in range(cfg["snapshots"], 0, -1)]


def _finish(info, outdir, T, steps, wall):
    """run.json of a finished run (T: its torque records); returns its dict."""
    cfg = info["cfg"]
    late = slice(len(T) // 2, None)  # the second half of the run
    out = {"particle_steps_per_s": len(info["flowing"]) * steps / wall, "wall_s": wall, "steps": steps,
           "torque_rotating_Nm": float(np.mean(T[late, 1])), "torque_static_Nm": float(np.mean(T[late, 2])),
           "Omega_rad_s": 2 * math.pi / cfg["period"]}
    with open(os.path.join(outdir, "run.json"), "w") as f:
        json.dump(dict(out, config=info["config"], case=info["case"], cfg=cfg), f, indent=1)
    return out


def run_segment(state_in, outdir, case=None, budget_s=None, save_every_s=1200.0, until_step=None, keep=None, log=print, reduce_more=None):
    """A run that may take several sittings (Gladkyy's cell), one segment per call: continue keep/state.npz
    if it exists, else start from the cell saved by save_state in `state_in` (a dry cell given the liquid
    of `case`, as run(..., case=...)); run until the configuration's run_s is done, or until `budget_s` of
    wall time has passed (None: no limit), or until step `until_step` of the run is reached, saving
    keep/state.npz every `save_every_s` of wall time and at the end. Torques are appended to
    keep/torque.csv; snapshots go to outdir as in run(), each one also reduced to its CG fields in
    keep/cg_NNN.npz (cellanalysis.reduce_snapshot, with `reduce_more` as its `more`;
    cellanalysis.analyse_reduced(keep) then fits the run when its snapshots were taken in several
    segments); when the run is complete, outdir and keep get run.json and outdir a copy of torque.csv.
    keep: the directory of what the next segment continues from (default outdir).
    Returns {"complete": bool, "done_steps", "steps", "t_s", "particle_steps_per_s"} of this segment."""
    import time

    from yade import O

    keep = outdir if keep is None else keep
    state = os.path.join(keep, "state.npz")
    for d in (outdir, keep):
        os.makedirs(d, exist_ok=True)
    continued = os.path.exists(state)
    info = load_state(state if continued else state_in, case=None if continued else case)
    steps = int(info["cfg"]["run_s"] / O.dt)
    rec = _Recorder(info, outdir, steps, log, reduce_dir=keep, reduce_more=reduce_more)
    O.engines = O.engines + [rec.engine(first=True)]
    torque_csv = os.path.join(keep, "torque.csv")
    if not continued and os.path.exists(torque_csv):
        os.remove(torque_csv)

    def save():
        info["done_steps"] = rec.done()
        info["wall_s"] = info.get("wall_s", 0.0) + rec.wall() - save.wall
        save.wall = rec.wall()
        save_state(state, info)
        with open(torque_csv, "a") as f:
            np.savetxt(f, np.array(rec.torques).reshape(-1, 3), delimiter=",", header=TORQUE_HEADER if os.path.getsize(torque_csv) == 0 else "",
                       comments="")
        rec.torques.clear()
        log("  saved %s at t = %.3f s (%d of %d steps)" % (state, _now(info), info["done_steps"], steps))

    save.wall = 0.0
    open(torque_csv, "a").close()
    chunk = max(1, rec.every // 20)
    last = time.time()
    iter0 = O.iter
    end = steps + 1 if until_step is None else min(steps + 1, until_step)
    while rec.done() < end:  # at least one chunk of steps per segment
        O.run(min(chunk * 2, end - rec.done()), True)
        if budget_s is not None and rec.wall() >= budget_s:
            break
        if time.time() - last > save_every_s:
            save()
            last = time.time()
    save()
    out = {"complete": rec.done() >= steps + 1, "done_steps": rec.done(), "steps": steps, "t_s": _now(info),
           "particle_steps_per_s": len(info["flowing"]) * (O.iter - iter0) / max(rec.wall(), 1e-9)}
    if out["complete"]:
        T = np.loadtxt(torque_csv, delimiter=",", skiprows=1, ndmin=2)
        _finish(info, outdir, T, steps, info["wall_s"])
        if keep != outdir:
            _finish(info, keep, T, steps, info["wall_s"])
            np.savetxt(os.path.join(outdir, "torque.csv"), T, delimiter=",", header=TORQUE_HEADER, comments="")
    return out


def _law():
    """The Law2_ScGeom_PendularPhys_Bridge of the current engines (its bridge totals)."""
    from yade import O

    for e in O.engines:
        for f in getattr(getattr(e, "lawDispatcher", None), "functors", []):
            if type(f).__name__ == "Law2_ScGeom_PendularPhys_Bridge":
                return f
    raise ValueError("engines: no Law2_ScGeom_PendularPhys_Bridge in O.engines")


def save_state(path, info):
    """Save the running cell compactly to `path` (npz, written to path + '.tmp' and renamed): every
    body's position, velocity, angular velocity and orientation (axis and angle; float64), the real interactions with
    their bridges (and tangential forces when the particles have friction), the bridge totals, O.time,
    O.dt and `info` (JSON). About 110 B per body and 9 B per real interaction, so that a
    Gladkyy-size state (2e5 bodies) can be committed and continued on another machine or with a later
    version of the plugin, which O.save's archives do not allow (their layout follows the classes).
    What is not kept: the potential interactions (the collider finds them again) and the loop's
    caches; a continued run differs from an uninterrupted one by round-off (the forces on a body are
    summed in another order)."""
    from yade import O

    if ALL_CASES[info["case"]].get("liquid", "fixed") != "fixed":
        raise ValueError("save_state: liquid=%r: only fixed-volume bridges are saved" % ALL_CASES[info["case"]]["liquid"])
    bodies = list(O.bodies)
    arrays = {k: np.array([getattr(b.state, k) for b in bodies]) for k in ("pos", "vel", "angVel")}
    arrays["ori"] = np.array([tuple(a) + (angle,) for a, angle in (b.state.ori.toAxisAngle() for b in bodies)])  # axis, angle [rad]
    arrays["radius"] = np.array([b.shape.radius for b in bodies])
    arrays["fixed"] = np.array([not b.dynamic for b in bodies])
    pairs, active, shear = [], [], []
    for I in O.interactions:
        if I.isReal:
            pairs.append((I.id1, I.id2))
            active.append(I.phys.active)
            if info["cfg"]["friction"] > 0:
                shear.append(tuple(I.phys.shearForce))
    law = _law()
    totals = {k: float(getattr(law, k)) for k in ("nBridges", "liquidVolume", "liquidFormed", "liquidReleased")}
    meta = dict(info, time_s=_now(info), dt_s=O.dt, totals=totals)
    for k in ("flowing", "static", "rotating"):
        arrays["ids_" + k] = np.array(meta.pop(k), dtype=np.int32)
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        np.savez_compressed(f, pairs=np.array(pairs, dtype=np.int32).reshape(-1, 2), active=np.array(active, dtype=bool),
                            shear=np.array(shear).reshape(-1, 3), meta=json.dumps(meta), **arrays)
    os.replace(tmp, path)


def load_state(path, case=None, loop="fused"):
    """Rebuild a cell saved by save_state in a new scene (O.reset()) with the running engines and
    return its info dict. Bodies keep their ids; the real interactions are made again
    (utils.createInteraction) and their bridges formed (Law2_ScGeom_PendularPhys_Bridge.formBridge),
    so nBridges and liquidVolume continue; liquidFormed and liquidReleased count from here, their
    values at the save are in info["totals"]. case: give a dry saved cell this liquid instead (every
    contact forms a bridge at the first step, as with run(..., case=...))."""
    from yade import O
    from yade.minieigenHP import Quaternion
    from yade.utils import createInteraction, sphere

    d = np.load(path)
    info = json.loads(str(d["meta"]))
    for k in ("flowing", "static", "rotating"):
        info[k] = d["ids_" + k].tolist()
    if case is not None and case != info["case"]:
        if case not in ALL_CASES:
            raise ValueError("case: %r is not one of %s" % (case, ", ".join(ALL_CASES)))
        if ALL_CASES[info["case"]]["wet"]:
            raise ValueError("case: only a dry saved cell can be given a liquid (saved: %r, asked: %r)" % (info["case"], case))
        info["case"] = case
    cfg = info["cfg"]
    O.reset()
    mat = O.materials.append(_material(cfg, info["case"]))
    ids = O.bodies.append([sphere(tuple(p), r, material=mat, fixed=bool(f)) for p, r, f in zip(d["pos"], d["radius"], d["fixed"])])
    if ids != list(range(len(ids))):
        raise ValueError("load_state: the bodies did not get the saved ids 0..%d" % (len(ids) - 1))
    for b, v, w, q in zip(O.bodies, d["vel"], d["angVel"], d["ori"]):
        b.state.vel, b.state.angVel = tuple(v), tuple(w)
        b.state.ori = Quaternion(tuple(q[:3]), q[3])
    O.dt = info.pop("dt_s")
    O.engines = run_engines(info, loop=loop)
    info["t_offset_s"] = info.pop("time_s")
    law = _law()
    frictional = cfg["friction"] > 0
    # Each d[...] of an NpzFile decompresses its whole array: read every array once, not once per pair.
    pairs, active, shear, vel = d["pairs"], d["active"], d["shear"], d["vel"]
    # A save follows Newton's half of a step, so a bridge may have been stretched past its rupture distance
    # by that step (the law breaks it at the next one, as in the uninterrupted run): by at most the
    # relative displacement of the step, |v2 - v1| dt of the saved velocities.
    stretch = np.linalg.norm(vel[pairs[:, 1]] - vel[pairs[:, 0]], axis=1) * O.dt  # pairs: (n, 2), also for n = 0
    for k, (a, b) in enumerate(pairs.tolist()):
        I = createInteraction(a, b)
        if active[k]:
            try:
                law.formBridge(a, b, pastRupture=float(stretch[k]))
            except ValueError as e:
                raise ValueError("load_state: %s: bridge %d-%d: %s" % (path, a, b, e)) from None
        if frictional:
            I.phys.shearForce = tuple(shear[k])
    return info


def _now(info):
    """Time of the cell since its preparation [s] (a cell rebuilt by load_state starts at O.time = 0)."""
    from yade import O

    return O.time + info.get("t_offset_s", 0.0)


def _torque_z(bid):
    from yade import O

    x = O.bodies[bid].state.pos
    F, T = O.forces.f(bid), O.forces.t(bid)
    return x[0] * F[1] - x[1] * F[0] + T[2]


def snapshot(path, info):
    """Positions, velocities, masses of the flowing spheres, every contact as (xP, xI or the
    contact point for wall contacts, force on P) -- what the coarse-graining needs -- and, for the
    torque balance, the centre (r, z) [m] and the torque about the axis [N m] of every static and
    rotating wall sphere (static_rz, static_Tz, rotating_rz, rotating_Tz)."""
    from yade import O

    walls = {}
    for kind in ("static", "rotating"):
        pos = np.array([O.bodies[i].state.pos for i in info[kind]])
        walls[kind + "_rz"] = np.stack([np.hypot(pos[:, 0], pos[:, 1]), pos[:, 2]], axis=1)
        walls[kind + "_Tz"] = np.array([_torque_z(i) for i in info[kind]])

    flowing = set(info["flowing"])
    ids = info["flowing"]
    x = np.array([O.bodies[i].state.pos for i in ids])
    v = np.array([O.bodies[i].state.vel for i in ids])
    m = np.array([O.bodies[i].state.mass for i in ids])
    xP, xI, F, gap = [], [], [], []
    for I in O.interactions:
        if not I.isReal:
            continue
        # force on body 2 (YADE convention): capillary and normal viscous force are in normalForce, the
        # tangential viscous force (eta > 0) is not in shearForce, the spring
        f2 = I.phys.normalForce + I.phys.shearForce + I.phys.viscousShear
        a, b = I.id1, I.id2
        if a not in flowing and b not in flowing:
            continue
        if b in flowing:
            P, other, f = b, a, f2
        else:
            P, other, f = a, b, -f2
        xP.append(O.bodies[P].state.pos)
        xI.append(O.bodies[other].state.pos if other in flowing else I.geom.contactPoint)
        F.append(f)
        gap.append(-I.geom.penetrationDepth)
    np.savez_compressed(path, x=x, v=v, m=m, xP=np.array(xP), xI=np.array(xI), F=np.array(F), gap=np.array(gap), t=_now(info), **walls)


def summary(fit):
    """The regression quantities of a fits.json: mu, c [Pa], Rc [m] (mean over the fitted heights) and
    the magnitude of the torque on the rotating walls [N m] (mean of the second half of the run)."""
    rc = [r for r in fit["Rc_m"] if r is not None]
    return {"mu": fit["mu"], "c_Pa": fit["c_Pa"], "Rc_m": float(np.mean(rc)) if rc else None, "torque_Nm": abs(fit["torque_Nm"])}
