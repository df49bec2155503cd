"""guard(): the patches that keep the interactions' Python objects current while PendularLoop computes
from its records, under the name that PendularLoop's docstrings (keepRecords, readersGuarded) give it
(import inside yade only). yade_capillary.patches lists and installs every patch of YADE's Python
objects; yade_capillary.scene.engines() installs them.
"""


def guard():
    """Install every patch, as yade_capillary.patches.install(records=True) does; PendularLoop keeps
    records only after it."""
    from . import patches

    patches.install(records=True)
