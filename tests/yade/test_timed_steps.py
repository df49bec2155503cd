# benchmark.timed_steps (bench/benchmark.py), which every timed run of ./run.sh bench goes through: the wall time of n steps is
# stamped in the n-th step by a PyRunner (benchmark.END_STAMP, the last engine), not read when a poll of the main
# thread notices the end. Checked on a small wet packing with PendularLoop (whose records must survive the stamp):
# - the stamp runs in exactly the last of the n steps, once: its iterLast is the iteration of that step
#   (the first iteration of the run plus n - 1) and nDone is 1, for several n and runs in a row;
# - the time it returns lies between the run's start and the return of O.wait (both read around the call
#   here): it cannot come from an earlier run or from after the wait;
# - the runner is appended once and stays last; PendularLoop computes every step of every timed run from its
#   records (nRecorded > 0 after each run, also after a one-step run: a step after the records were dropped
#   computes none from them);
# - n < 1, a run whose last step would be iteration 0, and an engine list without the stamp raise, naming why.
import os
import sys
import time

from testing import Checker
from yade import O
from yade.wrapper import PendularMat

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(sys.argv[0])))), "bench"))
import benchmark  # noqa: E402  (bench/benchmark.py)

ck = Checker("test_timed_steps")
benchmark.build(PendularMat(tc=benchmark.TC, en=benchmark.EN, et=benchmark.EN, density=benchmark.RHO, frictionAngle=0, wet=True, Vb=benchmark.VB,
                            gamma=benchmark.GAMMA, theta=0, model="willett_full"), 5, 1, 0.005)
O.engines = benchmark.engines(loop="fused")
ck.raises(RuntimeError, lambda: benchmark.timed_steps(5), ["end_stamp()"], "timed_steps without the stamp")
stamp = benchmark.end_stamp()
ck.true(O.engines[-1].label == benchmark.END_STAMP, "end_stamp() appends the stamp last")
ck.raises(ValueError, lambda: benchmark.timed_steps(1), ["n = 1 from iteration 0"], "timed_steps(1) at iteration 0")
O.run(20, True)
loop = O.engines[2]
ck.true(loop.nRecorded > 0, "PendularLoop keeps records before the timed runs (nRecorded %d)" % loop.nRecorded)
length = len(O.engines)
for n in (1, 7, 50, 50, 1):
    first = O.iter
    before = time.perf_counter()
    t = benchmark.timed_steps(n)
    after = time.perf_counter()
    ck.true(O.iter == first + n, "timed_steps(%d) ran %d steps" % (n, O.iter - first))
    ck.true(stamp.iterLast == first + n - 1 and stamp.nDone == 1,
            "timed_steps(%d): the stamp ran once (nDone %d) in the last step, iteration %d (iterLast %d)" % (n, stamp.nDone, first + n - 1, stamp.iterLast))
    ck.true(0 < t <= after - before, "timed_steps(%d) returned %g s, within the %g s around the call" % (n, t, after - before))
    ck.true(len(O.engines) == length and O.engines[-1].label == benchmark.END_STAMP,
            "the stamp is appended once and stays last (%d engines, %d before)" % (len(O.engines), length))
    ck.true(loop.nRecorded > 0, "timed_steps(%d): the last step computed from PendularLoop's records (nRecorded %d)" % (n, loop.nRecorded))
ck.raises(ValueError, lambda: benchmark.timed_steps(0), ["n = 0"], "timed_steps(0)")
ck.finish()
