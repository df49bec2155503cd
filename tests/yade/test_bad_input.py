# Bad input raises a Python ValueError naming the parameter and the allowed range: at assignment
# for one material's values, on the first step for combinations of two materials.
import math

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularMat

from yade_capillary.scene import engines
from yade_capillary.testing import Checker

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
    ("frictionAngle", 2.0, ["frictionAngle"]),
    ("model", "Willett_numeric", ["model", "willett_full", "rabinovich_lambert"]),
    ("rupture", "pitois", ["rupture", "lian", "willett_elskamp"]),
    ("calibrateFrom", "linear_irreversible", ["calibrateFrom"]),
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
ck.raises(ValueError, lambda: first_step(PendularMat(**good), PendularMat(wet=True, Vb=1e-11, gamma=0.05)),
          ["tc, en, et", "kn, cn, ks, cs"], "contact parameters missing on one material")
ck.raises(ValueError, lambda: first_step(PendularMat(**dict(good, Vb=5e-10)), PendularMat(**dict(good, Vb=5e-10))),
          ["willett_full", "fitted domain", "V* = V/R^3 = 0.5"], "willett_full outside its fitted domain (V* = 0.5)")
ck.raises(ValueError, lambda: first_step(PendularMat(**dict(good, model="linear_irreversible", linearFmax=1e-7, linearKc=1.0)),
                                         PendularMat(**dict(good, model="linear_irreversible", linearFmax=4e-7, linearKc=1.0))),
          ["linearFmax", "1e-07", "4e-07"], "linearFmax differing below 1e-6 N")


def run_wait(mat_a, mat_b):
    O.reset()
    O.dt = 1e-6
    a, b = O.materials.append(mat_a), O.materials.append(mat_b)
    O.bodies.append([sphere((0, 0, 0), 1e-3, material=a, fixed=True), sphere((2e-3 - 1e-9, 0, 0), 1e-3, material=b, fixed=True)])
    O.engines = engines()
    O.run(3, True)


ck.raises(ValueError, lambda: run_wait(PendularMat(**good), PendularMat(**dict(good, model="richefeu"))), ["model", "richefeu"],
          "O.run(n, True) raises ValueError as O.step() does")
# The error is reported once; a valid scene runs afterwards.
first_step(PendularMat(**good), PendularMat(**good))
ck.true(O.iter == 1, "a valid scene steps normally after an error")
ck.finish()
