# The critical time step of viscous bridges in both liquid modes, and PendularCheck's guards: the
# two-body limit of a pair with a viscous bridge (Ip2.criticalDt, stable_dt and PendularCheck.criticalDt)
# equals the leapfrog limit of the contact's dashpots plus the bridge's viscous ones at S_min
# (Elskamp2018 eq. 26, 28; coefficients from the kernels), in film mode with the largest bridge the
# pair can form (VbMax); a row of small and large wet spheres at stable_dt() never gains kinetic
# energy; a pair formed mid-run below the step is warned about in that step (or, with adaptDt, lowers
# O.dt); overlaps beyond maxOverlap are counted; a total without bridges reads exactly 0.
import math

from yade import O
from yade.utils import sphere, wall
from yade.wrapper import PendularCheck, PendularMat

from yade_capillary import kernels
from yade_capillary.scene import LOOPS, engines, stable_dt
from collisions import damping_ratio
from stress import oscillator_limit
from testing import Checker

ck = Checker("test_viscous_film_dt")
RHO, TC, EN, ET, ETA = 2500.0, 2e-4, 0.8, 0.8, 0.05
BIG, SMALL = 1e-3, 0.25e-3


def material(liquid, eta=ETA, tc=TC, Vb=None, wet=True):
    """Willett's bridge; Vb: fixed mode 2e-12 m^3 (V* = 0.03 for the big-small pair); film mode the cap
    1e-10 m^3, above the model's domain, so that the pair's largest bridge is V* = 0.1 (VbMax)."""
    Vb = Vb if Vb is not None else (1e-10 if liquid == "film" else 2e-12)
    return PendularMat(tc=tc, en=EN, et=ET, density=RHO, frictionAngle=0.3, wet=wet, Vb=Vb, gamma=0.072, theta=math.radians(20),
                       model="willett_full", rupture="willett", eta=eta, liquid=liquid)


def mass(r):
    return RHO * 4 / 3 * math.pi * r ** 3


def expected_limit(R1, R2, volume, tc=TC, eta=ETA):
    """Two free solid spheres: the leapfrog limit of kn, cn + c_visc (normal) and ks, cs + c_t + c_r
    (tangential, mass 2/7 m), the viscous coefficients at contact (S = 0, evaluated at S_min) from the
    kernels; eta = 0: the contact's dashpots alone."""
    m = mass(R1) * mass(R2) / (mass(R1) + mass(R2))
    w, x, xt = math.pi / tc, damping_ratio(EN), -math.log(ET) / math.pi
    kn, cn = m * w * w * (1 + x * x), 2 * m * w * x
    ks, cs = 2 / 7 * m * w * w * (1 + xt * xt), 2 / 7 * 2 * m * w * xt
    if eta > 0:
        cn -= kernels.viscous_normal_force("pitois", 0.0, 1.0, R1, R2, eta, volume)  # f = -c v_n at v_n = 1
        t = kernels.viscous_tangential(0.0, (1, 0, 0), (0, 1, 0), R1, R2, eta)
        cs += t["c_t"] + t["c_r"]
    return min(oscillator_limit(kn, cn, m), oscillator_limit(ks, cs, 2 / 7 * m))


def check_engine():
    return next(e for e in O.engines if isinstance(e, PendularCheck))


def ip2():
    return O.engines[2].physDispatcher.functors[0]


# ---- 1. One pair, both liquid modes: the three critical steps are the analytic limit ----
for liquid in ("fixed", "film"):
    O.reset()
    O.dt = 1e-9
    m = O.materials.append(material(liquid))
    O.bodies.append(sphere((0, 0, 0), BIG, material=m))
    O.bodies.append(sphere((BIG + SMALL - 1e-7, 0, 0), SMALL, material=m))
    O.engines = engines()
    if liquid == "film":
        O.bodies[0].state.film, O.bodies[1].state.film = 1e-11, 1e-12
    O.step()
    phys = O.interactions[0, 1].phys
    volume = phys.VbMax if liquid == "film" else phys.Vb  # film: the largest bridge the pair can form
    want = expected_limit(BIG, SMALL, volume)
    ck.close(ip2().criticalDt(0, 1), want, 1e-9, "Ip2.criticalDt, %s, eta = %g" % (liquid, ETA), "leapfrog limit with the viscous dashpots at S_min")
    ck.close(check_engine().criticalDt, want, 1e-9, "PendularCheck.criticalDt, %s" % liquid, "the same pair")
    ck.close(stable_dt(safety=1.0), want, 1e-9, "stable_dt(1), %s" % liquid, "the only pair of the scene")
    ck.true(tuple(check_engine().criticalPair) == (0, 1), "PendularCheck.criticalPair names the pair, %s" % liquid)


