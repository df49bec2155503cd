"""Wet scenes, time-step limit and invariant checks for the in-YADE stress tests (import inside yade only;
tests/support, on PYTHONPATH under ctest).

Used by tests/yade/test_stress_dynamic.py, test_threads.py and test_save_continue.py:

* ``material(model, ...)``: a wet PendularMat (linear spring-dashpot from tc, en, et);
* ``oscillator_limit(k, c, m)``, ``contact_dt_limit(tc, en)`` and ``stable_dt(tc, en)``: the stability
  limit of the central-difference (leapfrog) integration of a damped oscillator and of one contact of
  that law, written independently of the plugin (``yade_capillary.scene.stable_dt(safety=1)``);
* ``box_packing(...)``: polydisperse spheres in a closed box of walls (``utils.wall``) or facets
  (``geom.facetBox``), with the engines of ``yade_capillary.scene.engines``;
* ``invariants(law)`` / ``check(ck, law, where)``: finite positions, velocities and forces, bridge count,
  liquid balance.
"""
import math
import random

from yade import O, geom, pack
from yade.utils import sphere, wall
from yade.wrapper import InteractionLoop, PendularMat, Sphere

from yade_capillary import scene as _scene
from collisions import damping_ratio

LIQUID_RTOL = 1e-12  # liquid balance, relative to the liquid formed so far (the largest of the totals)


def material(model, Vb, gamma=0.0206, theta=0.0, tc=1e-4, en=0.5, et=0.5, density=2500.0, friction=0.3, rupture="willett",
             calibrate_from="willett_full", extrapolate=True, eta=0.0):
    """A wet PendularMat. extrapolate=True: wide radius ratios leave some bridges outside a model's
    fitted domain, which are then extrapolated instead of refused. eta: liquid viscosity [Pa s]."""
    m = PendularMat(tc=tc, en=en, et=et, density=density, frictionAngle=friction, Vb=Vb, gamma=gamma, theta=theta,
                    model=model, rupture=rupture, extrapolate=extrapolate, eta=eta, wet=True)
    if model == "linear_irreversible":
        m.calibrateFrom = calibrate_from  # linearFmax = linearKc = 0: calibrated per bridge (Roy section 4.2)
    return m


def oscillator_limit(k, c, m):
    """Stability limit [s] of the central-difference (leapfrog) integration of m x'' + c x' + k x = 0:
    (2/omega0)(sqrt(1 + zeta^2) - zeta), omega0^2 = k/m, zeta = c/(2 sqrt(k m)) (Belytschko, Liu &
    Moran 2000, section 6.3); 2/omega0 undamped."""
    omega0, zeta = math.sqrt(k / m), c / (2 * math.sqrt(k * m))
    return 2 / omega0 * (math.sqrt(1 + zeta * zeta) - zeta)


def contact_dt_limit(tc, en):
    """Stability limit [s] of the central-difference integration of one contact of the law.

    With tc, en the plugin sets kn = m omega^2 (1 + x^2), cn = 2 m omega x (omega = pi/tc, m the
    effective mass), so omega0 = sqrt(kn/m) = omega sqrt(1 + x^2) for every pair whatever its mass,
    and the damping ratio is zeta = cn / (2 sqrt(kn m)) = x / sqrt(1 + x^2). Undamped: dt < 2/omega0;
    damped: dt < (2/omega0)(sqrt(1 + zeta^2) - zeta). The tangential spring (ks = 2/7 kn with the
    rotation of spheres, I = 2/5 m R^2) has the same frequency. Returns the damped limit."""
    x, omega = damping_ratio(en), math.pi / tc
    return oscillator_limit(omega * omega * (1 + x * x), 2 * omega * x, 1.0)  # per unit mass


