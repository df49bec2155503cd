# The liquid shared over bonds (PendularMat.liquid = 'bonds', PendularBonds), each rule on a handful of
# fixed spheres against the printed rule (Richefeu2008):
#   1. the sharing: V_b = alpha R^3, R = sqrt(R1 R2) (eq. 14), sum V_b = the liquid (eq. 13), every pair within
#      the debonding distance (1 + theta/2) V_b^(1/3) of its own bond (eq. 6, rule iii) and no other; bonds at a
#      distance pull with the model's force; over a random packing of two materials, the kernel's sharing;
#   2. protocol 2 (section 3.2): a broken bond's liquid to its two particles in proportion to their diameters,
#      all of it taken by the next contact;
#   3. protocol 3 (section 4.2): a particle's share to its lowest bond in its lower hemisphere;
#   4. section 2.2: a particle's share to its remaining bonds in proportion to the partners' diameters;
#   5. protocol 1: the sharing again every interval steps and at every run of the collider;
#   6. the pairs kept dry: their fraction, reproducible by seed;
#   7. bad input.
# In the fused loop and in YADE's InteractionLoop.
import math

from yade import O
from yade.utils import sphere
from yade.wrapper import PendularBonds, PendularMat

from yade_capillary import bonds as wetting
from yade_capillary import kernels
from yade_capillary.scene import engines
from testing import Checker

ck = Checker("test_bonds_liquid")
GAMMA = 0.073


def material(append=True, **extra):
    """A bonds-mode material: its id in O.materials, or (append=False) the instance, outside O.materials (id -1)."""
    kw = dict(tc=1e-4, en=0.7, et=0.7, density=2500, frictionAngle=0.3, Vb=1e-6, gamma=GAMMA, theta=0.0, model="richefeu",
              rupture="lian", liquid="bonds")
    kw.update(extra)
    m = PendularMat(**kw)
    m.wet = True
    return O.materials.append(m) if append else m


def scene(loop, spheres, **engine):
    """Fixed spheres (centre, radius, velocity) and a PendularBonds with the given attributes."""
    O.reset()
    mat = material()
    ids = [O.bodies.append(sphere(c, r, material=mat, fixed=True)) for c, r, v in spheres]
    for i, (c, r, v) in zip(ids, spheres):
        O.bodies[i].state.vel = v
    e = PendularBonds(**engine)
    O.engines = engines(loop=loop, extra=[e])
    O.dt = 1e-6
    return ids, e


def bond(a, b):
    I = O.interactions[a, b] if O.interactions.has(a, b) else None
    return I.phys if I is not None and I.isReal and I.phys.active else None


def cube(r1, r2):
    return math.sqrt(r1 * r2) ** 3


