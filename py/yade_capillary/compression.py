"""Richefeu et al. 2008's simple compression test (section 4.2) inside yade: a cylinder of wet glass beads, the
liquid shared over bonds (PendularMat.liquid = 'bonds'), freed from its mould and compressed between two plates.

Preparation (section 4.2.1): the spheres of Table II fall into a cylindrical mould without friction and bonds; the
friction is set to mu and an upper plate seals the sample (17 mm high at a solid fraction of 0.62 in the paper);
the liquid of the water content is shared over every eligible pair (PendularBonds); the mould is removed and the
sample relaxes under gravity and its capillary cohesion. Loading (section 4.2.2): the upper plate moves down at
constant speed; the axial stress is its force over the sample's cross-section, the strength its peak.

Every parameter lives in CONFIGS (what the paper leaves open is chosen there and in docs/richefeu.md); scripts only
choose names.
"""
import json
import math
import os
import random
import time

from . import glassbeads

# Richefeu2008 section 4.2.1 and Table II: 8000 spheres of 0.8 to 1.3 mm in proportions 10/20/20/20/20/10 % (by
# number: the mould of 25 mm then holds them 17 mm high at phi = 0.62, as printed), glass and water as in the
# direct shear test (yade_capillary.directshear). The plate moves at 1 mm/s for 2 s (section 4.2.2). Chosen (not
# printed): the contact law of the direct shear test; the masses (and the liquid's density in the water content)
# times mass_scale with gravity over mass_scale, so that weights and the liquid are physical while the time step
# grows as sqrt(mass_scale) (section 2: "the particle masses can be increased artificially" in quasi-static
# loadings); richefeu beyond V* = 0.1 with extrapolate (the model at V* = 0.1 stretched to the bond's own
# rupture distance), since w of 4 and 6 % gives alpha of about 0.17 to 0.25.
PAPER = dict(D=0.025, n=8000, diameters=(0.8e-3, 0.9e-3, 1.0e-3, 1.1e-3, 1.2e-3, 1.3e-3), fractions=(0.1, 0.2, 0.2, 0.2, 0.2, 0.1),
             rho=2500.0, kn=2000.0, damping=0.3, mu=0.4, gamma=0.073, theta=0.0, extrapolate=True, mass_scale=100.0, speed=1e-3,
             shortening=2e-3, fill_height=0.036, settle_s=0.4, unload_s=0.2, unload_stages=20, relax_s=1.0, relax_chunk_s=0.02, dt_safety=0.2, records=200, seed=1)
# A sample of 10 mm across (about 500 spheres), shortened by 1 mm: a check of the machinery, not a reproduction.
CI = dict(PAPER, D=0.010, n=500, fill_height=0.016, settle_s=0.25, shortening=1e-3, records=50)
CONFIGS = {"paper": PAPER, "ci": CI}
GRAVITY = glassbeads.GRAVITY


def build(config="ci", protocol="particles", dry_fraction=0.0, seed=None, loop="fused"):
    """The mould with its loose spheres (no liquid, no friction); returns the info dict of the scene."""
    from yade import O, geom
    from yade.utils import sphere, wall
    cfg = dict(CONFIGS[config])
    rng = random.Random(cfg["seed"] if seed is None else seed)
    O.reset()
    beads, walls = glassbeads.materials(cfg)
    R = cfg["D"] / 2
    mould = O.bodies.append(geom.facetCylinder((0, 0, cfg["fill_height"]), R, 2 * cfg["fill_height"], segmentsNumber=48, wallMask=4, material=walls))
    bottom = O.bodies.append(wall(0, axis=2, sense=1, material=walls))
    spheres = [O.bodies.append(sphere(p, r, material=beads)) for p, r in glassbeads.fill(cfg, rng)]
    glassbeads.engines(cfg, protocol, dry_fraction, loop)  # full gravity: the physical weights after settle_and_seal
    return dict(config=config, cfg=cfg, mould=mould, bottom=bottom, top=None, spheres=spheres, protocol=protocol, dry_fraction=dry_fraction)


def _top(info):
    from yade import O
    return max(O.bodies[i].state.pos[2] + O.bodies[i].shape.radius for i in info["spheres"])


def solid_fraction(info, height):
    """The spheres' volume over the cylinder of the mould's diameter and `height` [-]."""
    from yade import O
    solid = sum(4 / 3 * math.pi * O.bodies[i].shape.radius ** 3 for i in info["spheres"])
    return solid / (math.pi * info["cfg"]["D"] ** 2 / 4 * height)


def settle_and_seal(info, log=print):
    """Settling without friction and bonds (settle_s; under the full gravity, which makes the scaled masses
    mass_scale times heavier), then the physical weights (gravity over mass_scale) and a rest, still without
    friction, until the highest sphere stops; friction mu on every contact (Ip2.updateContacts) and the upper plate
    on the highest sphere (fixed until the loading)."""
    from yade import O
    from yade.utils import wall
    from yade.wrapper import NewtonIntegrator
    cfg = info["cfg"]
    O.run(int(cfg["settle_s"] / O.dt), True)
    # The overlaps of mass_scale times the weight would stay locked in by the friction and burst the sample
    # outwards when its mould is removed (in a 17 mm sample at w = 2 %: spheres 15 mm beyond the mould within
    # 0.3 s, the bond coordination from 9.2 to 5.9); dropped at once, they throw the spheres up. The gravity comes
    # down to the physical weights in unload_stages geometric steps over unload_s, then the sample rests.
    newton = [e for e in O.engines if isinstance(e, NewtonIntegrator)][0]
    stages = cfg["unload_stages"]
    for k in range(1, stages + 1):
        newton.gravity = (0, 0, -GRAVITY / cfg["mass_scale"] ** (k / stages))
        O.run(max(1, int(cfg["unload_s"] / stages / O.dt)), True)
    rest = _rest(info)
    glassbeads.frictional(cfg)
    height = _top(info)
    walls = [m for m in O.materials if m.label == "walls"][0]
    info["top"] = O.bodies.append(wall(height, axis=2, sense=-1, material=walls))
    info["height_sealed_m"], info["phi_sealed"] = height, solid_fraction(info, height)
    log("sealed: %.2f mm high, phi %.4f (after %.2f s at rest under the physical weights)" % (1e3 * height, info["phi_sealed"], rest))


