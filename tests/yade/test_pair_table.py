# Contact parameters per pair of materials (Elskamp2018 Table 3): the pair tables frictionAngle,
# rollingFriction and en of Ip2_PendularMat_PendularMat_PendularPhys, in YADE's MatchMaker convention,
# override the mixing rules for the pairs of materials they list; the other pairs keep the rules (the
# MatchMaker's algo is not used); bad tables are refused naming the table, the match and the range.
import math

from yade import O
from yade.utils import sphere
from yade.wrapper import MatchMaker, PendularMat

from yade_capillary.scene import engines
from collisions import damping_ratio
from testing import Checker

ck = Checker("test_pair_table")
R, rho, tc = 1e-3, 2500.0, 1e-4
mass = rho * 4 / 3 * math.pi * R ** 3


def scene(tables, **extra):
    """Materials 0, 1 (and 2, unlisted) and one touching pair of each kind: (0, 1), (0, 0), (0, 2)."""
    O.reset()
    O.dt = tc / 200
    mats = [O.materials.append(PendularMat(tc=tc, en=en, et=0.9, density=rho, frictionAngle=phi, rollingFriction=mr, **extra))
            for en, phi, mr in ((0.5, 0.3, 1e-4), (0.7, 0.2, 3e-4), (0.8, 0.25, 2e-4))]
    pairs = {}
    for k, (ma, mb) in enumerate(((0, 1), (0, 0), (0, 2))):
        a = O.bodies.append(sphere((10 * R * k, 0, 0), R, material=mats[ma], fixed=True))
        b = O.bodies.append(sphere((10 * R * k + 2 * R - 1e-7, 0, 0), R, material=mats[mb], fixed=True))
        pairs[(ma, mb)] = (a, b)
    O.engines = engines()
    for name, table in tables.items():
        setattr(capillaryIp2, name, table)  # noqa: F821 (labelled by engines())
    O.step()
    return {k: O.interactions[a, b].phys for k, (a, b) in pairs.items()}


tables = dict(frictionAngle=MatchMaker(matches=((0, 1, 0.4),), algo="max"), rollingFriction=MatchMaker(matches=((1, 0, 5e-5),)),
              en=MatchMaker(matches=((0, 1, 0.9),)))
phys = scene(tables)
m_red, omega = mass / 2, math.pi / tc
# The listed pair (0, 1), in either order of the ids.
ck.close(phys[(0, 1)].tangensOfFrictionAngle, math.tan(0.4), 1e-14, "listed pair: friction", "the frictionAngle table")
ck.close(phys[(0, 1)].rollingFriction, 5e-5, 1e-14, "listed pair (ids reversed in the table): rolling friction", "the rollingFriction table")
x = damping_ratio(0.9)
ck.close(phys[(0, 1)].cn, 2 * m_red * omega * x, 1e-9, "listed pair: cn from the table's en = 0.9", "c = 2 m beta, Schwager2007")
ck.close(phys[(0, 1)].kn, m_red * omega ** 2 * (1 + x * x), 1e-9, "listed pair: kn from tc and the table's en", "k = m (omega^2 + beta^2)")
# Pairs the tables do not list keep the rules (the smaller angle, although the table's algo is 'max').
ck.close(phys[(0, 0)].tangensOfFrictionAngle, math.tan(0.3), 1e-14, "unlisted pair (0, 0): friction", "its material")
ck.close(phys[(0, 2)].tangensOfFrictionAngle, math.tan(0.25), 1e-14, "unlisted pair (0, 2): friction", "the smaller of 0.3 and 0.25")
ck.close(phys[(0, 2)].rollingFriction, 1.5e-4, 1e-14, "unlisted pair (0, 2): rolling friction", "the mean of 1e-4 and 2e-4")
x = damping_ratio(0.65)
ck.close(phys[(0, 2)].cn, 2 * m_red * omega * x, 1e-9, "unlisted pair (0, 2): cn from the mean en = 0.65", "c = 2 m beta, Schwager2007")
# Without tables every pair keeps the rules.
phys = scene({})
ck.close(phys[(0, 1)].tangensOfFrictionAngle, math.tan(0.2), 1e-14, "no table: friction of (0, 1)", "the smaller of 0.3 and 0.2")
ck.close(phys[(0, 1)].rollingFriction, 2e-4, 1e-14, "no table: rolling friction of (0, 1)", "the mean of 1e-4 and 3e-4")

# Bad tables: refused at assignment, naming the table, the match and the range.
O.engines = engines()
for name, table, words in (("frictionAngle", MatchMaker(matches=((0, 1, 1.7),)), ["frictionAngle", "1.7", "[0, pi/2)"]),
                           ("rollingFriction", MatchMaker(matches=((0, 1, -1e-4),)), ["rollingFriction", "-0.0001", "[0, inf)"]),
                           ("en", MatchMaker(matches=((0, 1, 1.2),)), ["en", "1.2", "1]"]),
                           ("frictionAngle", MatchMaker(matches=((0.5, 1, 0.3),)), ["frictionAngle", "0.5", "integer"])):
    def assign():
        setattr(capillaryIp2, name, table)  # noqa: F821
    ck.raises(ValueError, assign, words, "the table %s = %s" % (name, table.matches))
    ck.true(getattr(capillaryIp2, name) is None, "the rejected table %s is rolled back" % name)  # noqa: F821
# A restitution per pair needs the materials' tc, en, et; the approach-only dashpot needs en > exp(-1).
ck.raises(ValueError, lambda: scene(dict(en=MatchMaker(matches=((0, 1, 0.3),))), normalDamping="approach"), ["en", "0.3", "exp(-1)"],
          "a pair en of 0.3 with normalDamping='approach'")


def stiff_scene():
    O.reset()
    O.dt = 1e-6
    m = [O.materials.append(PendularMat(kn=100.0, cn=0.01, ks=50.0, cs=0.0, density=rho)) for _ in range(2)]
    O.bodies.append(sphere((0, 0, 0), R, material=m[0], fixed=True))
    O.bodies.append(sphere((2 * R - 1e-7, 0, 0), R, material=m[1], fixed=True))
    O.engines = engines()
    capillaryIp2.en = MatchMaker(matches=((0, 1, 0.8),))  # noqa: F821
    O.step()
ck.raises(ValueError, stiff_scene, ["en", "kn, cn, ks, cs", "tc, en, et"], "a pair en for materials given by kn, cn, ks, cs")
ck.finish()
