# Writes the class reference docs/reference.md from the docstrings of the build (see
# tools/reference.py); tests/yade/test_reference.py fails when the committed page is stale.
# Run:  build/yade-capillary -n -x tools/make_reference.py [output]     (default <repo>/docs/reference.md)
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # tools/reference.py; yade does not put the script's folder on sys.path
import reference  # noqa: E402

root = os.path.dirname(os.path.dirname(os.path.realpath(sys.argv[0])))
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "docs", "reference.md")
classes = reference.plugin_classes()
text = reference.markdown(classes)
with open(out, "w", encoding="utf-8") as f:
    f.write(text)
print("wrote %s: %d classes (%s), %d lines" % (out, len(classes), ", ".join(classes), text.count("\n")))
sys.exit(0)
