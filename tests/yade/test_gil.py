# The simulation thread must not need Python's GIL at every step. YADE's O.reset() (and O.load) hold the
# GIL while they wait for the step in progress to end; PendularIntegrator read its NewtonIntegrator's
# parameters and wrote the collider's flag through Python at every step, a step could wait for the GIL
# forever (after O.pause(); O.wait(); O.reset()). So the parameters are read before O.run and after a
# NewtonIntegrator attribute is set (PendularIntegrator.refresh, yade_capillary.patches), and the flag is written into
# the object directly.
# - While the main thread holds the GIL in one long C call (a sum over a range: the GIL is handed over
#   rarely), a run in the background goes on at least 0.3 times as fast as while the main thread sleeps
#   (a step that needs the GIL runs at a few percent of that speed; the main thread's loop takes a core of
#   its own, so on a busy machine the run may slow down a little).
# - A gravity set between two runs is used from the next step on: positions and velocities bit-identical
#   to NewtonIntegrator's with the same change.
# (O.pause() and O.wait() may return before the last step has ended, and O.reset() then races with it in
# YADE itself: the test lets that step end before it builds the next scene.)
import time

from yade import O
from yade.wrapper import NewtonIntegrator

import stress
from testing import Checker
from yade_capillary import scene

ck = Checker("test_gil")


def build(integrator="pendular"):
    stress.box_packing(60, "willett_full", rmin=0.5e-3, ratio=2.0, box="walls", porosity=0.85, speed=1.0)
    O.engines = scene.engines(gravity=(0, 0, -9.81), integrator=integrator)
    O.dt = scene.stable_dt(0.1)


build()
O.run()
time.sleep(0.2)  # the run under way
i0, t0 = O.iter, time.time()
time.sleep(0.3)  # the GIL released
i1, t1 = O.iter, time.time()
sum(range(30000000))  # the GIL held
i2, t2 = O.iter, time.time()
O.pause()
O.wait()
time.sleep(0.2)  # the last step ends
free, held = (i1 - i0) / (t1 - t0), (i2 - i1) / (t2 - t1)
ck.true(held >= 0.3 * free, "the run went on while the main thread held the GIL for %.2f s: %.0f steps/s against %.0f while it slept "
        "(at least 0.3 times)" % (t2 - t1, held, free))


def run_with_gravity_change(integrator):
    build(integrator)
    O.run(200, True)
    next(e for e in O.engines if isinstance(e, NewtonIntegrator)).gravity = (0, 3.0, -9.81)
    O.run(200, True)
    return [tuple(b.state.pos) + tuple(b.state.vel) for b in O.bodies]


ref = run_with_gravity_change("newton")
got = run_with_gravity_change("pendular")
ck.true(got == ref, "gravity changed between two runs: positions and velocities bit-identical to NewtonIntegrator's")
ck.finish()