for loop in ("fused", "standard"):
    mm = 1e-3
    # 1. The sharing. A chain of radii 1, 0.5, 1, 1, 1 mm with gaps 0, 0.05, 0.15, 0.4 mm. Thresholds of lian
    # at theta = 0: alpha >= gap^3 / R^3: 0, 3.5e-4, 3.4e-3, 6.4e-2. The liquid of alpha = 0.01 on the first
    # three pairs: the fourth would need alpha >= 0.064, and with it alpha would fall below 0.01.
    radii, gaps = [1 * mm, 0.5 * mm, 1 * mm, 1 * mm, 1 * mm], [0.0, 0.05 * mm, 0.15 * mm, 0.4 * mm]
    xs = [0.0]
    for i, g in enumerate(gaps):
        xs.append(xs[-1] + radii[i] + radii[i + 1] + g)
    cubes = [cube(radii[i], radii[i + 1]) for i in range(4)]
    liquid = 0.01 * sum(cubes[:3])
    ids, e = scene(loop, [((x, 0, 0), r, (0, 0, 0)) for x, r in zip(xs, radii)])
    O.bodies[ids[2]].state.film = liquid  # free liquid on one particle: the first step shares it
    O.step()
    ck.close(e.alpha, 0.01, 1e-12, "%s: alpha" % loop, "Richefeu2008 eq. (13)-(14): liquid / sum R^3 of the eligible pairs")
    ck.true(e.nShared == 3 and e.nSharings == 1, "%s: three bonds, one sharing (got %d, %d)" % (loop, e.nShared, e.nSharings))
    O.step()  # the bonds made at the end of the first step pull from the second
    for i in range(3):
        p = bond(ids[i], ids[i + 1])
        ck.true(p is not None, "%s: pair %d-%d bonded" % (loop, i, i + 1))
        ck.close(p.Vb, 0.01 * cubes[i], 1e-12, "%s: V_b of pair %d-%d" % (loop, i, i + 1), "Richefeu2008 eq. (14), R = sqrt(R1 R2)")
        if gaps[i] > 0:
            F = float(kernels.force("richefeu", gaps[i], radii[i], radii[i + 1], p.Vb, GAMMA, 0.0, rupture="lian"))
            ck.close(p.Fcap, F, 1e-12, "%s: force of the bond %d-%d at a gap of %g mm" % (loop, i, i + 1, gaps[i] / mm),
                     "Richefeu2008 eq. (10) (yade_capillary.kernels.force)")
    ck.true(bond(ids[3], ids[4]) is None, "%s: the pair at 0.4 mm, beyond the debonding distance, has no bond" % loop)
    law = O.engines[2].lawDispatcher.functors[0]
    tot = law.liquidTotals()
    ck.close(tot["bridges"], liquid, 1e-12, "%s: sum V_b = the liquid" % loop, "Richefeu2008 eq. (13)")
    ck.true(tot["films"] == 0, "%s: no free liquid after the sharing" % loop)
    ck.close(e.reach, (0.01 * cubes[2]) ** (1 / 3), 1e-12, "%s: the longest debonding distance" % loop, "Richefeu2008 eq. (6), theta = 0")
    ck.close(wetting.coordination(), 2 * 3 / 5, 1e-12, "%s: bond coordination number" % loop, "2 bonds / particles")

    # 2. Protocol 2. Spheres of 1 and 0.5 mm in contact share the liquid; the small one leaves along +x and
    # the bond breaks: 2/3 of it stays on the large sphere, 1/3 on the small one (diameters). A third
    # sphere reaches the large one from -x and takes all its free liquid.
    V = 0.01 * cube(mm, 0.5 * mm)
    ids, e = scene(loop, [((0, 0, 0), mm, (0, 0, 0)), ((1.5 * mm, 0, 0), 0.5 * mm, (0.5, 0, 0)),
                          ((-3.5 * mm, 0, 0), mm, (0.5, 0, 0))], protocol="particles")
    O.bodies[ids[0]].state.film = V
    O.step()
    ck.close(bond(ids[0], ids[1]).Vb, V, 1e-12, "%s: protocol 2: the first bond holds the liquid" % loop, "Richefeu2008 eq. (13), one pair")
    while bond(ids[0], ids[1]) is not None and O.iter < 2000:
        O.step()
    O.step()
    ck.close(O.bodies[ids[0]].state.film, V * 2 / 3, 1e-12, "%s: protocol 2: the large sphere's share" % loop, "Richefeu2008 section 3.2: D1/(D1 + D2)")
    ck.close(O.bodies[ids[1]].state.film, V / 3, 1e-12, "%s: protocol 2: the small sphere's share" % loop, "Richefeu2008 section 3.2")
    while bond(ids[0], ids[2]) is None and O.iter < 6000:
        O.step()
    p = bond(ids[0], ids[2])
    ck.true(p is not None, "%s: protocol 2: the new contact has a bond" % loop)
    ck.close(p.Vb, V * 2 / 3, 1e-12, "%s: protocol 2: the new bond takes all the free liquid" % loop, "Richefeu2008 section 3.2")
    ck.true(O.bodies[ids[0]].state.film == 0, "%s: protocol 2: none left on the large sphere" % loop)

    # 3. and 4. A centre sphere C with bonds below (B, 1 mm), low aside (S, 0.5 mm, 10 deg below the horizontal),
    # above (U, 1 mm) and to +y (P, 1 mm), which leaves. C's half of P's bond goes to B (lowest), or to B, S
    # and U in proportion 1 : 0.5 : 1 (neighbours); P keeps its half as free liquid (no other bond).
    s10, c10 = math.sin(math.radians(10)), math.cos(math.radians(10))
    layout = [((0, 0, 0), mm, (0, 0, 0)), ((0, 0, -2 * mm), mm, (0, 0, 0)), ((1.5 * mm * c10, 0, -1.5 * mm * s10), 0.5 * mm, (0, 0, 0)),
              ((0, 0, 2 * mm), mm, (0, 0, 0)), ((0, 2 * mm, 0), mm, (0, 0.5, 0))]
    alpha = 0.01
    for protocol in ("lowest", "neighbours"):
        ids, e = scene(loop, layout, protocol=protocol)
        C, B, S, U, P = ids
        O.bodies[C].state.film = alpha * (3 * mm ** 3 + cube(mm, 0.5 * mm))
        O.step()
        ck.close(e.alpha, alpha, 1e-12, "%s, %s: alpha of the four bonds" % (loop, protocol), "Richefeu2008 eq. (13)-(14)")
        before = {k: bond(C, k).Vb for k in (B, S, U)}
        while bond(C, P) is not None and O.iter < 2000:
            O.step()
        O.step()
        half = alpha * mm ** 3 / 2
        if protocol == "lowest":
            gain = {B: half, S: 0.0, U: 0.0}
            source = "Richefeu2008 section 4.2: the lowest contact in the lower hemisphere"
        else:
            gain = {B: half * 1 / 2.5, S: half * 0.5 / 2.5, U: half * 1 / 2.5}
            source = "Richefeu2008 section 2.2: the remaining bonds, in proportion to the diameters"
        for k, name in ((B, "below"), (S, "aside"), (U, "above")):
            ck.close(bond(C, k).Vb, before[k] + gain[k], 1e-12, "%s, %s: the bond %s" % (loop, protocol, name), source)
        ck.close(O.bodies[P].state.film, half, 1e-12, "%s, %s: the leaving sphere keeps its half, having no other bond" % (loop, protocol),
                 "Richefeu2008 section 3.2: D1/(D1 + D2)")
        ck.true(O.bodies[C].state.film == 0 and e.nPlaced == 1 and e.nFree == 1, "%s, %s: one share placed, one free" % (loop, protocol))
        ck.close(O.engines[2].lawDispatcher.functors[0].liquidTotals()["total"],
                 alpha * (3 * mm ** 3 + cube(mm, 0.5 * mm)), 1e-12, "%s, %s: liquid conserved" % (loop, protocol), "the liquid at the start")

    # 5. Protocol 1. A-B in contact, B-C 0.1 mm apart, the liquid of alpha = 0.01 on both. A leaves: between
    # sharings its bond's liquid waits on A and B; the next sharing gives it all to B-C (alpha = 0.02).
    ids, e = scene(loop, [((-2 * mm, 0, 0), mm, (-2.0, 0, 0)), ((0, 0, 0), mm, (0, 0, 0)), ((2.1 * mm, 0, 0), mm, (0, 0, 0))],
                   protocol="update", interval=400)
    A, B_, C_ = ids
    O.bodies[B_].state.film = 0.02 * mm ** 3
    O.step()
    ck.close(e.alpha, 0.01, 1e-12, "%s: protocol 1: alpha of two bonds" % loop, "Richefeu2008 eq. (13)-(14)")
    while bond(A, B_) is not None and O.iter < 399:
        O.step()
    O.step()
    ck.close(O.bodies[A].state.film + O.bodies[B_].state.film, 0.01 * mm ** 3, 1e-12, "%s: protocol 1: the broken bond waits on its particles" % loop,
             "liquid conserved")
    O.run(401 - O.iter, True)
    ck.true(e.nSharings == 2 and e.lastSharing == 400, "%s: protocol 1: the sharing every 400 steps (got %d at %d)" % (loop, e.nSharings, e.lastSharing))
    ck.close(e.alpha, 0.02, 1e-12, "%s: protocol 1: all the liquid on the one eligible pair" % loop, "Richefeu2008 eq. (13)-(14)")
    ck.close(bond(B_, C_).Vb, 0.02 * mm ** 3, 1e-12, "%s: protocol 1: its volume" % loop, "Richefeu2008 eq. (14)")
    ck.true(O.bodies[A].state.film == 0 and O.bodies[B_].state.film == 0, "%s: protocol 1: no free liquid after the sharing" % loop)
    # interval = 0: a sharing at every run of the collider (the paper's update of the contact list).
    e.interval = 0
    collider = [x for x in O.engines if x.label == "collider"][0]
    runs = collider.numAction
    while collider.numAction == runs and O.iter < 3000:
        O.step()
    ck.true(e.lastSharing == O.iter - 1, "%s: protocol 1: a sharing in the step of the collider's run (at %d, step %d)" % (loop, e.lastSharing, O.iter - 1))