def stable_dt(tc, en, fraction=0.9, parallel_contacts=1):
    """`fraction` of the two-body stability limit (yade_capillary.scene.stable_dt(safety=1): call this
    after the bodies are created; it equals contact_dt_limit(tc, en) for these materials, a check of
    test_stress_dynamic), divided by sqrt(parallel_contacts): how
    many contacts may act in parallel on one sphere along one direction (2: a sphere pinched between
    a neighbour and a wall or between two neighbours, the highest mode of a chain, omega = sqrt(2)
    omega0; 3: the two facets of a face diagonal of a facet box and a neighbour). At 0.9 of the
    binary limit, dense scenes gain energy and spheres leave the box."""
    limit = _scene.stable_dt(safety=1.0)  # the two-body limit itself; the fraction is applied here
    return fraction * limit / math.sqrt(parallel_contacts)


def box_packing(n, model, rmin=0.5e-3, ratio=10.0, box="walls", vstar=0.02, seed=1, speed=0.0, gravity=(0, 0, -9.81),
                porosity=0.8, **material_kw):
    """n spheres (radii uniform in [rmin, ratio rmin]) on a loose random cloud in a closed cubic box of
    walls (box='walls', utils.wall) or facets (box='facets', geom.facetBox); liquid bridge volume
    Vb = vstar rmin^3; random velocities of magnitude `speed` [m/s]. Returns (material, box side [m])."""
    O.reset()
    mat = O.materials.append(material(model, vstar * rmin ** 3, **material_kw))
    rmax = ratio * rmin
    rmean = (rmin + rmax) / 2
    solid = n * 4 / 3 * math.pi * (rmin ** 3 + rmin ** 2 * rmax + rmin * rmax ** 2 + rmax ** 3) / 4  # mean of r^3, uniform r
    L = max((solid / (1 - porosity)) ** (1 / 3), 4 * rmax)
    sp = pack.SpherePack()
    sp.makeCloud((rmax, rmax, rmax), (L - rmax, L - rmax, L - rmax), rMean=rmean, rRelFuzz=(rmax - rmin) / (rmax + rmin), num=n,
                 seed=seed)
    rng = random.Random(seed)
    for c, r in sp:
        b = O.bodies.append(sphere(c, r, material=mat))
        if speed:
            d = [rng.gauss(0, 1) for _ in range(3)]
            s = math.sqrt(sum(v * v for v in d))
            O.bodies[b].state.vel = tuple(speed * v / s for v in d)
    if box == "walls":
        for axis in range(3):
            for pos, sense in ((0.0, 1), (L, -1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = pos
                O.bodies.append(wall(tuple(p), axis=axis, sense=sense, material=mat))
    elif box == "facets":
        O.bodies.append(geom.facetBox((L / 2, L / 2, L / 2), (L / 2, L / 2, L / 2), wallMask=63, material=mat))
    else:
        raise ValueError("box = %r is unknown; allowed: walls, facets" % (box,))
    O.engines = _scene.engines(gravity=gravity)
    return mat, L


def capillary_law():
    """The Law2 functor of the scene's InteractionLoop (holds nBridges and the liquid totals)."""
    for e in O.engines:
        if isinstance(e, InteractionLoop):
            return e.lawDispatcher.functors[0]
    raise RuntimeError("no InteractionLoop in O.engines")


def spheres():
    return [b for b in O.bodies if b is not None and isinstance(b.shape, Sphere)]


def invariants(law=None, box=None):
    """Dict of the quantities the stress tests check (see check()). box: side L of the box [0, L]^3 of
    box_packing, to count the spheres that left it (by more than a largest radius)."""
    law = law or capillary_law()
    bodies = spheres()
    finite = lambda v: all(math.isfinite(x) for x in v)
    rmax = max((b.shape.radius for b in bodies), default=0.0)
    real = [I for I in O.interactions if I.isReal]
    active = [I for I in real if I.phys.active]
    return dict(
        n_spheres=len(bodies),
        bad_pos=sum(not finite(b.state.pos) for b in bodies),
        bad_vel=sum(not (finite(b.state.vel) and finite(b.state.angVel)) for b in bodies),
        bad_force=sum(not (finite(O.forces.f(b.id)) and finite(O.forces.t(b.id))) for b in O.bodies if b is not None),
        bad_fcap=sum(not (math.isfinite(I.phys.Fcap) and math.isfinite(I.phys.Fvisc) and finite(I.phys.normalForce) and finite(I.phys.shearForce)
                          and finite(I.phys.viscousShear)) for I in real),
        outside=sum(not all(-rmax <= x <= box + rmax for x in b.state.pos) for b in bodies) if box else 0,
        max_speed=max((b.state.vel.norm() for b in bodies), default=0.0),
        nBridges=law.nBridges, n_active=len(active), sum_Vb=math.fsum(I.phys.Vb for I in active),
        liquidVolume=law.liquidVolume, liquidFormed=law.liquidFormed, liquidReleased=law.liquidReleased)


def check(ck, where, law=None, box=None, escapes_fail=True):
    """Record the invariants as checks of the Checker ck; returns the invariants. box: side of the box
    of box_packing, to check that no sphere left it (escapes_fail=False: only print how many did)."""
    v = invariants(law, box)
    if box and escapes_fail:
        ck.true(v["outside"] == 0, "%s: %d spheres left the box (max speed %.3g m/s)" % (where, v["outside"], v["max_speed"]))
    elif box and v["outside"]:
        print("%s: %d spheres left the box (max speed %.3g m/s; not counted as a failure)" % (where, v["outside"], v["max_speed"]))
    ck.true(v["bad_pos"] == 0, "%s: finite positions (%d of %d spheres not)" % (where, v["bad_pos"], v["n_spheres"]))
    ck.true(v["bad_vel"] == 0, "%s: finite velocities (%d not)" % (where, v["bad_vel"]))
    ck.true(v["bad_force"] == 0, "%s: finite forces and torques (%d bodies not)" % (where, v["bad_force"]))
    ck.true(v["bad_fcap"] == 0, "%s: finite Fcap, Fvisc, normal, shear and viscous shear forces (%d interactions not)" % (where, v["bad_fcap"]))
    ck.true(v["nBridges"] >= 0 and v["nBridges"] == v["n_active"],
            "%s: nBridges = %d >= 0 and = number of active bridges %d" % (where, v["nBridges"], v["n_active"]))
    scale = max(v["liquidFormed"], v["liquidVolume"], 1e-300)
    ck.true(abs(v["liquidFormed"] - v["liquidReleased"] - v["liquidVolume"]) <= LIQUID_RTOL * scale,
            "%s: liquidFormed - liquidReleased = %.17g, liquidVolume = %.17g (rtol %g of liquidFormed)"
            % (where, v["liquidFormed"] - v["liquidReleased"], v["liquidVolume"], LIQUID_RTOL))
    ck.true(abs(v["liquidVolume"] - v["sum_Vb"]) <= LIQUID_RTOL * scale,
            "%s: liquidVolume = %.17g, sum of Vb over active bridges = %.17g" % (where, v["liquidVolume"], v["sum_Vb"]))
    return v


def state_vector():
    """Positions, velocities, angular velocities of the spheres, normal and shear forces of the real
    interactions (sorted by ids), and the law's totals, as plain floats (for exact comparisons)."""
    law = capillary_law()
    s = {}
    for b in spheres():
        s["pos%d" % b.id] = tuple(b.state.pos)
        s["vel%d" % b.id] = tuple(b.state.vel)
        s["angVel%d" % b.id] = tuple(b.state.angVel)
    for I in O.interactions:
        if I.isReal:
            k = "%d-%d" % (min(I.id1, I.id2), max(I.id1, I.id2))
            s["shear" + k] = tuple(I.phys.shearForce)
            s["normal" + k] = tuple(I.phys.normalForce)
            s["active" + k] = (float(I.phys.active),)
    for name in ("nBridges", "liquidVolume", "liquidFormed", "liquidReleased"):
        s[name] = (float(getattr(law, name)),)
    return s


def repo_root():
    """The source tree (this file is tests/support/stress.py)."""
    import os
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))


def build_dir():
    """$BUILD_DIR (set by ctest) or <repo>/build."""
    import os
    return os.environ.get("BUILD_DIR") or os.path.join(repo_root(), "build")
