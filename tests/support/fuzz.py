"""Randomised stress test ("fuzz") of the capillary kernels (plain python3 or inside yade).

Random bridges over every model (``kernels.MODEL_NAMES``) and rupture rule (``kernels.RUPTURE_NAMES``)
with wide parameter ranges plus absurd values, each evaluated at about 30 gaps (negative, 0, inside,
at and beyond rupture, huge, infinite) and at a NaN gap. Every outcome of a call must be one of:

* a ``ValueError`` whose message names the offending parameter (``NAMES``, in the form
  ``"<name> = <value> ..."`` or ``"<name> is ..."``), for ``bridge()`` and ``force()`` alike;
* an accepted bridge: invariants (rupture, force0, energy, linear parameters) finite and >= 0, forces
  finite and >= 0, zero beyond the rupture distance, non-increasing in the gap over [0, rupture] for
  the models that ``kernels.models()`` declares monotone.

Everything else is counted as a failure: ``nan``, ``inf``, ``negative``, ``nonzero_beyond_rupture``,
``non_monotone``, ``bad_invariant``, ``unnamed_value_error`` (a ValueError not naming a parameter),
``other_exception`` (any other exception type), ``inconsistent`` (``bridge()`` and ``force()``
disagree on accepting the same bridge), ``hang`` (no answer within ``timeout`` seconds) and ``crash``
(the process died). Calls run in a worker process (a hang in C++ cannot be interrupted in-process):
on a hang or crash the worker is replaced and the run goes on with the next bridge. A worker is a
fresh interpreter (``python3 -m fuzz``), neither a fork of the caller (a fork copies the locks that the
caller's threads may hold at that moment, pytest's or BLAS's, and a worker that inherits a held lock
waits forever, reported as a false hang) nor a multiprocessing spawn
(which runs the caller's main script again: a script calling ``run`` at top level, or yade itself).

Deterministic: bridge i is drawn from ``numpy.random.default_rng([seed, i])``, independent of the
chunking. Half of the bridges pass ``extrapolate=True``.

    import fuzz                            # tests/support, with build/python on PYTHONPATH
    report = fuzz.run(100000, seed=1)      # number of force evaluations
    print(fuzz.format_report(report)); assert not fuzz.failures(report)
"""
import math
import os
import re
import subprocess
import sys
import time
from multiprocessing.connection import Connection

import numpy as np

from yade_capillary import kernels

# Parameter names a ValueError may name (how the kernels spell them in messages).
NAMES = ("R1", "R2", "volume", "gamma", "theta", "theta1", "theta2", "rupture", "model", "linear_fmax", "linear_kc",
         "calibrate_from", "gap", "V*", "V", "R2/R1", "R1/R2", "R_small/R_large", "ratio", "extrapolate", "Rh")
_NAMED = re.compile(r"(?<![A-Za-z0-9_])(%s)\s*(=|is\b)" % "|".join(re.escape(n) for n in sorted(NAMES, key=len, reverse=True)))

FAILURES = ("nan", "inf", "negative", "nonzero_beyond_rupture", "non_monotone", "bad_invariant", "unnamed_value_error",
            "other_exception", "inconsistent", "hang", "crash")
GAPS_PER_BRIDGE = 31  # 30 finite/infinite gaps + 1 NaN gap
FRACTIONS = (1e-6, 1e-3, 0.01, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.99, 0.999, 1 - 1e-9)
MONOTONE_RTOL = 1e-12

ABSURD_RADII = (1e-150, 1e150, 0.0, -1e-3, math.nan, math.inf)
ABSURD_VSTAR = (5e-324, 1e300)  # V* = V/R1^3
ABSURD_VOLUME = (5e-324, 1e300, 0.0, -1e-12, math.nan, math.inf)  # absolute volumes [m^3]
ABSURD_GAMMA = (1e-300, 1e300, 0.0, -0.07, math.nan, math.inf)
ABSURD_THETA = (-0.1, math.pi / 2, 2.0, 1e300, math.nan, math.inf)
ABSURD_LINEAR = (0.0, -1.0, 1e-300, 1e300, math.nan, math.inf)


def names_parameter(message):
    """True if the message names a parameter: '<name> = ...' or '<name> is ...' with a name of NAMES."""
    return _NAMED.search(message) is not None


