# The random-scene campaign (tests/support/random_scenes.py): random wet scenes as a new user builds them
# (models, rupture rules, viscosities 0 / water / 50 x water, fixed or film liquid, transfer rules,
# friction, size ratios up to 4, walls or facets, both loops, gravity, save and reload at half time),
# each at stable_dt(). Fails if any scene that runs explodes (a speed above 20 times what its start
# allows), has a non-finite state, a negative or non-zero-without-bridges total, or loses or creates
# film liquid beyond 1e-12 of the total, or if a set-up error is not a ValueError naming its parameter.
# CI size (defaults): 60 scenes of 2000 steps. Nightly size, with its counts in the closing notes:
#   PYTHONPATH=tests/support build/yade-capillary -j2 -n -x tests/yade/test_random_scenes.py 500 3000 1
import sys

import random_scenes
from testing import Checker

n = int(sys.argv[1]) if len(sys.argv) > 1 else 60
steps = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
seed = int(sys.argv[3]) if len(sys.argv) > 3 else 1
ck = Checker("test_random_scenes")
counts = random_scenes.campaign(n, steps, seed)
print("campaign seed %d, %d scenes x %d steps: %d ran, %d refused, %d failed; %s"
      % (seed, n, steps, counts["ran"], counts["refused"], counts["failed"], ", ".join("%s %d" % (c, counts[c]) for c in random_scenes.CLASSES)))
ck.true(counts["ran"] >= n // 2, "at least half of the scenes ran (%d of %d; the rest refused as bad input)" % (counts["ran"], n))
for cls in random_scenes.CLASSES:
    ck.true(counts[cls] == 0, "no scene with failure class %s (%d)" % (cls, counts[cls]))
ck.finish()
