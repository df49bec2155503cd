# Liquid migration in a rotating drum (PendularMat.liquid = 'film'; Elskamp & Kruggel-Emden 2018 section
# 2.2.1 and 2.2.4, Shi & McCarthy): a wet population (film 1 % of its volume, the left half) and a dry
# one (the right half) settle in a drum of facets, which then turns at 0.5 rev/s and mixes them.
# Bridges form at contact from both films, break by Willett's rule and give their liquid back by the
# exact transfer ratio; the drum's facets are wettable but start dry and take their share too.
# Run:  build/yade-capillary -j1 -n -x scripts/liquid_migration.py [outdir] [--quick]
#       (default results/liquid_migration; --quick: 0.1 s of rotation, for ./run.sh validate)
# Writes migration.csv (MIGRATION_COLUMNS of yade_capillary.liquid, units in the names),
# liquid_migration.png and VTK files (vtk/drum_<t>_particles.vtk, _bridges.vtk) for ParaView; exits
# with status 1 if films + bridges + removed drift by more than 1e-12 or no liquid reaches the dry
# population.
import math
import os
import sys
import time

from yade import O, geom, pack
from yade import Quaternion, Vector3
from yade.utils import sphere
from yade.wrapper import PendularMat, RotationEngine

from yade_capillary import liquid
from yade_capillary.scene import engines, stable_dt

args = [a for a in sys.argv[1:] if not a.startswith("--")]
quick = "--quick" in sys.argv
outdir = args[0] if args else os.path.join("results", "liquid_migration")
os.makedirs(os.path.join(outdir, "vtk"), exist_ok=True)

RD, LD, R, FUZZ = 15e-3, 10e-3, 0.7e-3, 0.2  # drum radius and length, mean radius, radius spread [m, m, m, -]
OMEGA = math.pi                              # drum speed [rad/s], 0.5 rev/s
SETTLE, ROTATE = (0.15, 0.1) if quick else (0.3, 4.0)  # [s]
mat = PendularMat(tc=4e-4, en=0.5, et=0.5, density=2500, frictionAngle=0.4, wet=True, Vb=1e-6, gamma=0.072,
                  theta=math.radians(15), model="willett_full", rupture="willett", liquid="film", transfer="exact")
O.materials.append(mat)
# The drum: axis along y, gravity along -z; its facets are wettable (film over each facet's area).
drum = O.bodies.append(geom.facetCylinder((0, 0, 0), RD, LD, orientation=Quaternion(Vector3(1, 0, 0), math.pi / 2),
                                          segmentsNumber=24, wallMask=7, material=mat))
for i in drum:
    v = O.bodies[i].shape.vertices
    O.bodies[i].state.filmArea = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm()
cloud = pack.SpherePack()
cloud.makeCloud((-0.7 * RD, -0.45 * LD, -0.7 * RD), (0.7 * RD, 0.45 * LD, 0.25 * RD), rMean=R, rRelFuzz=FUZZ, seed=3)
groups = {"wet": [], "dry": []}
for c, r in cloud:
    if c[0] ** 2 + c[2] ** 2 > (RD - r - 1e-4) ** 2:
        continue
    b = O.bodies.append(sphere(c, r, material=mat))
    if c[0] < 0:
        O.bodies[b].state.film = 0.01 * 4 / 3 * math.pi * r ** 3
        groups["wet"].append(b)
    else:
        groups["dry"].append(b)
rotation = RotationEngine(ids=drum, rotationAxis=(0, 1, 0), rotateAroundZero=True, zeroPoint=(0, 0, 0), angularVelocity=0, label="drum")
O.engines = engines(gravity=(0, 0, -9.81), extra=[rotation])
O.dt = stable_dt()
law = O.engines[2].lawDispatcher.functors[0]
total0 = law.liquidTotals()["total"]
print("Liquid migration in a drum: %d wet + %d dry spheres, R = %g mm +- %d %%, drum %g x %g mm at %.2f rev/s, dt = %.3g s, "
      "settle %g s, rotate %g s -> %s" % (len(groups["wet"]), len(groups["dry"]), R * 1e3, FUZZ * 100, 2 * RD * 1e3, LD * 1e3,
                                          OMEGA / (2 * math.pi), O.dt, SETTLE, ROTATE, outdir))

rows, every, vtk_every = [], 0.05 if not quick else 0.025, 0.5
start, next_vtk = time.time(), 0.0
while O.time < SETTLE + ROTATE - 1e-12:
    if O.time >= SETTLE:
        rotation.angularVelocity = OMEGA
    O.run(max(1, int(round(every / O.dt))), True)
    rows.append(liquid.populations(law, groups, O.time, total0))
    r = rows[-1]
    if O.time >= next_vtk - 1e-12:
        liquid.write_scene_vtk(os.path.join(outdir, "vtk", "drum_%05.2fs" % O.time), law, groups)
        next_vtk += vtk_every
    print("t = %5.2f s: %4d bridges, liquid in films %.4g nl, in bridges %.4g nl; per particle wet %.4g nl, dry %.4g nl "
          "(%.0f %% of the dry ones wet); drift %.1e; %.0f s" % (O.time, r["n_bridges"], r["films_m3"] * 1e12, r["bridges_m3"] * 1e12,
                                                                 r["wet_mean_carried_m3"] * 1e12, r["dry_mean_carried_m3"] * 1e12,
                                                                 100 * r["dry_with_liquid_frac"], r["drift_rel"], time.time() - start))
    sys.stdout.flush()
liquid.write_csv(rows, os.path.join(outdir, "migration.csv"))
liquid.plot_migration(rows, os.path.join(outdir, "liquid_migration.png"),
                      "Liquid migration in a drum (%d wet + %d dry spheres, film 1 %% of the wet spheres' volume, %.2f rev/s from t = %g s)"
                      % (len(groups["wet"]), len(groups["dry"]), OMEGA / (2 * math.pi), SETTLE))
worst = max(abs(r["drift_rel"]) for r in rows)
first, last = rows[0], rows[-1]
print("conservation: largest relative drift of films + bridges + removed %.2e (bound 1e-12)" % worst)
print("dry population: mean liquid per particle %.4g nl after settling, %.4g nl at the end; wet population %.4g -> %.4g nl" % (
    first["dry_mean_carried_m3"] * 1e12, last["dry_mean_carried_m3"] * 1e12, first["wet_mean_carried_m3"] * 1e12,
    last["wet_mean_carried_m3"] * 1e12))
print("wrote %s/{migration.csv, liquid_migration.png, vtk/}" % outdir)
ok = worst <= 1e-12 and last["dry_mean_carried_m3"] > 0 and last["wet_mean_carried_m3"] < rows[0]["wet_mean_carried_m3"] * (1 + 1e-12)
if not ok:
    print("FAILED: conservation or migration")
sys.exit(0 if ok else 1)
