# PendularLoop's records and the objects made from them (PendularLoop.keepRecords): a recorded
# interaction holds two placeholders shared by all instead of its own ScGeom and PendularPhys, which are
# made from the record when read and dropped after the next step unless something else holds them.
# Expected values: the same scene run with keepRecords=False, where every interaction keeps its own
# objects (the loop is bit-identical with and without records on one thread: test_loop).
# - An object that Python holds, or that Python assigned (its control block holds the Python object,
#   so its count is 1), stays the interaction's own and is kept current: it is never dropped for the
#   placeholders (dropping a Python-assigned one released the Python object without the GIL and left
#   Python holding a detached copy).
# - While O.run() runs in the background, reading I.geom and O.save raise RuntimeError naming
#   O.pause()/O.wait() (the loop makes and drops the objects between steps: a save then wrote the shared
#   placeholders into the file); after O.pause() both work, and the saved scene loads with the bodies,
#   the real interactions, the bridges and the forces of the original, each interaction with objects of
#   its own (continuing it is test_save_continue's).
# - Two PendularLoops in O.engines keep no records (the second would take the first one's placeholders
#   for objects of its own).
# - O.reset and O.load free the arrays of the replaced scene's loop (section 4).
# - A record keeps no shear increment in contact (the law does not read it): ScGeom.shearInc is made from
#   the bodies when the objects are, and kept from the last step in contact when the bridge separates;
#   read from Python it equals the run without records, for separated bridges too (section 5).
# - A recorded interaction whose body is no longer a PendularMat sphere of the scene's subdomain leaves the
#   records at the next step (section 6: the loop checks the records' bodies only after a body changed
#   kind or subdomain).
import os
import tempfile
import time

from yade import O
from yade.wrapper import InteractionLoop, PendularPhys

import stress
from testing import Checker
from yade_capillary import scene

ck = Checker("test_records")


def build(records=True, friction=0.3):
    stress.box_packing(150, "willett_full", rmin=0.5e-3, ratio=1.5, box="walls", porosity=0.7, speed=0.1, friction=friction)
    O.engines = scene.engines(gravity=(0, 0, -9.81))
    O.dt = scene.stable_dt(0.1)
    loop = next(e for e in O.engines if isinstance(e, InteractionLoop))
    loop.keepRecords = records
    return loop


def sphere_pairs():
    return sorted((i.id1, i.id2) for i in O.interactions if i.isReal and type(i.phys).__name__ == "PendularPhys"
                  and O.bodies[i.id1].shape.__class__.__name__ == "Sphere" and O.bodies[i.id2].shape.__class__.__name__ == "Sphere")


def real_forces():
    return {(i.id1, i.id2): (tuple(i.phys.normalForce), getattr(i.phys, "active", None)) for i in O.interactions if i.isReal}


def state():
    return [tuple(b.state.pos) + tuple(b.state.vel) for b in O.bodies if b.dynamic]


# 1. Held and assigned objects stay the interaction's own and current.
results = {}
for records in (False, True):
    loop = build(records)
    O.run(300, True)
    pairs = sphere_pairs()
    held, assigned = pairs[0], pairs[-1]
    phys = O.interactions[held].phys  # held by Python
    copy = PendularPhys()
    copy.updateAttrs(O.interactions[assigned].phys.dict())
    O.interactions[assigned].phys = copy  # assigned from Python, then dropped by the Python name below
    del copy
    O.run(300, True)
    I = O.interactions[assigned]
    results[records] = (state(), tuple(phys.normalForce), phys.Fcap, tuple(I.phys.normalForce) if I.isReal else None,
                        loop.nRecorded, loop.nWithObjects)
    del phys, I
ck.true(results[True][4] > 0 and results[True][5] >= 1,
        "with records: %d recorded interactions, %d with objects of their own after the run (a held object and an assigned one)"
        % (results[True][4], results[True][5]))
ck.true(results[True][:4] == results[False][:4],
        "a held PendularPhys and one assigned from Python: their values after 300 more steps and the positions and velocities "
        "bit-identical to the run without records")

# 2. While the simulation runs in the background.
build()
O.run(200, True)
pair = sphere_pairs()[0]
path = os.path.join(tempfile.mkdtemp(), "records.yade.gz")
I = O.interactions[pair]
O.run()
time.sleep(0.2)
ck.raises(RuntimeError, lambda: I.geom, "O.pause", "Interaction.geom while O.run() runs")
ck.raises(RuntimeError, lambda: O.save(path), "O.pause", "O.save while O.run() runs")
O.pause()
O.wait()
time.sleep(0.2)  # the last step ends (see test_gil)
del I
saved = (state(), real_forces())
O.save(path)
O.load(path)
loaded = (state(), real_forces())
ck.true(loaded == saved and len(saved[1]) > 0, "saved after O.pause(): O.load gives the %d bodies' positions and velocities and the %d real "
        "interactions with their forces and bridges" % (len(saved[0]), len(saved[1])))
