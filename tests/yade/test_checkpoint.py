# The compact state of a shear cell (shearcell.save_state / load_state, what a run split into
# segments is continued from; Gladkyy-size runs commit it) and the segmented run (run_segment).
#
# The ci cell (dry, settled, seed 1) given 13.6 nl and rotated for N steps, so that it has bridges in
# contact and separated ones. State A: save_state, then one more step. State B: load_state of that
# file in a new scene, then one step. Expected: the same scene, so
# * equal: the bodies, the real interactions, which pairs have a bridge, nBridges;
# * liquidVolume within 1e-12 relative (a sum of the same Vb in another order);
# * positions and velocities saved exactly (float64): after the step, the forces on every body
#   within 1e-12 of the largest force of A, the positions within 1e-12 of R. The forces of A and B
#   are sums of the same terms in another order (YADE's container order, as after O.load; see
#   test_save_continue); 1e-12 leaves room for that round-off only.
# Then run_segment on a copy of the state with a run of 3 snapshot intervals: a first segment stopped
# by its wall-time budget, a second one that completes it; the torque records must follow each other
# in time without a gap or a repeat, and every snapshot, its reduced CG fields and run.json must exist. Bad input: formBridge
# on a pair without interaction, twice on one bridge, and with a negative or NaN pastRupture raise ValueError
# naming the pair. A bridge saved
# past its rupture distance is restored only within the last step's stretch (see below).
# Settling with a checkpoint (prepare(..., checkpoint=...), how the Gladkyy-size cell settles across
# segments): a short settling (0.03 s, 1111 steps, the bottom layer reaches the floor) saved after
# every 500-step chunk, then continued from its last checkpoint (step 1000): the positions and
# velocities at the end within 1e-12 R and 1e-12 of the largest speed of the uninterrupted settling
# (round-off, as above); a checkpoint of another case raises ValueError naming the file.
import json
import os
import tempfile

import numpy as np
from yade import O

from yade_capillary import shearcell
from testing import Checker

N = 1500
ck = Checker("test_checkpoint")
work = tempfile.mkdtemp(prefix="checkpoint_")
prepared = os.path.join(work, "prepared.yade.gz")
shearcell.prepare("ci", "dry", prepared, seed=1)
O.load(prepared)
info = json.loads(O.tags["shearcell"])
shearcell._set_case(info, "wet13.6nl")
O.engines = shearcell.run_engines(info)
O.run(N, True)
law = shearcell._law()


def state():
    """Bridges and totals of the current scene."""
    real = {(I.id1, I.id2): I.phys.active for I in O.interactions if I.isReal}
    return real, int(law.nBridges), float(law.liquidVolume)


def after_step():
    O.step()
    ids = range(len(O.bodies))
    return np.array([O.forces.f(i) for i in ids]), np.array([O.bodies[i].state.pos for i in ids])


path = os.path.join(work, "state.npz")
shearcell.save_state(path, info)
realA, nA, volA = state()
separated = sum(1 for I in O.interactions if I.isReal and I.phys.active and I.geom.penetrationDepth < 0)
ck.true(nA > 500 and separated > 20, "the cell has bridges (%d), separated ones among them (%d)" % (nA, separated))
FA, XA = after_step()
size_mb = os.path.getsize(path) / 1e6
print("state: %d bodies, %d real interactions, %.2f MB" % (len(O.bodies), len(realA), size_mb))

info_b = shearcell.load_state(path)
law = shearcell._law()
# rupture distance and volume of every saved bridge, as rebuilt (used below)
sCrit = {(I.id1, I.id2): (I.phys.sCrit, I.phys.Vb) for I in O.interactions if I.isReal and I.phys.active}
realB, nB, volB = state()
ck.true(realA == realB, "the same real interactions and bridges after load_state (%d / %d)" % (len(realA), len(realB)))
ck.true(nA == nB, "nBridges %d after load_state, %d saved" % (nB, nA))
ck.close(volB, volA, 1e-12, "liquidVolume after load_state", "the saved scene's")
ck.true(info_b["case"] == "wet13.6nl" and info_b["flowing"] == info["flowing"], "info restored")
FB, XB = after_step()
scale_f = np.abs(FA).max()
ck.close(float(np.abs(FB - FA).max()), 0.0, 0, "largest force difference after one step [N]", "the saved scene's step",
         atol=1e-12 * scale_f)