# 1b. The sharing over a random loose packing of two materials (theta 0 and 0.8 rad; radii 0.5 to 1 mm): the
# engine's bonds and alpha are the kernel's sharing (share_liquid) over every pair within the collider's reach,
# the gaps computed here from the positions, whether the engine met a pair as a contact or as a potential pair, and
# whether the materials are in O.materials or not.
def packing(loop, append):
    import random
    rng = random.Random(5)
    O.reset()
    mats = [material(append), material(append, theta=0.8)]
    placed = []
    while len(placed) < 150:
        r = (0.5 + 0.5 * rng.random()) * 1e-3
        c = tuple(12e-3 * rng.random() for _ in range(3))
        if placed and len(placed) % 4 == 0:  # every fourth sphere in contact with the one before, 0.01 mm deep
            q, rq, _ = placed[-1]
            u = [rng.gauss(0, 1) for _ in range(3)]
            n = math.sqrt(sum(x * x for x in u))
            c = tuple(qk + (r + rq - 0.01e-3) * uk / n for qk, uk in zip(q, u))
        if all(math.dist(c, q) > r + rq - 0.02e-3 for q, rq, _ in placed):
            placed.append((c, r, rng.randrange(2)))
    ids = [O.bodies.append(sphere(c, r, material=mats[m], fixed=True)) for c, r, m in placed]
    e = PendularBonds()
    O.engines = engines(loop=loop, extra=[e])
    [x for x in O.engines if x.label == "collider"][0].verletDist = 0.6e-3
    O.dt = 1e-6
    O.bodies[ids[0]].state.film = 1e-9
    O.step()
    pairs, thresholds, cubes_, touching = [], [], [], set()
    for i, (ci, ri, mi) in enumerate(placed):
        for j in range(i + 1, len(placed)):
            cj, rj, mj = placed[j]
            gap = math.dist(ci, cj) - ri - rj
            if gap < 0.5e-3:
                pairs.append((ids[i], ids[j]))
                if gap < 0:
                    touching.add((ids[i], ids[j]))
                thresholds.append(kernels.bond_threshold("lian", ri, rj, gap, 0.8 * mi, 0.8 * mj))
                cubes_.append(kernels.bond_cube(ri, rj))
    alpha, bonded = kernels.share_liquid(thresholds, cubes_, 1e-9)
    tag = "" if append else ", materials outside O.materials"
    want = {p for p, b in zip(pairs, bonded) if b}
    got = {(I.id1, I.id2) for I in O.interactions if I.isReal and I.phys.active}
    contacts = len(want & touching)
    ck.true(got == want and len(want) > 50 and 0 < contacts < len(want),
            "%s%s: random packing: the engine's %d bonds are the kernel's %d (%d in contact)" % (loop, tag, len(got), len(want), contacts))
    ck.close(e.alpha, alpha, 1e-12, "%s%s: random packing: alpha" % (loop, tag), "share_liquid over the pairs within reach (Richefeu2008 eq. 13-14, rule iii)")


