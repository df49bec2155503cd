"""A small check harness for the in-YADE tests (run as ``yade -n -x test.py``).

Every check states its tolerance and where the expected value comes from; ``finish()`` prints
the tally and exits with status 1 if any check failed, so that ctest sees the failure.
"""
import math
import sys


class Checker:
    def __init__(self, name):
        self.name, self.passed, self.failed = name, 0, []

    def _record(self, ok, text):
        if ok:
            self.passed += 1
        else:
            self.failed.append(text)
            print("FAIL:", text)

    def close(self, actual, expected, rtol, what, source, atol=0.0):
        """|actual - expected| <= rtol |expected| + atol; `source` says where `expected` comes from."""
        ok = math.isfinite(actual) and abs(actual - expected) <= rtol * abs(expected) + atol
        self._record(ok, "%s: got %.12g, expected %.12g (%s), rtol %g" % (what, actual, expected, source, rtol))

    def true(self, condition, what):
        self._record(bool(condition), what)

    def raises(self, exc_type, fn, must_contain, what):
        """fn() must raise exc_type whose message contains every string of must_contain."""
        try:
            fn()
        except exc_type as e:
            missing = [s for s in must_contain if s not in str(e)]
            self._record(not missing, "%s: message %r lacks %s" % (what, str(e), missing))
            return
        except Exception as e:  # a different exception type is a failure too
            self._record(False, "%s: raised %s(%s), expected %s" % (what, type(e).__name__, e, exc_type.__name__))
            return
        self._record(False, "%s: no exception" % what)

    def finish(self):
        print("%s: %d checks passed, %d failed" % (self.name, self.passed, len(self.failed)))
        sys.exit(1 if self.failed or not self.passed else 0)