# ---- 2. The row of six (small and large spheres, one wall) at stable_dt() gains no energy ----
def row(liquid, loop):
    O.reset()
    m = O.materials.append(material(liquid, Vb=1e-12 if liquid == "fixed" else None))  # V* <= 0.064 for every pair
    O.bodies.append(wall((0, 0, 0), axis=0, material=m))
    x, radii = 0.0, [BIG, SMALL] * 3
    for i, r in enumerate(radii):
        x += r + 1e-6
        b = O.bodies[O.bodies.append(sphere((x, 0, 0), r, material=m))]
        b.state.vel = (0.05 if i % 2 else -0.05, 0, 0)  # to the wall, and pairs (1, 2), (3, 4) approach
        if liquid == "film":
            b.state.film = 0.05 * 4 / 3 * math.pi * r ** 3
        x += r
    O.engines = engines(loop=loop)
    O.dt = stable_dt()
    kinetic = lambda: sum(0.5 * b.state.mass * b.state.vel.squaredNorm() for b in O.bodies if b.dynamic)  # noqa: E731
    e0 = kinetic()
    e_max, v_max = e0, 0.0
    for _ in range(20000):
        O.step()
        e_max = max(e_max, kinetic())
        v_max = max(v_max, max(b.state.vel.norm() for b in O.bodies if b.dynamic))
    formed = O.engines[2].lawDispatcher.functors[0].liquidFormed
    return e0, e_max, v_max, formed


for loop in LOOPS:
    for liquid in ("fixed", "film"):
        e0, e_max, v_max, formed = row(liquid, loop)
        ck.true(formed > 0, "row of six, %s, %s loop: bridges formed (liquidFormed %.3g m^3)" % (liquid, loop, formed))
        ck.true(e_max <= e0 * (1 + 1e-9), "row of six at stable_dt(), %s, %s loop: kinetic energy never above its start (max/start = %.6g)"
                % (liquid, loop, e_max / e0))
        ck.true(v_max <= 0.05 * (1 + 1e-9), "row of six, %s, %s loop: no speed above the initial 0.05 m/s (max %.4g m/s)" % (liquid, loop, v_max))


# ---- 3. A viscous film pair formed mid-run with a limit below the step: warned in that step, or adapted ----
def approach(adapt, liquid="film", loop="fused"):
    """Two small spheres 10 um apart approach at 0.01 m/s; O.dt is 0.9 of the dry pair's safe step."""
    O.reset()
    m = O.materials.append(material(liquid))
    O.bodies.append(sphere((0, 0, 0), SMALL, material=m))
    O.bodies.append(sphere((2 * SMALL + 1e-5, 0, 0), SMALL, material=m))
    if liquid == "film":
        O.bodies[0].state.film = O.bodies[1].state.film = 1e-12
    O.bodies[1].state.vel = (-0.01, 0, 0)
    O.engines = engines(loop=loop)
    check = check_engine()
    check.adaptDt = adapt
    O.dt = 0.9 * check.dtSafety * expected_limit(SMALL, SMALL, 0.0, eta=0.0)  # below the pair's limit without viscosity
    first = None
    for _ in range(int(2e-5 / 0.01 / O.dt) + 10):
        O.step()
        if first is None and O.interactions.countReal() > 0:
            first = O.iter
            break
    return check, first


for loop in LOOPS:
    check, first = approach(False, loop=loop)
    want = expected_limit(SMALL, SMALL, O.interactions[0, 1].phys.VbMax)
    ck.true(first is not None, "mid-run pair, %s loop: the spheres met" % loop)
    ck.true(check.dtWarnings == 1, "mid-run viscous film pair below O.dt, %s loop: warned in the step it appeared (dtWarnings = %d)"
            % (loop, check.dtWarnings))
    ck.close(check.criticalDt, want, 1e-9, "mid-run pair, %s loop: PendularCheck.criticalDt" % loop, "leapfrog limit with VbMax's dashpots")
    check, first = approach(True, loop=loop)
    ck.true(check.dtAdaptations == 1 and check.dtWarnings == 0, "adaptDt, %s loop: O.dt lowered once, no warning" % loop)
    ck.close(O.dt, check.dtSafety * want, 1e-12, "adaptDt, %s loop: O.dt = dtSafety x the new limit" % loop, "PendularCheck.adaptDt")