for loop in ("fused", "standard"):
    packing(loop, True)
packing("fused", False)  # two materials outside O.materials: both have id -1

# 6. The pairs kept dry: a fraction of the candidates, the same for a seed. A cubic lattice of 6^3 spheres of
# 1 mm, 0.05 mm apart: 540 neighbour pairs.
def lattice(dry, seed):
    O.reset()
    mat = material()
    for i in range(6):
        for j in range(6):
            for k in range(6):
                O.bodies.append(sphere((i * 2.05e-3, j * 2.05e-3, k * 2.05e-3), 1e-3, material=mat, fixed=True))
    e = PendularBonds(dryFraction=dry, seed=seed)
    O.engines = engines(extra=[e])
    O.dt = 1e-6
    O.bodies[0].state.film = 540 * 0.01e-9
    O.step()
    return e, {(I.id1, I.id2) for I in O.interactions if I.isReal and I.phys.active}


e0, all_pairs = lattice(0.0, 0)
ck.true(len(all_pairs) == 540 and e0.nShared == 540, "lattice: the 540 neighbour pairs bonded without dry pairs (got %d)" % len(all_pairs))
e1, half1 = lattice(0.5, 11)
e2, half2 = lattice(0.5, 11)
e3, half3 = lattice(0.5, 12)
frac = len(half1) / 540
ck.true(abs(frac - 0.5) < 3 * math.sqrt(0.25 / 540), "dryFraction 0.5: %.3f of the pairs bonded (3 sigma of a fair coin: 0.065)" % frac)
ck.true(half1 == half2 and half1 != half3, "the dry pairs are the same for a seed, others for another seed")
ck.true(all(not O.interactions[a, b].phys.keptDry for a, b in half3), "no kept-dry pair holds a bond")
ck.close(e3.alpha * len(half3), 540 * 0.01, 1e-12, "dry pairs: the same liquid on fewer bonds", "Richefeu2008 eq. (13)")

