# A wet scene run serially or with YADE's MPI module (yade.mpy) on several ranks, the driver of
# tests/python/test_mpi.py (the scenes come from tests/support/stress.py, hence PYTHONPATH):
#   PYTHONPATH=tests/support build/yade-capillary -n -x tests/support/mpi_run.py SCENE OUT.json [steps] [error]
#   PYTHONPATH=tests/support mpiexec --allow-run-as-root -n 3 build/yade-capillary -n -x tests/support/mpi_run.py SCENE OUT.json [steps] [error]
# SCENE: packing (300 spheres in a box of walls, random velocities, gravity) or shear_cell (the ci
# split-bottom cell filled densely, rotating). The dynamic spheres are split into slabs along x,
# one per worker rank (rank 0, the master, keeps the walls and the rotating wall spheres). The
# master writes the final positions and velocities (merged from the ranks) and the liquid totals
# summed over the ranks (yade_capillary.mpi.liquid_totals) to OUT.json. error: the spheres of the
# last slab get another capillary model, so the first bridge there is an input error on a worker.
import json
import sys

from yade import O
from yade.wrapper import PendularMat

import stress
from yade_capillary import mpi, scene, shearcell

what, out = sys.argv[1], sys.argv[2]
steps = int(sys.argv[3]) if len(sys.argv) > 3 else 1000
error = len(sys.argv) > 4 and sys.argv[4] == "error"
rank, ranks = mpi.rank_and_size()

if what == "packing":
    stress.box_packing(300, "willett_full", rmin=0.5e-3, ratio=2.0, box="walls", porosity=0.9, speed=0.3, friction=0.3)
    O.dt = scene.stable_dt(0.1)
elif what == "shear_cell":
    cfg = shearcell.CI
    ids = shearcell.build(cfg, "wet13.6nl", spacing=2.0, fill=0.6)
    O.engines = shearcell.run_engines({"rotating": ids["rotating"], "cfg": cfg})
    O.dt = cfg["dt_over_tc"] * cfg["tc"]
else:
    raise ValueError("SCENE = %r is not one of packing, shear_cell" % (what,))
O.engines = scene.newton_only(O.engines)  # serial and MPI runs alike: yade.mpy places its engines next to NewtonIntegrator
if error:
    m = O.materials[0]
    other = O.materials.append(PendularMat(tc=m.tc, en=m.en, et=m.et, density=m.density, frictionAngle=m.frictionAngle, Vb=m.Vb,
                                           gamma=m.gamma, model="rabinovich", extrapolate=True, wet=True))
    xmax = max(b.state.pos[0] for b in O.bodies if b.dynamic)
    for b in O.bodies:
        if b.dynamic and b.state.pos[0] > xmax - 3e-3:
            b.material = O.materials[other]
if ranks > 1:
    from yade import mpy

    mpi.assign_slabs(ranks)
    mpy.mpirun(steps, ranks, withMerge=True)
else:
    O.run(steps, True)
totals = mpi.liquid_totals(stress.capillary_law())  # after the run: the workers' scenes are the master's copies
if rank == 0:
    bodies = {b.id: [list(b.state.pos), list(b.state.vel)] for b in O.bodies if b is not None and b.dynamic and not b.isSubdomain}
    with open(out, "w") as f:
        json.dump({"ranks": ranks, "steps": steps, "bodies": bodies, "totals": totals,
                   "bridges": sum(1 for i in O.interactions if i.isReal and i.phys.active)}, f)
if ranks > 1:
    from yade import mpy

    mpy.MPI.Finalize()
sys.exit(0)
