# Bad input raises a Python ValueError naming the parameter and the allowed range: at assignment
# for one material's values, on the first step for combinations of two materials.
import math
import shutil
import subprocess
import sys
import time

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_bad_input")
nan = float("nan")
good = dict(tc=1e-4, en=0.8, et=0.8, wet=True, Vb=1e-11, gamma=0.05, theta=0.2)

# At assignment (constructor keywords and attribute assignment). NaN is an error for the liquid
# parameters; for tc, en, et, kn, cn, ks, cs it means "not given", as in YADE's ViscElMat.
bad_values = [
    ("Vb", -1e-12, ["Vb", "allowed range"]), ("Vb", nan, ["Vb"]), ("Vb", 0.0, ["Vb", "when wet"]),
    ("gamma", -0.07, ["gamma"]), ("gamma", 0.0, ["gamma", "when wet"]),
    ("theta", math.pi / 2, ["theta", "[0, pi/2)"]), ("theta", -0.1, ["theta"]), ("theta", nan, ["theta"]),
    ("en", 0.0, ["en", "1]"]), ("en", 1.2, ["en"]), ("et", 0.0, ["et"]),
    ("tc", 0.0, ["tc", "(0, inf)"]), ("tc", -1e-4, ["tc"]), ("kn", -1.0, ["kn"]),
    ("frictionAngle", 2.0, ["frictionAngle"]), ("rollingFriction", -1e-4, ["rollingFriction", "[0, inf)"]),
    ("model", "Willett_numeric", ["model", "willett_full", "rabinovich_lambert"]),
    ("rupture", "bogus", ["rupture", "lian", "willett_elskamp", "+pitois"]),
    ("rupture", "pitois", ["rupture", "eta > 0"]),  # the dynamic rule needs a viscosity
    ("eta", -0.1, ["eta", "allowed range"]), ("eta", nan, ["eta"]),
    ("viscousNormal", "stokes", ["viscousNormal", "pitois", "adams_perchard"]), ("viscousSmin", 2.0, ["viscousSmin"]),
    ("calibrateFrom", "linear_irreversible", ["calibrateFrom"]),
    ("normalDamping", "sometimes", ["normalDamping", "always", "approach"]), ("friction", "sliding", ["friction", "spring", "viscous"]),
]
for name, value, words in bad_values:
    ck.raises(ValueError, lambda: PendularMat(**dict(good, **{name: value})), words, "PendularMat(%s=%r)" % (name, value))
    m = PendularMat(**good)
    before = getattr(m, name)

    def assign():
        setattr(m, name, value)
    ck.raises(ValueError, assign, words, "assignment %s = %r" % (name, value))
    after = getattr(m, name)
    ck.true(after == before or (isinstance(before, float) and math.isnan(before) and math.isnan(after)),
            "a rejected %s assignment is rolled back (%r -> %r)" % (name, before, after))
ck.raises(ValueError, lambda: PendularMat(wet=True, gamma=0.05), ["Vb", "when wet"], "wet without Vb")
# The approach-only dashpot (Richefeu2008 eq. 3) dissipates less: its en is above exp(-1).
ck.raises(ValueError, lambda: PendularMat(**dict(good, en=0.3, normalDamping="approach")), ["en", "exp(-1)", "approach"],
          "en = 0.3 with normalDamping='approach'")
m = PendularMat(**dict(good, en=0.3))


def approach():
    m.normalDamping = "approach"
ck.raises(ValueError, approach, ["en", "exp(-1)"], "normalDamping='approach' on a material with en = 0.3")
ck.true(m.normalDamping == "always", "the rejected normalDamping assignment is rolled back")
m = PendularMat(tc=1e-4, en=0.8, et=0.8)
m.Vb, m.gamma = 1e-11, 0.05
m.wet = True
ck.true(m.wet, "Vb and gamma first, then wet=True, is accepted")


def first_step(mat_a, mat_b, R=1e-3):
    O.reset()
    O.dt = 1e-6
    a = O.materials.append(mat_a)
    b = O.materials.append(mat_b)
    O.bodies.append(sphere((0, 0, 0), R, material=a, fixed=True))
    O.bodies.append(sphere((2 * R - 1e-9, 0, 0), R, material=b, fixed=True))
    O.engines = engines()
    O.step()


# On the first step: combinations of two materials, and bridges outside a model's domain.
ck.raises(ValueError, lambda: first_step(PendularMat(**good), PendularMat(**dict(good, model="richefeu"))),
          ["model", "willett_full", "richefeu"], "different models on the two materials")
ck.raises(ValueError, lambda: first_step(PendularMat(**good), PendularMat(**dict(good, rupture="lian"))),
          ["rupture"], "different rupture rules")
for name, value in (("normalDamping", "approach"), ("friction", "viscous")):
    ck.raises(ValueError, lambda: first_step(PendularMat(**good), PendularMat(**dict(good, **{name: value}))), [name, "always" if name == "normalDamping" else "spring", value],
              "different %s on the two materials" % name)
