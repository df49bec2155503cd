# YADE's own materials and engines behave as in plain YADE once yade_capillary's patches are installed
# (yade_capillary.patches, as yade_capillary.scene.engines() installs them). Expected values: the same
# scenes run by Debian's /usr/bin/yade in a process that never imports yade_capillary (nothing of the
# build on its paths), twice, to show that the reference is deterministic.
#
# This file runs under yade (-x) and starts three subprocesses, each running this same file with
# `--worker MODE OUT`: "plain" twice (/usr/bin/yade) and "patched" once (build/yade-capillary, which
# imports yade_capillary and first runs a wet chain of 8 spheres with scene.engines(), which installs
# every patch, its PendularLoop keeping records of the 7 bridges). Each then runs two scenes of 36
# spheres in a closed box of walls, one of ViscElMat (Law2_ScGeom_ViscElPhys_Basic, no damping) and one
# of dry FrictMat (Law2_ScGeom_FrictPhys_CundallStrack, damping 0.2), compressed, with gravity and random
# initial velocities: 300 steps, with positions, orientations, velocities, angular velocities, forces
# and torques every 25 steps; then dict() of every body, material, interaction and engine, pickling,
# YADE's C++ utils functions, the XML that O.save writes and O.sceneToString's archive (the scene's
# speed, measured in wall-clock time, left out), the round trip through O.load (the loaded scene's
# dict() and the XML that O.save writes of it) and 100 more steps from the loaded scene. Everything
# must be equal bit for bit (floats compared by their bits); the runs are on one thread, where YADE is
# deterministic.
import os
import pickle
import random
import re
import struct
import subprocess
import sys
import tempfile

from yade import O, utils
from yade.wrapper import (Bo1_Sphere_Aabb, Bo1_Wall_Aabb, ForceResetter, FrictMat, Ig2_Sphere_Sphere_ScGeom, Ig2_Wall_Sphere_ScGeom,
                          InsertionSortCollider, InteractionLoop, Ip2_FrictMat_FrictMat_FrictPhys, Ip2_ViscElMat_ViscElMat_ViscElPhys,
                          Law2_ScGeom_FrictPhys_CundallStrack, Law2_ScGeom_ViscElPhys_Basic, NewtonIntegrator, ViscElMat)

STEPS, EVERY, AFTER_LOAD = 300, 25, 100
R, TC = 1e-3, 1e-4  # sphere radius [m]; ViscElMat's contact time [s]
GREY = (0.5, 0.5, 0.5)  # utils.sphere's default colour is random
WALL_CLOCK = b"wall-clock"  # in place of the scene's speed in what O.save and O.sceneToString write


def build(kind):
    """36 spheres (radii 0.99-1 R) on a jittered 3x3x4 lattice of spacing 1.98 R in a closed box of walls, with
    velocities of 0.1 m/s in random directions: a compressed packing, in which contacts last, open and close."""
    O.reset()
    for k in list(O.tags.keys()):  # author, time and id of the process: the same in every run
        O.tags[k] = "fixed"
    rng = random.Random(7)
    if kind == "ViscElMat":
        mat = O.materials.append(ViscElMat(density=2500, frictionAngle=0.4, tc=TC, en=0.6, et=0.7, label="mat"))
        ip2, law, damping = Ip2_ViscElMat_ViscElMat_ViscElPhys(), Law2_ScGeom_ViscElPhys_Basic(), 0.0
    else:
        mat = O.materials.append(FrictMat(young=1e7, poisson=0.3, density=2500, frictionAngle=0.5, label="mat"))
        ip2, law, damping = Ip2_FrictMat_FrictMat_FrictPhys(), Law2_ScGeom_FrictPhys_CundallStrack(), 0.2
    a = 1.98 * R
    for i in range(3):
        for j in range(3):
            for k in range(4):
                c = tuple((n + 0.5) * a + 0.01 * R * rng.uniform(-1, 1) for n in (i, j, k))
                b = O.bodies.append(utils.sphere(c, R * rng.uniform(0.99, 1.0), material=mat, color=GREY))
                d = [rng.gauss(0, 1) for _ in range(3)]
                s = sum(v * v for v in d) ** 0.5
                O.bodies[b].state.vel = tuple(0.1 * v / s for v in d)
    for axis, pos, sense in ((0, 0, 1), (0, 3 * a, -1), (1, 0, 1), (1, 3 * a, -1), (2, 0, 1), (2, 4 * a, -1)):
        O.bodies.append(utils.wall(pos, axis=axis, sense=sense, material=mat, color=GREY))
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb(), Bo1_Wall_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom(), Ig2_Wall_Sphere_ScGeom()], [ip2], [law]),
                 NewtonIntegrator(gravity=(0, 0, -9.81), damping=damping)]
    O.dt = TC / 20 if kind == "ViscElMat" else 0.5 * utils.PWaveTimeStep()


