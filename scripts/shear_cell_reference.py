# Regenerates tests/data/shear_cell_ci_reference.json: the ci configuration of the shear cell,
# every liquid case, several seeds; stores mean and seed-to-seed standard deviation of mu, c, Rc
# and the torque on the rotating walls, and the command line. The CI regression (tests/yade/test_shear_cell_ci.py) compares its own
# run (seed 1) with these values within 4 standard deviations.
# Run:  build/yade-capillary -j1 -n -x scripts/shear_cell_reference.py [nseeds]   (about 1 min per seed)
import os
import sys
import tempfile

from yade_capillary import cellanalysis, shearcell
sys.path.insert(0, os.path.dirname(os.path.realpath(sys.argv[0])))  # yade does not put the script's folder on sys.path
from studies import seedref  # noqa: E402

nseeds = int(sys.argv[1]) if len(sys.argv) > 1 else 3
root = os.path.dirname(os.path.dirname(os.path.realpath(sys.argv[0])))  # yade puts the script's path in sys.argv[0]
work = tempfile.mkdtemp(prefix="shear_cell_ref_")
values = {}
for case in shearcell.CASES:
    for seed in range(1, nseeds + 1):
        d = os.path.join(work, "%s_%d" % (case, seed))
        os.makedirs(d)
        shearcell.prepare("ci", case, os.path.join(d, "prepared.yade.gz"), seed=seed)
        shearcell.run(os.path.join(d, "prepared.yade.gz"), d)
        s = shearcell.summary(cellanalysis.analyse(d))
        print(case, seed, s)
        for k, v in s.items():
            values.setdefault(case, {}).setdefault(k, []).append(v)
seedref.write(os.path.join(root, "tests", "data", "shear_cell_ci_reference.json"),
              "build/yade-capillary -j1 -n -x scripts/shear_cell_reference.py %d" % nseeds, values, config="ci",
              seeds=list(range(1, nseeds + 1)))
sys.exit(0)