kns = {i.phys.dict()["kn"] for i in O.interactions if i.isReal and type(i.phys).__name__ == "PendularPhys"}
ck.true(0 not in kns and len(kns) > 0, "loaded: no interaction with the placeholder physics (kn = 0); kn of the real ones %s" % sorted(kns)[:3])
O.run(100, True)
ck.true(next(e for e in O.engines if isinstance(e, InteractionLoop)).nRecorded > 0, "the loaded scene runs on, with records")

# 3. Two PendularLoops: no records.
build()
loop = next(e for e in O.engines if isinstance(e, InteractionLoop))
second = scene.interaction_loop("fused")
second.dead = True  # its functors are those of the first; present in the list, not running
O.engines = O.engines + [second]
O.run(100, True)
ck.true(loop.nRecorded == 0 and loop.nFused > 0, "two PendularLoops in O.engines: no records (%d fused, %d recorded)" % (loop.nFused, loop.nRecorded))

# 4. O.reset and O.load free what the loop holds for the scene they replace: YADE keeps the engines of a
#    replaced scene alive, and a loop kept its arrays and, through its records, the interactions (a script
#    that loaded ten Gladkyy-size states in one process grew to 18 GB). A released loop used again computes
#    as a new one: the same positions and velocities after 100 steps, bit for bit.
loop = build()
O.run(100, True)
held, recorded = loop.heldBytes(), loop.nRecorded
O.reset()
ck.true(recorded > 0 and held > 0 and loop.heldBytes() == 0,
        "O.reset: the replaced scene's PendularLoop holds %d B (%d B and %d records before)" % (loop.heldBytes(), held, recorded))
build()
O.run(100, True)
fresh = state()
build()
O.engines = [loop if isinstance(e, InteractionLoop) else e for e in O.engines]
O.run(100, True)
ck.true(state() == fresh and loop.nRecorded > 0, "the released loop in a new scene: the %d bodies as with a new loop after 100 steps" % len(fresh))
path = os.path.join(tempfile.mkdtemp(), "records.yade.gz")
O.save(path)
held = loop.heldBytes()
O.load(path)
ck.true(held > 0 and loop.heldBytes() == 0, "O.load: the replaced scene's PendularLoop holds %d B (%d B before)" % (loop.heldBytes(), held))

# 5. shearInc of every sphere-sphere interaction read between steps, with and without records, with and
#    without friction (with friction the records also compute ScGeom::rotate's axes, without they do not).
for friction in (0.3, 0.0):
    reads = {}
    for records in (False, True):
        build(records, friction)
        rows, separated = [], 0
        for _ in range(8):
            O.run(40, True)
            rows.append({(i.id1, i.id2): (tuple(i.geom.shearInc), i.geom.penetrationDepth) for i in O.interactions
                         if i.isReal and type(i.geom).__name__ == "ScGeom" and O.bodies[i.id1].shape.__class__.__name__ == "Sphere"
                         and O.bodies[i.id2].shape.__class__.__name__ == "Sphere"})
            separated += sum(1 for v in rows[-1].values() if v[1] < 0 and any(v[0]))
        reads[records] = (rows, separated, next(e for e in O.engines if isinstance(e, InteractionLoop)).nRecorded)
    ck.true(reads[True][2] > 0 and reads[True][1] > 20 and reads[True][0] == reads[False][0],
            "friction %g: shearInc of every sphere-sphere interaction at 8 reads (%d of separated bridges, kept from their last step in "
            "contact) bit-identical with records (%d recorded) and without" % (friction, reads[True][1], reads[True][2]))

# 6. A sphere moved to another subdomain from Python: its interactions leave the records at the next step
#    (they are recorded only between bodies of the scene's subdomain), as the first step of a new loop sees it.
build()
O.engines = scene.engines(gravity=(0, 0, -9.81), integrator="newton")  # PendularIntegrator refuses other subdomains
loop = next(e for e in O.engines if isinstance(e, InteractionLoop))
O.run(100, True)
moved = max(sphere_pairs(), key=lambda pair: pair[0])[0]
before = sphere_pairs()
O.bodies[moved].subdomain = 1
O.run(1, True)
expected = len([pair for pair in before if moved not in pair])
ck.true(len(before) > expected and loop.nRecorded == expected,
        "a sphere moved to subdomain 1: %d interactions computed from records in the next step, %d expected (%d before, %d of them "
        "with the moved sphere)" % (loop.nRecorded, expected, len(before), len(before) - expected))

ck.finish()