def plain(x):
    """x as Python numbers, strings, lists and dicts: a YADE object as its class and dict(), recursively;
    minieigen vectors, matrices and quaternions as their coefficients."""
    if x is None or isinstance(x, (bool, int, float, str, bytes)):
        return x
    if isinstance(x, (list, tuple)):
        return [plain(v) for v in x]
    if isinstance(x, dict):
        return {k: plain(v) for k, v in sorted(x.items())}
    name = type(x).__name__
    if callable(getattr(x, "dict", None)):
        return dict(plain(x.dict()), __class__=name)
    if name.startswith("Quaternion"):
        return [name] + [x[i] for i in range(4)]
    if name.startswith("Matrix"):
        return [name] + [x[i, j] for i in range(x.rows()) for j in range(x.cols())]
    if name.startswith("AlignedBox"):
        return [name, plain(x.min), plain(x.max)]
    if name.startswith("Vector"):
        return [name] + list(x)
    raise TypeError("no plain form for %s" % name)


def trajectory(steps):
    out = []
    for _ in range(steps // EVERY):
        O.run(EVERY, True)
        out.append([plain((b.state.pos, b.state.ori, b.state.vel, b.state.angVel, O.forces.f(b.id), O.forces.t(b.id))) for b in O.bodies])
    return out


def scene_dicts():
    return {"bodies": [plain(b) for b in O.bodies], "materials": [plain(m) for m in O.materials],
            "interactions": [plain(i) for i in O.interactions], "engines": [plain(e) for e in O.engines]}


def xml(path):
    """The file that O.save wrote, with the scene's speed [steps/s] replaced (it is measured in wall-clock time)."""
    with open(path, "rb") as f:
        return re.sub(rb"<speed>[^<]*</speed>", b"<speed>" + WALL_CLOCK + b"</speed>", f.read())


def run_scene(kind, tmp):
    build(kind)
    out = {"trajectory": trajectory(STEPS)}
    out["real"] = sum(1 for i in O.interactions if i.isReal)
    out["dicts"] = scene_dicts()
    out["pickled"] = plain(pickle.loads(pickle.dumps(O.materials[0])))
    out["utils"] = plain((utils.unbalancedForce(), utils.kineticEnergy(), utils.sumForces(list(range(36)), (0, 0, 1)),
                          utils.getStress(1e-6), utils.aabbExtrema()))
    archive, speed = O.sceneToString(), struct.pack("<d", O.speed)
    out["speed in the archive"] = archive.count(speed)
    out["sceneToString"] = archive.replace(speed, WALL_CLOCK)
    saved = [os.path.join(tmp, "%s%d.xml" % (kind, n)) for n in (1, 2)]
    for path in saved:
        O.save(path)
    out["xml"] = [xml(path) for path in saved]
    O.load(saved[0])
    out["loaded"] = scene_dicts()
    O.save(saved[1])
    out["saved again"] = xml(saved[1])
    out["after load"] = trajectory(AFTER_LOAD)
    return out


def worker(mode, path):
    installed, recorded = [], 0
    if mode == "patched":  # a wet scene of the plugin first, with every patch installed by engines() and records kept
        from yade.wrapper import PendularLoop, PendularMat

        from yade_capillary import patches, scene
        mat = O.materials.append(PendularMat(tc=TC, en=0.5, et=0.5, density=2500, Vb=0.02 * R ** 3, gamma=0.0206, wet=True))
        O.bodies.append([utils.sphere((1.98 * R * i, 0, 0), R, material=mat, color=GREY) for i in range(8)])
        O.engines = scene.engines()
        O.dt = scene.stable_dt()
        O.run(20, True)
        installed, recorded = patches.installed(), next(e for e in O.engines if isinstance(e, PendularLoop)).nRecorded
    tmp = tempfile.mkdtemp(prefix="test_plain_yade_")
    out = {kind: run_scene(kind, tmp) for kind in ("ViscElMat", "FrictMat")}
    out["imported yade_capillary"] = "yade_capillary" in sys.modules
    out["installed"], out["recorded"] = installed, recorded
    out["threads"] = O.numThreads
    with open(path, "wb") as f:
        pickle.dump(out, f)


if "--worker" in sys.argv:
    i = sys.argv.index("--worker")
    worker(sys.argv[i + 1], sys.argv[i + 2])
    sys.exit(0)

import stress  # noqa: E402
from testing import Checker  # noqa: E402


def first_difference(a, b, where=""):
    """Where a and b first differ (a path of keys and indices), or None; floats bit for bit."""
    if type(a) is not type(b):
        return "%s: %s against %s" % (where, type(a).__name__, type(b).__name__)
    if isinstance(a, dict):
        if sorted(a) != sorted(b):
            return "%s: keys %s against %s" % (where, sorted(set(a) - set(b)), sorted(set(b) - set(a)))
        return next((d for d in (first_difference(a[k], b[k], "%s[%r]" % (where, k)) for k in sorted(a)) if d), None)
    if isinstance(a, list):
        if len(a) != len(b):
            return "%s: %d items against %d" % (where, len(a), len(b))
        return next((d for d in (first_difference(x, y, "%s[%d]" % (where, n)) for n, (x, y) in enumerate(zip(a, b))) if d), None)
    same = struct.pack("<d", a) == struct.pack("<d", b) if isinstance(a, float) else a == b  # NaN as NaN, -0 as -0
    return None if same else "%s: %r against %r" % (where, a[:200] if isinstance(a, bytes) else a, b[:200] if isinstance(b, bytes) else b)


ck = Checker("test_plain_yade")
me = os.path.realpath(sys.argv[0])
tmp = tempfile.mkdtemp(prefix="test_plain_yade_")
# Plain YADE: no launcher prefix, nothing of the build on PYTHONPATH.
plain_env = {k: v for k, v in os.environ.items() if k not in ("YADE_PREFIX", "PYTHONPATH")}
runs = {}
for name, command, env in (("plain", "/usr/bin/yade", plain_env), ("plain again", "/usr/bin/yade", plain_env),
                           ("patched", os.path.join(stress.build_dir(), "yade-capillary"), dict(os.environ))):
    out = os.path.join(tmp, name.replace(" ", "_") + ".pickle")
    p = subprocess.run([command, "-j1", "-n", "-x", me, "--worker", name.split()[0], out], env=dict(env, OMP_NUM_THREADS="1"),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=600)
    ok = p.returncode == 0 and os.path.exists(out)
    ck.true(ok, "%s run (%s): exit code %d%s" % (name, command, p.returncode, "" if ok else "\n" + p.stdout.decode(errors="replace")[-3000:]))
    if ok:
        with open(out, "rb") as f:
            runs[name] = pickle.load(f)

if len(runs) == 3:
    ref, again, patched = runs["plain"], runs["plain again"], runs["patched"]
    ck.true(not ref["imported yade_capillary"] and patched["imported yade_capillary"] and patched["installed"] == ["always", "records"]
            and patched["recorded"] == 7 and ref["threads"] == patched["threads"] == 1,
            "the plain runs never imported yade_capillary; the patched one installed the groups %s and its wet scene had %d recorded "
            "bridges of 7; one thread each" % (patched["installed"], patched["recorded"]))
    for kind in ("ViscElMat", "FrictMat"):
        r = ref[kind]
        ck.true(r["real"] >= 20 and len(r["dicts"]["interactions"]) >= r["real"],
                "%s: %d real interactions at the end of the run (collisions happened)" % (kind, r["real"]))
        ck.true(r["speed in the archive"] == 1, "%s: the scene's speed is found once in O.sceneToString's archive (%d times)"
                % (kind, r["speed in the archive"]))
        ck.true(r["xml"][0] == r["xml"][1] and len(r["xml"][0]) > 10000,
                "%s: O.save writes the same XML twice in one plain run (%d bytes): its content is compared" % (kind, len(r["xml"][0])))
    d = first_difference(ref, again)
    ck.true(d is None, "two plain runs are identical (the reference is deterministic)%s" % ("" if d is None else ": first difference at " + d))
    for kind in ("ViscElMat", "FrictMat"):
        for part in ("trajectory", "real", "dicts", "pickled", "utils", "sceneToString", "xml", "loaded", "saved again", "after load"):
            d = first_difference(ref[kind][part], patched[kind][part], "%s %s" % (kind, part))
            ck.true(d is None, "%s %s with the patches installed = plain YADE, bit for bit%s"
                    % (kind, part, "" if d is None else "; first difference (plain against patched) at " + d))
ck.finish()