ck.close(float(np.abs(XB - XA).max()), 0.0, 0, "largest position difference after one step [m]", "the saved scene's step",
         atol=1e-12 * info["cfg"]["R"])

ids = (info["flowing"][0], info["flowing"][1])
if O.interactions.has(*ids):
    ids = (info["flowing"][0], info["static"][0])
ck.raises(ValueError, lambda: law.formBridge(*ids), ["formBridge(id1=%d, id2=%d)" % ids, "no real interaction"], "formBridge without interaction")
a, b = next(k for k, v in realB.items() if v)
ck.raises(ValueError, lambda: law.formBridge(a, b), ["formBridge(id1=%d, id2=%d)" % (a, b), "already has a bridge"], "formBridge twice")
for bad in (-1e-06, float("nan")):
    ck.raises(ValueError, lambda: law.formBridge(a, b, pastRupture=bad), ["formBridge(id1=%d, id2=%d)" % (a, b), "pastRupture = %g m" % bad,
              "a finite value >= 0 m"], "formBridge with pastRupture = %g" % bad)

# A bridge saved past its rupture distance (the step before a save can stretch a bridge past it; the law
# breaks it at the next step). From the saved arrays: body b of a separated bridge a-b moved along the
# line of centres to 1e-3 sCrit past that bridge's rupture distance sCrit (a body whose other bridges
# stay within theirs). With the saved velocities made equal, the step's stretch |v2 - v1| dt is 0 and
# load_state must refuse it, naming the file and the pair; with v_b - v_a = 2e-3 sCrit / dt along the
# normal (a stretch twice the excess) it restores all nA bridges, and the next step breaks this one
# (liquidReleased grows by at least its Vb).
d = dict(np.load(path))


def gap(x, i, j):
    return float(np.linalg.norm(x[j] - x[i]) - d["radius"][i] - d["radius"][j])


def past_rupture(a, b):
    """Positions with b moved 1e-3 sCrit past the rupture distance of a-b, or None if another of b's bridges
    would then be past its own."""
    x = d["pos"].copy()
    n = (x[b] - x[a]) / np.linalg.norm(x[b] - x[a])
    s = sCrit[a, b][0]
    x[b] += n * (1.001 * s - gap(x, a, b))
    others = [(i, j) for (i, j) in sCrit if b in (i, j) and (i, j) != (a, b)]
    return (x, n, s) if all(gap(x, i, j) < sCrit[i, j][0] for (i, j) in others) else None


flowing = set(info["flowing"])
a, b, x, n, s = next((a, b) + found for (a, b), (sc, _) in sCrit.items()
                     if a in flowing and b in flowing and 0 < gap(d["pos"], a, b) < sc and (found := past_rupture(a, b)))
v = d["vel"].copy()
v[b] = v[a]
past = os.path.join(work, "past_rupture.npz")
np.savez_compressed(past, **dict(d, pos=x, vel=v))
ck.raises(ValueError, lambda: shearcell.load_state(past), ["load_state", past, "bridge %d-%d" % (a, b), "beyond the rupture distance"],
          "a saved bridge past rupture by more than the step's stretch")