# ---- 4. Overlaps beyond maxOverlap: counted for a fast collision, not for a slow one ----
def collision(speed, tc, loop="fused"):
    O.reset()
    m = O.materials.append(material("fixed", eta=0.0, tc=tc, wet=False))  # dry: the sphere rebounds
    O.bodies.append(wall((0, 0, 0), axis=0, material=m))
    O.bodies.append(sphere((SMALL + 1e-7, 0, 0), SMALL, material=m))
    O.bodies[1].state.vel = (-speed, 0, 0)
    O.engines = engines(loop=loop)
    O.dt = stable_dt()
    depth, met = 0.0, False
    for _ in range(200000):  # until the sphere leaves the wall
        O.step()
        real = O.interactions.has(0, 1) and O.interactions[0, 1].isReal
        if real:
            met, depth = True, max(depth, O.interactions[0, 1].geom.penetrationDepth)
        elif met:
            break
    ck.true(met and not real, "collision at %g m/s, %s loop: the sphere met the wall and left it" % (speed, loop))
    return check_engine(), depth


for loop in LOOPS:
    check, depth = collision(6.0, 5e-4, loop)
    ck.true(depth > 0.5 * SMALL, "6 m/s, tc = 5e-4 s, %s loop: the overlap exceeds half the radius (%.3g R)" % (loop, depth / SMALL))
    ck.true(check.nOverlaps > 0 and check.largestOverlap > 0.5, "6 m/s, %s loop: counted (nOverlaps %d, largest %.3g R)"
            % (loop, check.nOverlaps, check.largestOverlap))
    ck.close(check.largestOverlap, depth / SMALL, 1e-9, "6 m/s, %s loop: largestOverlap is the deepest overlap" % loop, "the run's deepest overlap")
    tc_bound = math.pi * 0.5 * SMALL / 6.0  # the warning's tc <= pi maxOverlap r / v0
    check, depth = collision(6.0, tc_bound, loop)
    ck.true(depth < 0.5 * SMALL and check.nOverlaps == 0, "6 m/s with the warning's tc bound, %s loop: overlap %.3g R below 0.5" % (loop, depth / SMALL))
    check, depth = collision(0.1, 5e-4, loop)
    ck.true(check.nOverlaps == 0 and check.largestOverlap == 0, "0.1 m/s, %s loop: not counted (overlap %.3g R)" % (loop, depth / SMALL))

collision(0.1, 5e-4)
check_engine().maxOverlap = -1
ck.raises(ValueError, O.step, "maxOverlap", "maxOverlap = -1 raises a ValueError naming it")
check_engine().maxOverlap = 0.5
check_engine().dtSafety = 3
ck.raises(ValueError, O.step, "dtSafety", "dtSafety = 3 raises a ValueError naming it")

# ---- 5. Totals: no bridge left, liquidVolume exactly 0 (not a running sum's round-off) ----
for loop in LOOPS:
    O.reset()
    O.dt = 1e-7
    ma = O.materials.append(material("fixed", eta=0.0, Vb=1e-13))
    mb = O.materials.append(material("fixed", eta=0.0, Vb=2e-13))
    O.bodies.append([sphere((0, 0, 0), SMALL, material=ma, fixed=True), sphere((2 * SMALL - 1e-7, 0, 0), SMALL, material=ma, fixed=True),
                     sphere((0, 1, 0), SMALL, material=mb, fixed=True), sphere((2 * SMALL - 1e-7, 1, 0), SMALL, material=mb, fixed=True)])
    O.engines = engines(loop=loop)
    O.step()
    law = O.engines[2].lawDispatcher.functors[0]
    ck.true(law.nBridges == 2, "two bridges formed, %s loop" % loop)
    for i in (1, 3):
        O.bodies[i].state.vel = (1.0, 0, 0)
    for _ in range(3000):
        O.step()
        if law.nBridges == 0:
            break
    ck.true(law.nBridges == 0 and law.liquidVolume == 0.0, "%s loop: no bridge left, liquidVolume = %r exactly 0" % (loop, law.liquidVolume))

ck.finish()
