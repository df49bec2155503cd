"""Kernel fuzz, CI size (1e5 force evaluations, seed 1; about 5 s on one core plus 0.5 s CPU per hang): every model x rupture
rule over wide and absurd parameter ranges (tests/support/fuzz.py). Every call either raises a
ValueError naming the parameter, or gives finite, non-negative forces, zero beyond rupture and
monotone where the model is declared monotone; no hang, no crash, no other exception type.
The nightly size (1e6) is tests/fuzz_kernels.py."""
import fuzz


def test_names_parameter():
    assert fuzz.names_parameter("R1 = 1e-150 m is outside the allowed range (0, inf)")
    assert fuzz.names_parameter("model willett_full is not defined for this bridge: f4 >= 0 (V* = 0.3, theta = 0.1)")
    assert fuzz.names_parameter("gap is NaN; allowed: any real number [m]")
    assert fuzz.names_parameter("young_laplace_table: R_small/R_large = 0.1 is outside the table's range")
    assert not fuzz.names_parameter("bad bridge")
    assert not fuzz.names_parameter("theta1x = 3")


def test_fuzz_ci_size():
    report = fuzz.run(100000, seed=1)
    print(fuzz.format_report(report))
    assert report["counts"]["evaluations"] >= 99990
    assert report["counts"]["accepted"] > 0.3 * report["counts"]["bridges"], "the fuzz must mostly hit valid bridges"
    assert not fuzz.failures(report), fuzz.format_report(report)


def test_worker_hang_is_detected():
    # A worker (a fresh interpreter) that stops answering: stopped by SIGSTOP, it uses no CPU, so the
    # wall-time limit (20 timeouts) must report it within about 1 s at timeout = 0.05 s; killed, it is
    # reported as dead.
    import os
    import signal
    import time
    w = fuzz._Worker(1, 0, 10 ** 9)
    try:
        os.kill(w.pid, signal.SIGSTOP)
        while w.conn.poll(0.2):  # the answers sent before the stop
            w.conn.recv()
        t0 = time.time()
        assert not fuzz._answer_within(w.conn, w, 0.05)
        assert time.time() - t0 < 5
        assert w.is_alive()
    finally:
        w.close()
    assert not w.is_alive() and w.exitcode == -signal.SIGKILL
