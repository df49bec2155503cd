"""YADE's MPI module (yade.mpy) with our law and PendularLoop: tests/support/mpi_run.py run serially and
under `mpiexec -n 2` and `-n 3` (1 and 2 worker ranks, spheres split into slabs along x).

Expected values: the serial run of the same script. Checked:
- positions (in units of the smallest radius) and velocities (in units of the largest speed) of
  every sphere after the run agree to 1e-9 (measured: 3e-17 for the packing, 2e-13 for the shear
  cell: only the order of force summation differs);
- the liquid totals summed over the ranks (yade_capillary.mpi.liquid_totals) equal the serial
  ones: the same number of bridges, volumes to 1e-12 relative. Before the law counted a bridge
  only on the rank owning it, a bridge across a subdomain boundary was counted on both ranks;
- an input error on a worker (two capillary models meeting in its slab) ends the whole run with
  a nonzero exit and the error's message within the timeout, instead of leaving the master
  waiting for ever.
"""
import json
import os
import subprocess
import tempfile

import pytest

BUILD = os.environ.get("BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))
ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
SCRIPT = os.path.join(ROOT, "tests", "support", "mpi_run.py")
LAUNCHER = os.path.join(BUILD, "yade-capillary")
TIMEOUT = 300  # s; a run takes 2-10 s
RMIN = {"packing": 0.5e-3, "shear_cell": 2.381e-3}
STEPS = {"packing": 2000, "shear_cell": 300}


def run(scene, ranks, steps, *extra):
    out = os.path.join(tempfile.mkdtemp(), "out.json")
    cmd = [LAUNCHER, "-n", "-x", SCRIPT, scene, out, str(steps), *extra]
    if ranks > 1:
        cmd = ["mpiexec", "--allow-run-as-root", "--oversubscribe", "-n", str(ranks)] + cmd
    proc = subprocess.run(cmd, capture_output=True, text=True, timeout=TIMEOUT, cwd=ROOT)
    return proc, out


def result(scene, ranks):
    proc, out = run(scene, ranks, STEPS[scene])
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    with open(out) as f:
        return json.load(f)


@pytest.fixture(scope="module")
def serial():
    return {scene: result(scene, 1) for scene in STEPS}


@pytest.mark.parametrize("ranks", [2, 3])
@pytest.mark.parametrize("scene", sorted(STEPS))
def test_mpi_matches_serial(serial, scene, ranks):
    ref, got = serial[scene], result(scene, ranks)
    assert got["ranks"] == ranks
    assert sorted(got["bodies"]) == sorted(ref["bodies"])
    vmax = max(abs(v) for pos, vel in ref["bodies"].values() for v in vel)
    assert vmax > 0
    worst = 0.0
    for key, (pos, vel) in ref["bodies"].items():
        gpos, gvel = got["bodies"][key]
        worst = max(worst, max(abs(a - b) for a, b in zip(pos, gpos)) / RMIN[scene], max(abs(a - b) for a, b in zip(vel, gvel)) / vmax)
    print("%s on %d ranks: largest scaled difference from serial %.3g" % (scene, ranks, worst))
    assert worst <= 1e-9
    n, volume, formed, released = got["totals"]
    assert ref["totals"][0] > 0 and ref["totals"][2] > 0
    assert n == ref["totals"][0] == ref["bridges"], "bridges summed over ranks: %d, serial %d" % (n, ref["totals"][0])
    for a, b in zip((volume, formed, released), ref["totals"][1:]):
        assert a == pytest.approx(b, rel=1e-12, abs=1e-30)


def test_worker_input_error_ends_the_run():
    proc, out = run("packing", 3, 2000, "error")
    text = proc.stdout + proc.stderr
    assert proc.returncode != 0
    assert "PendularMat.model must be equal on both materials" in text and "rabinovich" in text, text[-3000:]
    assert not os.path.exists(out)