def _log_uniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def bridge_spec(seed, i):
    """Keyword arguments of kernels.bridge/force for bridge i of the run `seed` (deterministic)."""
    rng = np.random.default_rng([seed, i])
    models, rules = kernels.MODEL_NAMES, kernels.RUPTURE_NAMES
    absurd = lambda values: values[int(rng.integers(len(values)))]
    p = 0.04  # probability of an absurd value, per parameter
    model = models[i % len(models)]  # every model equally often
    if rng.random() < 0.005:
        model = "no_such_model"
    R1 = absurd(ABSURD_RADII) if rng.random() < p else _log_uniform(rng, 1e-7, 1e-1)
    u = rng.random()
    if u < p:
        R2 = absurd(ABSURD_RADII)
    elif u < 0.15:
        R2 = math.inf  # sphere-wall
    elif u < 0.6:
        R2 = abs(R1) * _log_uniform(rng, 0.1, 10) if math.isfinite(R1) and R1 != 0 else 1e-3  # similar sizes
    else:
        R2 = _log_uniform(rng, 1e-7, 1e-1)
    Rref = R1 if 1e-8 < R1 < 1 else 1e-3  # V* = V/R1^3 for ordinary R1
    u = rng.random()
    if u < p / 2:
        volume = absurd(ABSURD_VSTAR) * Rref ** 3
    elif u < p:
        volume = absurd(ABSURD_VOLUME)
    else:
        volume = _log_uniform(rng, 1e-8, 10) * Rref ** 3
    gamma = absurd(ABSURD_GAMMA) if rng.random() < p else _log_uniform(rng, 1e-4, 1)
    theta = absurd(ABSURD_THETA) if rng.random() < p else math.radians(rng.uniform(0, 89))
    u = rng.random()
    theta2 = None if u < 0.5 else (absurd(ABSURD_THETA) if u < 0.5 + p else math.radians(rng.uniform(0, 89)))
    rupture = rules[int(rng.integers(len(rules)))] if rng.random() > 0.005 else "no_such_rule"
    kw = dict(model=model, R1=R1, R2=R2, volume=volume, gamma=gamma, theta=theta, theta2=theta2, rupture=rupture)
    if model == "linear_irreversible":
        if rng.random() < 0.5:  # given parameters
            kw["linear_fmax"] = absurd(ABSURD_LINEAR) if rng.random() < 2 * p else _log_uniform(rng, 1e-9, 1)
            kw["linear_kc"] = absurd(ABSURD_LINEAR) if rng.random() < 2 * p else _log_uniform(rng, 1e-3, 1e6)
        else:  # calibrated from another model (now and then from itself: an error)
            kw["calibrate_from"] = models[int(rng.integers(len(models)))]
    if rng.random() < 0.5:
        kw["extrapolate"] = True
    return kw


def _gaps(rupture, scale):
    """30 gaps [m]: negative, zero, inside, at and just beyond rupture, far, infinite."""
    rc = rupture if math.isfinite(rupture) and rupture > 0 else scale
    g = [-10 * rc, -rc, -1e-3 * rc, -0.0, 0.0, 5e-324]
    g += [f * rc for f in FRACTIONS]
    g += [rc, float(np.nextafter(rc, math.inf)), rc * (1 + 1e-9), 1.01 * rc, 2 * rc, 1e3 * rc, 1e300, math.inf]
    return np.array(g[:30])


class _Counts:
    def __init__(self):
        self.c = dict.fromkeys(("bridges", "evaluations", "accepted", "rejected") + FAILURES, 0)
        self.examples = {}

    def fail(self, what, spec, detail, n=1):
        self.c[what] += n
        ex = self.examples.setdefault(what, [])
        if len(ex) < 3:
            ex.append("%s: %s" % (detail, spec))


def _classify_error(counts, e, spec, where):
    """A ValueError naming a parameter is fine; anything else is a failure. Returns True if fine."""
    if type(e) is ValueError:
        if names_parameter(str(e)):
            return True
        counts.fail("unnamed_value_error", spec, "%s: %r" % (where, str(e)))
        return False
    counts.fail("other_exception", spec, "%s: %s(%r)" % (where, type(e).__name__, str(e)))
    return False