ck.raises(ValueError, lambda: first_step(PendularMat(**good), PendularMat(wet=True, Vb=1e-11, gamma=0.05)),
          ["tc, en, et", "kn, cn, ks, cs"], "contact parameters missing on one material")
ck.raises(ValueError, lambda: first_step(PendularMat(**dict(good, Vb=5e-10)), PendularMat(**dict(good, Vb=5e-10))),
          ["willett_full", "fitted domain", "V* = V/R^3 = 0.5"], "willett_full outside its fitted domain (V* = 0.5)")
# Before the hardening Vb = 1e300 m^3 was accepted and the bridge never broke (infinite rupture distance).
ck.raises(ValueError, lambda: first_step(PendularMat(**dict(good, Vb=1e300)), PendularMat(**dict(good, Vb=1e300))),
          ["volume = 1e+300 m^3", "allowed range"], "an absurd bridge volume (1e300 m^3) is refused, naming the volume")
ck.raises(ValueError, lambda: first_step(PendularMat(**dict(good, model="linear_irreversible", linearFmax=1e-7, linearKc=1.0)),
                                         PendularMat(**dict(good, model="linear_irreversible", linearFmax=4e-7, linearKc=1.0))),
          ["linearFmax", "1e-07", "4e-07"], "linearFmax differing below 1e-6 N")


def two_spheres(mat_a, mat_b):
    O.reset()
    O.dt = 1e-6
    a, b = O.materials.append(mat_a), O.materials.append(mat_b)
    O.bodies.append([sphere((0, 0, 0), 1e-3, material=a, fixed=True), sphere((2e-3 - 1e-9, 0, 0), 1e-3, material=b, fixed=True)])
    O.engines = engines()


def run_wait(mat_a, mat_b):
    two_spheres(mat_a, mat_b)
    O.run(3, True)


def bad_pair():
    return PendularMat(**good), PendularMat(**dict(good, model="richefeu"))


ck.raises(ValueError, lambda: run_wait(*bad_pair()), ["model", "richefeu"], "O.run(n, True) raises ValueError as O.step() does")


# YADE's wait() returns without looking at the simulation thread's exception if the simulation has
# already stopped when it looks. Deterministically: the thread raises and stops before O.wait().
def until_stopped():
    deadline = time.time() + 30
    while O.running and time.time() < deadline:
        time.sleep(0.01)


def run_then_wait(mat_a, mat_b):
    two_spheres(mat_a, mat_b)
    O.run(3)
    until_stopped()
    O.wait()


def returns(fn, what):
    try:
        fn()
        ck.true(True, what)
    except Exception as e:
        ck.true(False, "%s: raised %s(%s)" % (what, type(e).__name__, e))


ck.raises(ValueError, lambda: run_then_wait(*bad_pair()), ["model", "richefeu"],
          "O.run(n); O.wait() after the simulation thread stopped on the error raises ValueError")
returns(O.wait, "a second O.wait() returns (the error is raised once)")
# In O.run(n, True) the same race depends on the scheduler (the simulation thread's first step is
# over before the Python thread looks): loop the scenario under CPU load.
hogs, missed = [], []
try:
    python = shutil.which("python3") or sys.executable
    hogs = [subprocess.Popen([python, "-c", "while True: pass"]) for _ in range(2)]
    for i in range(50):
        try:
            run_wait(*bad_pair())
            missed.append("%d: no exception" % i)
        except ValueError as e:
            if "richefeu" not in str(e):
                missed.append("%d: %s" % (i, e))
        except Exception as e:
            missed.append("%d: %s(%s)" % (i, type(e).__name__, e))
finally:
    for hog in hogs:
        hog.kill()
        hog.wait()
ck.true(not missed, "O.run(3, True) raises ValueError 50 times of 50 under CPU load (missed: %s)" % missed[:5])
# An error that nobody waited for is not raised by a later run (YADE forgets it too), nor for
# another scene.
two_spheres(*bad_pair())
O.run(3)
until_stopped()
returns(lambda: O.run(3, True), "a new run after an error nobody waited for does not raise it (bridge refused, contact stays)")
two_spheres(*bad_pair())
O.run(3)
until_stopped()
first_step(PendularMat(**good), PendularMat(**good))
returns(O.wait, "O.wait() in another scene does not raise an error of the last one nobody waited for")
returns(lambda: O.run(3, True), "O.run(3, True) in another scene does not raise it either")
ck.true(O.iter == 4, "the valid scene ran (iter %d, expected 4)" % O.iter)
# An error raised by O.step() (in the Python thread) is not raised again by O.wait().
ck.raises(ValueError, lambda: first_step(*bad_pair()), ["model"], "O.step() raises ValueError")
returns(O.wait, "O.wait() after O.step() raised does not raise it again")
# The error is reported once; a valid scene runs afterwards.
first_step(PendularMat(**good), PendularMat(**good))
ck.true(O.iter == 1, "a valid scene steps normally after an error")
ck.finish()