v[b] = v[a] + n * 2e-3 * s / json.loads(str(d["meta"]))["dt_s"]
np.savez_compressed(past, **dict(d, pos=x, vel=v))
shearcell.load_state(past)
law = shearcell._law()
ck.true(int(law.nBridges) == nA and O.interactions[a, b].phys.active, "a bridge within the step's stretch past rupture restored (%d of %d)" % (int(law.nBridges), nA))
O.step()
ck.true(not (O.interactions.has(a, b) and O.interactions[a, b].isReal and O.interactions[a, b].phys.active), "the restored bridge breaks at the next step")
ck.true(float(law.liquidReleased) >= sCrit[a, b][1], "liquidReleased %.6g >= Vb %.6g of the broken bridge" % (float(law.liquidReleased), sCrit[a, b][1]))

# Segments: a run of 3 snapshot intervals of 0.004 s (cfg changed in the state's info).
meta = json.loads(str(d["meta"]))
meta["cfg"].update(run_s=0.012, snapshots=3, snapshot_dt_s=0.004)
short = os.path.join(work, "short.npz")
np.savez_compressed(short, **dict(d, meta=json.dumps(meta)))
outdir = os.path.join(work, "segments")
keep = os.path.join(work, "keep")
first = shearcell.run_segment(short, outdir, budget_s=0.0, keep=keep)
ck.true(not first["complete"] and 0 < first["done_steps"] < first["steps"], "the first segment stops at its budget (%d of %d steps)" % (first["done_steps"], first["steps"]))
second = shearcell.run_segment(short, outdir, budget_s=1e9, keep=keep)
ck.true(second["complete"], "the second segment completes the run")
T = np.loadtxt(os.path.join(keep, "torque.csv"), delimiter=",", skiprows=1, ndmin=2)
dt = np.diff(T[:, 0])
ck.true(len(T) > 10 and dt.min() > 0 and dt.max() < 1.5 * np.median(dt),
        "torque records follow each other across the segments (%d rows, steps %.3g-%.3g s)" % (len(T), dt.min(), dt.max()))
ck.close(float(T[0, 0]), meta["time_s"], 0, "first torque record [s]", "the time of the saved state", atol=2 * np.median(dt))
ck.true(all(os.path.exists(os.path.join(outdir, "snap_%03d.npz" % k)) and os.path.exists(os.path.join(keep, "cg_%03d.npz" % k)) for k in (1, 2, 3))
        and all(os.path.exists(os.path.join(d, "run.json")) for d in (outdir, keep)) and os.path.exists(os.path.join(outdir, "torque.csv")),
        "snapshots 1-3 and their reductions, run.json and torque.csv written")

shearcell.CONFIGS["ci_settle"] = dict(shearcell.CI, settle_s=0.03)
settling = os.path.join(work, "settling.npz")
shearcell.prepare("ci_settle", "dry", None, seed=1, checkpoint=settling, save_every_s=0.0, log=lambda *a: None)
XA = np.array([b.state.pos for b in O.bodies])
VA = np.array([b.state.vel for b in O.bodies])
contacts = sum(1 for I in O.interactions if I.isReal)
resumed = []
shearcell.prepare("ci_settle", "dry", None, seed=1, checkpoint=settling, log=resumed.append)
ck.true(contacts > 0 and resumed and "at step 1000 of 1111" in resumed[0], "settling continued from its checkpoint (%s; %d contacts)" % (resumed, contacts))
XB = np.array([b.state.pos for b in O.bodies])
VB = np.array([b.state.vel for b in O.bodies])
ck.close(float(np.abs(XB - XA).max()), 0.0, 0, "largest position difference, continued settling [m]", "the uninterrupted settling",
         atol=1e-12 * info["cfg"]["R"])
ck.close(float(np.abs(VB - VA).max()), 0.0, 0, "largest velocity difference, continued settling [m/s]", "the uninterrupted settling",
         atol=1e-12 * np.abs(VA).max())
ck.raises(ValueError, lambda: shearcell.prepare("ci_settle", "wet13.6nl", None, seed=1, checkpoint=settling), ["checkpoint", settling, "ci_settle/dry"],
          "a checkpoint of another case")
ck.finish()