def check_bridge(spec, monotone, counts):
    """Evaluate one bridge (bridge(), force() at 30 gaps, force() at a NaN gap) and count outcomes."""
    kw = {k: v for k, v in spec.items() if k != "model"}
    model = spec["model"]
    counts.c["bridges"] += 1
    counts.c["evaluations"] += GAPS_PER_BRIDGE
    try:
        info = kernels.bridge(model, **kw)
    except Exception as e:  # noqa: BLE001 - every exception type is classified
        info, bridge_error = None, e
    scale = spec["R1"] if isinstance(spec["R1"], float) and math.isfinite(spec["R1"]) and spec["R1"] > 0 else 1e-3
    rupture = info["rupture"] if info is not None else math.nan
    gaps = _gaps(rupture, scale)
    try:
        F = np.asarray(kernels.force(model, gaps, **kw), dtype=float)
        force_error = None
    except Exception as e:  # noqa: BLE001
        F, force_error = None, e
    if info is None:
        counts.c["rejected"] += 1
        _classify_error(counts, bridge_error, spec, "bridge")
        if force_error is None:
            counts.fail("inconsistent", spec, "bridge() raised %r but force() returned" % str(bridge_error))
        else:
            _classify_error(counts, force_error, spec, "force")
        return
    counts.c["accepted"] += 1
    inv = {k: info[k] for k in ("rupture", "force0", "energy", "linear_fmax", "linear_kc") if k in info}
    if not all(math.isfinite(v) and v >= 0 for v in inv.values()) or not rupture > 0:
        counts.fail("bad_invariant", spec, "invariants %s" % inv)
    if force_error is not None:
        if _classify_error(counts, force_error, spec, "force"):
            counts.fail("inconsistent", spec, "bridge() accepted, force() raised %r" % str(force_error))
        return
    nan, inf, neg = int(np.isnan(F).sum()), int(np.isinf(F).sum()), int((F < 0).sum())
    if nan:
        counts.fail("nan", spec, "%d NaN forces at gaps %s" % (nan, gaps[np.isnan(F)][:4]), nan)
    if inf:
        counts.fail("inf", spec, "%d infinite forces" % inf, inf)
    if neg:
        counts.fail("negative", spec, "%d negative forces, min %g" % (neg, F.min()), neg)
    if math.isfinite(rupture):
        beyond = (gaps > rupture) & (F != 0)
        if beyond.any():
            counts.fail("nonzero_beyond_rupture", spec, "F = %s beyond rupture %g" % (F[beyond][:3], rupture), int(beyond.sum()))
    if monotone and not nan:
        inside = (gaps >= 0) & (gaps <= rupture)
        f = F[inside]  # gaps are increasing
        rises = f[1:] - f[:-1] > MONOTONE_RTOL * np.abs(f[:-1]) + 1e-300
        if rises.any():
            k = int(np.argmax(rises))
            counts.fail("non_monotone", spec, "F rises from %.17g to %.17g at gaps %s" % (f[k], f[k + 1], gaps[inside][k:k + 2]),
                        int(rises.sum()))
    try:  # a NaN gap: a ValueError naming gap, or a finite, non-negative force
        v = np.asarray(kernels.force(model, np.array([math.nan]), **kw), dtype=float)
        if not (np.isfinite(v).all() and (v >= 0).all()):
            counts.fail("nan" if np.isnan(v).any() else "negative", spec, "NaN gap gives %s" % v)
    except Exception as e:  # noqa: BLE001
        _classify_error(counts, e, spec, "force(NaN gap)")