# 6b. A sharing between steps sees the pairs at a distance the collider lists, also before the first step: the
# collider runs first (as after O.load, which keeps no potential pair). The lattice's 540 pairs, all 0.05 mm apart.
O.reset()
mat = material()
for i in range(6):
    for j in range(6):
        for k in range(6):
            O.bodies.append(sphere((i * 2.05e-3, j * 2.05e-3, k * 2.05e-3), 1e-3, material=mat))
O.engines = engines(extra=[PendularBonds()])
O.dt = 1e-6
e = wetting.engine()
e.share(540 * 0.01e-9)
pairs = {(I.id1, I.id2) for I in O.interactions if I.isReal and I.phys.active}
ck.true(len(pairs) == 540 and e.nShared == 540, "share() before the first step: the 540 pairs at a distance bonded (got %d)" % len(pairs))
ck.close(e.alpha, 0.01, 1e-12, "share() before the first step: alpha", "Richefeu2008 eq. (13)-(14)")

# 7. Bad input.
ck.raises(ValueError, lambda: PendularBonds(protocol="gravity"), "protocol", "an unknown protocol")
ck.raises(ValueError, lambda: PendularBonds(dryFraction=1.5), "dryFraction", "a dry fraction above 1")
ck.raises(ValueError, lambda: PendularBonds(dryFraction=-0.1), "dryFraction", "a dry fraction below 0")
ck.raises(ValueError, lambda: PendularBonds(interval=-1), "interval", "a negative interval")
ck.raises(ValueError, lambda: PendularBonds(down=(0, 0, 0)), "down", "a zero direction")
ck.raises(ValueError, lambda: wetting.water_volume(-0.01), "w = -0.01", "a negative water content")
ck.raises(ValueError, lambda: PendularBonds().share(-1e-9), "added", "negative liquid added")
O.reset()
m = material()
O.bodies.append([sphere((0, 0, 0), 1e-3, material=m), sphere((2e-3, 0, 0), 1e-3, material=m)])
O.engines = engines()
O.dt = 1e-6
ck.raises(ValueError, lambda: O.step(), "needs a PendularBonds engine", "bonds without the engine")
O.reset()
m = material(model="young_laplace_table")
O.bodies.append([sphere((0, 0, 0), 1e-3, material=m), sphere((2e-3, 0, 0), 1e-3, material=m)])
O.engines = engines(extra=[PendularBonds()])
O.dt = 1e-6
ck.raises(ValueError, lambda: O.step(), "its own range", "bonds with a model of its own range")
# A water content and its sharing: w = liquid mass / solid mass.
O.reset()
m = material()
O.bodies.append([sphere((0, 0, 0), 1e-3, material=m, fixed=True), sphere((2.05e-3, 0, 0), 1e-3, material=m, fixed=True)])
O.engines = engines(extra=[PendularBonds()])
O.dt = 1e-6
O.step()
e = wetting.share_water(1e-4)
solid = 2 * 2500 * 4 / 3 * math.pi * 1e-9
ck.close(O.interactions[0, 1].phys.Vb, 1e-4 * solid / 1000, 1e-12, "share_water: the liquid of w = 1e-4", "w = m_w / m_s (Richefeu2008 section 3.1.2)")
ck.raises(ValueError, lambda: wetting.share_water(0.5e-4), "not removed", "a water content below the liquid present")
ck.finish()