def wet(info, w):
    """Shares the liquid of water content w over the eligible pairs (Richefeu2008 eq. 13-14); the water content
    counts the physical solid mass (state.mass over mass_scale)."""
    from . import bonds
    if w > 0:
        bonds.share_water(w, 1000.0 * info["cfg"]["mass_scale"])


def _rest(info):
    """Runs until the highest sphere moves by less than 1 um in each of two successive relax_chunk_s (the scaled
    masses respond mass_scale^(1/2) times slower than the real beads; one chunk may span a bouncing sphere's apex),
    at most relax_s; returns the time it took [s]."""
    from yade import O
    cfg = info["cfg"]
    chunk, last, still, t0 = max(1, int(cfg["relax_chunk_s"] / O.dt)), _top(info), 0, O.time
    for _ in range(max(1, int(cfg["relax_s"] / cfg["relax_chunk_s"]))):
        O.run(chunk, True)
        now = _top(info)
        still = still + 1 if abs(now - last) < 1e-6 else 0
        if still == 2:
            break
        last = now
    return O.time - t0


def unmould(info, log=print):
    """Removes the mould; the sample relaxes until its highest sphere stops (at most relax_s); the plate is lowered
    onto that sphere. Returns its settlement [m]."""
    from yade import O
    before = _top(info)
    for i in info["mould"]:
        O.bodies.erase(i)
    plate = O.bodies[info["top"]].state
    plate.pos = (plate.pos[0], plate.pos[1], before + max(info["cfg"]["diameters"]))  # off the sample while it relaxes
    info["relax_time_s"] = _rest(info)
    info["settlement_m"] = before - _top(info)
    # The loading starts from the sample's top as it stands (a weakly bonded sample settles by more than the travel).
    plate.pos = (plate.pos[0], plate.pos[1], _top(info))
    log("unmoulded: settled by %.3f mm in %.3f s" % (1e3 * info["settlement_m"], info["relax_time_s"]))
    return info["settlement_m"]


def compress(info, outdir):
    """Moves the upper plate down at the configuration's speed over its shortening; writes compression.csv (the
    axial stress, its force over the mould's cross-section) and returns the rows."""
    from yade import O
    from . import bonds
    cfg = info["cfg"]
    A = math.pi * cfg["D"] ** 2 / 4
    top = O.bodies[info["top"]]
    top.state.vel = (0, 0, -cfg["speed"])
    z0 = top.state.pos[2]
    steps = int(cfg["shortening"] / cfg["speed"] / O.dt)
    law = glassbeads.law()
    rows = []
    for chunk in glassbeads.chunks(steps, cfg["records"]):
        O.run(chunk, True)
        rows.append(dict(shortening_m=z0 - top.state.pos[2], axial_stress_Pa=O.forces.f(info["top"])[2] / A, sample_top_m=_top(info),
                         bond_coordination=bonds.coordination(),
                         liquid_m3=law.liquidTotals()["total"]))
    os.makedirs(outdir, exist_ok=True)
    glassbeads.write_csv(os.path.join(outdir, "compression.csv"), rows)
    return rows


def run(config, w, outdir, protocol="particles", dry_fraction=0.0, seed=None, loop="fused", log=print):
    """One simple compression test: build, settle and seal, wet to water content w, unmould, compress. Writes
    compression.csv and summary.json to outdir; returns the summary (the strength: the peak axial stress)."""
    from yade import O
    from . import bonds
    t0 = time.time()
    info = build(config, protocol, dry_fraction, seed, loop)
    settle_and_seal(info, log)
    iter0 = O.iter
    wet(info, w)
    z0 = bonds.coordination()
    unmould(info, log)
    rows = compress(info, outdir)
    peak = max(rows, key=lambda r: r["axial_stress_Pa"])
    summary = dict(config=config, w=w, protocol=protocol, dry_fraction=dry_fraction, strength_Pa=peak["axial_stress_Pa"],
                   shortening_at_peak_m=peak["shortening_m"], stress_end_Pa=rows[-1]["axial_stress_Pa"], bond_coordination_wet=z0,
                   bond_coordination_end=rows[-1]["bond_coordination"], height_sealed_m=info["height_sealed_m"], phi_sealed=info["phi_sealed"],
                   settlement_m=info["settlement_m"], relax_time_s=info["relax_time_s"], dt_s=O.dt, spheres=len(info["spheres"]),
                   particle_steps=len(info["spheres"]) * (O.iter - iter0), wall_s=time.time() - t0)
    with open(os.path.join(outdir, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    log("w %g, protocol %s, dry %g: strength %.1f Pa at %.3f mm, z %.2f, %.0f s" % (w, protocol, dry_fraction, summary["strength_Pa"],
                                                                               1e3 * summary["shortening_at_peak_m"], z0, summary["wall_s"]))
    return summary