class _Worker:
    """A worker process (``python3 -m fuzz FD SEED START STOP``) that evaluates bridges
    start..stop-1 and sends each one's counts through the pipe whose write end is its FD."""

    def __init__(self, seed, start, stop):
        read, write = os.pipe()
        here = os.path.dirname(os.path.abspath(__file__))  # this module's folder, for -m; yade_capillary comes from PYTHONPATH
        env = dict(os.environ, PYTHONPATH=os.pathsep.join([here] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
        python = sys.executable if os.path.basename(sys.executable).startswith("python") else "/usr/bin/python3"  # not yade's launcher
        self.proc = subprocess.Popen([python, "-m", __name__, str(write), str(seed), str(start), str(stop)], pass_fds=(write,), env=env,
                                     stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL)
        os.close(write)
        self.conn, self.pid = Connection(read, writable=False), self.proc.pid
        # The interpreter's start and imports are not a bridge's time: wait for the worker's first word.
        try:
            if self.conn.poll(300) and self.conn.recv() == "ready":
                return
        except EOFError:
            pass
        self.close()
        raise RuntimeError("fuzz: a worker process did not start (%s -m %s, exit code %s)" % (python, __name__, self.exitcode))

    def is_alive(self):
        return self.proc.poll() is None

    @property
    def exitcode(self):
        return self.proc.poll()

    def close(self):
        if self.is_alive():
            self.proc.kill()
        self.proc.wait()
        self.conn.close()


def _worker(conn, seed, start, stop):
    monotone = {m["name"]: bool(m["monotone"]) for m in kernels.models()}
    for i in range(start, stop):
        spec = bridge_spec(seed, i)
        counts = _Counts()
        check_bridge(spec, monotone.get(spec["model"], False), counts)
        conn.send((i, counts.c, counts.examples))
    conn.close()


def _cpu_seconds(pid):
    """CPU time (user + system) of a process [s], from /proc; None where /proc is not available."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / _CLOCK_TICKS
    except (OSError, IndexError, ValueError):
        return None


try:
    import os
    _CLOCK_TICKS = os.sysconf("SC_CLK_TCK")
except (AttributeError, ValueError, OSError):
    _CLOCK_TICKS = 100


def _answer_within(conn, proc, timeout):
    """Wait for the worker's next answer. A hang is `timeout` seconds of CPU time of the worker on one
    bridge (not wall time: the machine may be shared), or 20 timeouts of wall time without an answer."""
    t0, c0 = time.time(), _cpu_seconds(proc.pid)
    while True:
        if conn.poll(min(0.05, timeout)):
            return True
        if not proc.is_alive():
            return conn.poll(0)
        c = _cpu_seconds(proc.pid)
        if (c is not None and c0 is not None and c - c0 > timeout) or time.time() - t0 > 20 * timeout or \
                (c0 is None and time.time() - t0 > timeout):
            return False


def run(n_evaluations, seed=1, timeout=0.5, progress=None):
    """Fuzz about n_evaluations force evaluations (GAPS_PER_BRIDGE per bridge). timeout [s]: a bridge that
    takes more CPU time than this is a hang (a valid bridge takes under 1 ms, calibration included).
    Returns a dict: counts (every category), examples (up to 3 per category), hung (index and spec of
    every bridge that hung or crashed), by_model (model -> failure counts), seconds, seed."""
    t0 = time.time()
    n = max(1, int(round(n_evaluations / GAPS_PER_BRIDGE)))
    total = _Counts()
    hung = []  # (index, spec) of every hang and crash
    by_model = {}  # model -> failure counts
    i = 0
    while i < n:
        proc = _Worker(seed, i, n)
        parent = proc.conn
        while i < n:
            if not _answer_within(parent, proc, timeout):
                spec = bridge_spec(seed, i)
                total.c["bridges"] += 1
                total.c["evaluations"] += GAPS_PER_BRIDGE
                hung.append((i, spec))
                by_model.setdefault(spec["model"], dict.fromkeys(FAILURES, 0))["hang" if proc.is_alive() else "crash"] += 1
                if proc.is_alive():
                    total.fail("hang", spec, "bridge %d: no answer within %g s" % (i, timeout))
                else:
                    total.fail("crash", spec, "bridge %d: worker died with exit code %s" % (i, proc.exitcode))
                break
            try:
                j, c, ex = parent.recv()
            except EOFError:  # died between poll and recv
                spec = bridge_spec(seed, i)
                total.c["bridges"] += 1
                total.c["evaluations"] += GAPS_PER_BRIDGE
                total.fail("crash", spec, "bridge %d: worker died" % i)
                hung.append((i, spec))
                by_model.setdefault(spec["model"], dict.fromkeys(FAILURES, 0))["crash"] += 1
                break
            assert j == i
            model = bridge_spec(seed, i)["model"]
            for k, v in c.items():
                total.c[k] += v
                if k in FAILURES and v:
                    by_model.setdefault(model, dict.fromkeys(FAILURES, 0))[k] += v
            for k, v in ex.items():
                room = 3 - len(total.examples.setdefault(k, []))
                total.examples[k] += v[:max(room, 0)]
            i += 1
            if progress and i % 1000 == 0:
                progress(i, n)
        proc.close()
        i += 1 if i < n else 0  # skip the bridge that hung or crashed
    return dict(counts=total.c, examples=total.examples, seconds=time.time() - t0, seed=seed,
                hung=hung, by_model=by_model)


def failures(report):
    """The failure categories with a non-zero count."""
    return {k: report["counts"][k] for k in FAILURES if report["counts"][k]}


def format_report(report):
    c = report["counts"]
    lines = ["kernel fuzz: seed %d, %d bridges, %d evaluations (%d accepted, %d rejected with a named ValueError or "
             "failed), %.1f s" % (report["seed"], c["bridges"], c["evaluations"], c["accepted"], c["rejected"],
                                   report["seconds"])]
    lines.append("  " + ", ".join("%s %d" % (k, c[k]) for k in FAILURES))
    for model, fc in sorted(report.get("by_model", {}).items()):
        lines.append("  %-20s %s" % (model, ", ".join("%s %d" % (k, v) for k, v in fc.items() if v)))
    for k in FAILURES:
        for e in report["examples"].get(k, []):
            lines.append("  e.g. %s: %s" % (k, e))
    return "\n".join(lines)


if __name__ == "__main__":  # a worker of _Worker: FD SEED START STOP
    out = Connection(int(sys.argv[1]), readable=False)
    out.send("ready")
    _worker(out, *(int(a) for a in sys.argv[2:5]))
