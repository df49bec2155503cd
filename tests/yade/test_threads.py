# Stress suite: the same wet packing with 1 and 2 OpenMP threads gives the same physics.
#
# This file runs under yade (-x) and starts two subprocesses of build/yade-capillary (-j1 and -j2;
# $BUILD_DIR as set by ctest, else <repo>/build), each running this same file with
# `--worker OUT`: a wet packing (walls, 400 spheres of radius ratio 3, willett_full, gravity,
# random initial velocities of 0.1 m/s), 500 steps, then positions, velocities, angular velocities,
# forces of the real interactions and the law's totals written to OUT (JSON, exact floats).
#
# What may differ between thread counts: the order in which contact forces are summed on a body
# (YADE's force container adds per-thread buffers) and hence the last bits of the forces. In a wet
# packing such differences grow with every collision and every stick-slip switch of a contact
# (granular packings are chaotic): measured on this scene, the largest position difference grows
# about tenfold every 50 steps, from 1e-18 m after 50 steps to 1e-17 .. 1e-12 m after 500 (it varies
# from run to run of -j2, whose thread scheduling differs). Hence a short run and the bounds:
# positions to 1e-9 of the box side (2e-11 m, 20x the largest difference measured); velocities to
# omega0 times that (a position error d in a contact of frequency omega0 goes with a velocity
# error omega0 d; omega0 = 3.6e4 1/s here: 8e-7 m/s), angular velocities to that over the smallest
# radius. A race in the law (a lost update of a counter, a bridge formed twice) shows instead as a
# different bridge count or liquid total: the count must be equal and the totals agree to 1e-12
# relative (every bridge has the same Vb, so they are sums of equal terms). Two -j1 runs must be
# bitwise identical (the single-threaded run is deterministic).
import json
import os
import subprocess
import sys
import tempfile

from yade import O

import stress
from collisions import damping_ratio

STEPS = 500
SPEED, RMIN = 0.1, 0.5e-3  # initial speed [m/s], smallest radius [m] (box_packing's default)
TC, EN = 1e-4, 0.5


def worker(out):
    _, L = stress.box_packing(400, "willett_full", ratio=3.0, box="walls", speed=SPEED, seed=3, porosity=0.8, tc=TC, en=EN)
    O.dt = 0.5 * stress.contact_dt_limit(TC, EN)
    O.run(STEPS, True)
    s = stress.state_vector()
    s["L"] = (L,)
    s["threads"] = (float(O.numThreads),)
    with open(out, "w") as f:
        json.dump(s, f)


if "--worker" in sys.argv:
    worker(sys.argv[sys.argv.index("--worker") + 1])
    sys.exit(0)

from testing import Checker  # noqa: E402

ck = Checker("test_threads")
launcher = os.path.join(stress.build_dir(), "yade-capillary")
me = os.path.join(stress.repo_root(), "tests", "yade", "test_threads.py")
tmp = tempfile.mkdtemp(prefix="test_threads_")
runs = {}
for run, j in (("j1", 1), ("j1 again", 1), ("j2", 2)):
    out = os.path.join(tmp, run.replace(" ", "_") + ".json")
    env = dict(os.environ, OMP_NUM_THREADS=str(j))
    p = subprocess.run([launcher, "-j%d" % j, "-n", "-x", me, "--worker", out], env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       timeout=600)
    ok = p.returncode == 0 and os.path.exists(out)
    ck.true(ok, "%s run: exit code %d%s" % (run, p.returncode, "" if ok else "\n" + p.stdout.decode(errors="replace")[-3000:]))
    if ok:
        with open(out) as f:
            runs[run] = json.load(f)

if "j1" in runs and "j1 again" in runs:
    ck.true(runs["j1"] == runs["j1 again"], "two -j1 runs are bitwise identical")
if "j1" in runs and "j2" in runs:
    a, b = runs["j1"], runs["j2"]
    ck.true(a["threads"][0] == 1 and b["threads"][0] == 2, "thread counts: %g and %g" % (a["threads"][0], b["threads"][0]))
    L = a["L"][0]
    ck.true(a["nBridges"] == b["nBridges"] and a["nBridges"][0] > 50,
            "same number of bridges: %g (-j1), %g (-j2)" % (a["nBridges"][0], b["nBridges"][0]))
    for name in ("liquidVolume", "liquidFormed", "liquidReleased"):
        ck.close(b[name][0], a[name][0], 1e-12, "%s with -j2" % name, "-j1", atol=1e-30)
    pos = [k for k in a if k.startswith("pos")]
    ck.true(set(pos) == {k for k in b if k.startswith("pos")} and len(pos) > 300, "same bodies (%d spheres)" % len(pos))
    dpos = max(max(abs(x - y) for x, y in zip(a[k], b[k])) for k in pos)
    dvel = max(max(abs(x - y) for x, y in zip(a[k], b[k])) for k in a if k.startswith("vel"))
    dang = max(max(abs(x - y) for x, y in zip(a[k], b[k])) for k in a if k.startswith("angVel"))
    print("-j1 vs -j2 after %d steps: max |dpos| = %.3g m = %.3g of the box side, max |dvel| = %.3g m/s, max |dangVel| = %.3g rad/s"
          % (STEPS, dpos, dpos / L, dvel, dang))
    ck.true(dpos <= 1e-9 * L, "positions agree to 1e-9 of the box side: max |dpos| = %.3g m, L = %.3g m" % (dpos, L))
    omega0 = 3.14159 / TC * (1 + damping_ratio(EN) ** 2) ** 0.5
    ck.true(dvel <= omega0 * 1e-9 * L, "velocities agree to omega0 1e-9 L = %.3g m/s: max |dvel| = %.3g m/s" % (omega0 * 1e-9 * L, dvel))
    ck.true(dang <= omega0 * 1e-9 * L / RMIN, "angular velocities agree to omega0 1e-9 L / R_min: max %.3g rad/s" % dang)
    same_contacts = {k for k in a if k.startswith("active")} == {k for k in b if k.startswith("active")}
    ck.true(same_contacts, "same set of real interactions")
    if same_contacts:
        dact = sum(a[k] != b[k] for k in a if k.startswith("active"))
        ck.true(dact == 0, "same bridges active (%d differ)" % dact)
ck.finish()
