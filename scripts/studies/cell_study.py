"""The shear-cell analysis of the cause analysis (docs/studies/gladkyy-cause-analysis.md): the pipeline's
(yade_capillary.cellanalysis) fits.json with the study's entries added: the fit under each other convention
(fit_variants), the torque balance of cylinders (torque_closure) and, from full snapshots, the CG torque
through the split (torque_cg_at_Rs_Nm, and with a quarter of the kernel width). Plain numpy."""
import json
import os

import numpy as np
from yade_capillary import cellanalysis

from . import cell_closure, cell_fits

# Gladkyy 2014 §4.2: band centres and widths "obtained for 13 different heights" (Fig. 6; which heights
# is not stated: here evenly from 0.2 to 0.7 of the bed height, as for the 5 heights of the smaller cells).
GLADKYY_HEIGHTS = 13

TORQUE = ("torque_Nm: on the rotating walls from their contacts (z component about the axis, mean of the second half of "
          "the run); torque_cg_at_Rs_Nm: 2 pi Rs^2 times the integral of sigma_r_theta over z on the cylinder r = Rs, "
          "from 3 kernel widths below the bottom to 3 above the highest particle; lower than torque_Nm because the "
          "kernel averages the torque flux over r around Rs, where it peaks, and bottom contacts straddling the split "
          "pass torque to the static bottom outside Rs; torque_cg_at_Rs_w4_Nm: the same with w/4; torque_closure: the "
          "balance of cylinders r0 (cell_closure.torque_closure)")
TORQUE_REDUCED = ("torque_Nm: on the rotating walls from their contacts, mean of the second half of the run; torque_closure: "
                  "contact by contact only (the CG flux needs every contact)")


def more_of_snapshots(cfg):
    """The `more` of cellanalysis.analyse for a cell of configuration dict cfg: fit_variants, torque_cg_at_Rs_Nm,
    torque_cg_at_Rs_w4_Nm and torque_closure."""
    w = cellanalysis.analysis_grid(cfg).w

    def more(f, data):
        return {"fit_variants": cell_fits.variants_of(f), "torque_cg_at_Rs_Nm": cell_closure.cylinder_flux(data, cfg["Rs"], w),
                "torque_cg_at_Rs_w4_Nm": cell_closure.cylinder_flux(data, cfg["Rs"], w / 4),
                "torque_closure": cell_closure.torque_closure(data, cfg, w), "conventions": {"torque": TORQUE}}
    return more


def more_of_reduced(cfg):
    """The `more` of cellanalysis.analyse_reduced (and interim): fit_variants and the torque balance counted
    contact by contact, from reduced snapshots that keep it (reduce_more)."""
    def more(f, red):
        return {"fit_variants": cell_fits.variants_of(f), "torque_closure": cell_closure.closure_of_reduced(red, cfg),
                "conventions": {"torque": TORQUE_REDUCED}}
    return more


# What the study keeps of each snapshot beside the pipeline's fields (shearcell.run_segment(..., reduce_more=...)).
reduce_more = cell_closure.reduced_closure


def _cfg(rundir):
    with open(os.path.join(rundir, "run.json")) as fh:
        return json.load(fh)["cfg"]


def analyse(rundir, gamma_dot_min=None, heights=5):
    """cellanalysis.analyse of rundir with the study's entries (more_of_snapshots); returns the fits dict."""
    return cellanalysis.analyse(rundir, gamma_dot_min, heights, more=more_of_snapshots(_cfg(rundir)))


def analyse_reduced(rundir, heights=5):
    """cellanalysis.analyse_reduced of rundir with the study's entries (more_of_reduced); returns the fits dict."""
    return cellanalysis.analyse_reduced(rundir, heights=heights, more=more_of_reduced(_cfg(rundir)))


def interim(keep, heights=5):
    """cellanalysis.interim of a run in segments with the study's entries (more_of_reduced)."""
    with np.load(os.path.join(keep, "state.npz")) as d:
        cfg = json.loads(str(d["meta"]))["cfg"]
    return cellanalysis.interim(keep, heights=heights, more=more_of_reduced(cfg))
