# docs/reference.md, the class reference generated from the docstrings of the build
# (tools/reference.py), is up to date: the page this build generates must equal the
# committed one. On a difference the head of the unified diff (committed -> generated) and the
# command that regenerates the page are printed. Also: the class list, which the generator takes from
# the plugin library's symbols, is the list of classes pkg/yade/*.hpp registers (REGISTER_SERIALIZABLE),
# and two generations in one process give the same text (nothing that varies between runs).
import difflib
import glob
import os
import re
import sys

from testing import Checker

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(sys.argv[0])))), "tools"))
import reference  # noqa: E402  (tools/reference.py)

DIFF_LINES = 40  # of the unified diff shown on failure

ck = Checker("test_reference")
root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(sys.argv[0]))))

classes = reference.plugin_classes()
declared = set()
for header in glob.glob(os.path.join(root, "pkg", "yade", "*.hpp")):
    with open(header, encoding="utf-8") as f:
        declared |= set(re.findall(r"^\s*REGISTER_SERIALIZABLE\(\s*(\w+)\s*\)", f.read(), re.M))
ck.true(classes == sorted(declared), "classes found in %s %s = classes registered by pkg/yade/*.hpp %s"
        % (reference.PLUGIN_LIBRARY, classes, sorted(declared)))

generated = reference.markdown(classes)
ck.true(reference.markdown(classes) == generated, "two generations of the page in one process are identical")

path = os.path.join(root, "docs", "reference.md")
committed = open(path, encoding="utf-8").read() if os.path.exists(path) else ""
if committed != generated:
    diff = list(difflib.unified_diff(committed.splitlines(), generated.splitlines(), "docs/reference.md (committed)",
                                     "docs/reference.md (generated from this build)", lineterm=""))
    print("\n".join(diff[:DIFF_LINES]))
    if len(diff) > DIFF_LINES:
        print("... (%d more diff lines)" % (len(diff) - DIFF_LINES))
    print("docs/reference.md is stale; regenerate it (from the repository root) with:\n    %s" % reference.REGENERATE)
ck.true(committed == generated, "docs/reference.md equals the page generated from this build (%d lines)" % generated.count("\n"))
ck.finish()
