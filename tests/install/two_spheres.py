# Run by test_install.sh with Debian's /usr/bin/yade after the package yade-capillary is installed:
# the plugin must come from YADE's own plugin folder and yade_capillary from dist-packages (no
# launcher, no build directory), and the bridge force between two wetted spheres must equal the
# kernels' force at the same gap. Exit status 0 when all checks pass.
# Usage: yade -n -x two_spheres.py PLUGIN_DIR PYTHON_DIR
import math
import sys

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

import yade_capillary
from yade_capillary import kernels
from yade_capillary.scene import engines

plugin_dir, python_dir = sys.argv[1], sys.argv[2]
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


check(yade_capillary.__file__.startswith(python_dir + "/yade_capillary/"), "yade_capillary from %s (%s)" % (python_dir, yade_capillary.__file__))
with open("/proc/self/maps") as f:
    plugins = sorted({line.split()[-1] for line in f if line.rstrip().endswith("/libyadecapillary.so")})
check(plugins == [plugin_dir + "/libyadecapillary.so"], "the plugin loaded once, from %s (mapped: %s)" % (plugin_dir, plugins))

# Two fixed spheres of 1 mm with a water-like bridge (V* = V/R^3 = 0.01, theta = 20 deg), as in tests/yade/test_law.py.
R, V, gamma, theta, model = 1e-3, 1e-11, 0.05, math.radians(20), "willett_full"
O.dt = 1e-6
mat = O.materials.append(PendularMat(tc=2e-5, en=0.8, et=0.8, density=2500, wet=True, Vb=V, gamma=gamma, theta=theta, model=model))
b1 = O.bodies.append(sphere((0, 0, 0), R, material=mat, fixed=True))
b2 = O.bodies.append(sphere((2 * R, 0, 0), R, material=mat, fixed=True))
O.engines = engines()
O.step()  # touching: the bridge forms
rupture = kernels.bridge(model, R, R, V, gamma, theta)["rupture"]
O.bodies[b2].state.pos = (2 * R + 0.4 * rupture, 0, 0)
O.step()
gap = -O.interactions[b1, b2].geom.penetrationDepth
F, expected = O.forces.f(b1)[0], kernels.force(model, gap, R, R, V, gamma, theta)
check(expected > 0 and abs(F - expected) <= 1e-9 * expected,
      "bridge force %.12g N at gap %.6g m, kernels.force %.12g N (rtol 1e-9)" % (F, gap, expected))
sys.exit(1 if failures else 0)
