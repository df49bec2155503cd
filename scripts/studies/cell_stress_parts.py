"""Where the wet band's excess shear stress over the dry material comes from (the cause analysis,
scripts/stress_parts.py): the stress of a snapshot split into separated bridges, contacts and kinetic
part, and the band's excess over the dry line split the same way. Plain numpy."""
import json
import os

import numpy as np

from yade_capillary import cellanalysis, cg

from .cell_study import GLADKYY_HEIGHTS


def stress_parts(snap, cfg):
    """The stress of one snapshot (shearcell.snapshot's arrays, as a dict) split by where it comes from: the
    separated bridges (surface separation a > 0, the capillary force alone), the contacts (a <= 0: spring and
    dashpot, and F(0) only where forceInContact is on; Gladkyy 2014 eq. (4) has it off) and the kinetic stress
    (about the snapshot's own streaming velocity, cg.kinetic_stress). Returns {"bridges", "contacts",
    "kinetic"}, each (3, 3, nr, nz) [Pa] on cellanalysis.analysis_grid(cfg)."""
    grid = cellanalysis.analysis_grid(cfg)
    apart = np.asarray(snap["gap"]) > 0
    part = lambda m: cg.contact_stress(grid, snap["xP"][m], snap["xI"][m], snap["F"][m]) if m.any() else np.zeros((3, 3) + grid.R.shape)
    rho, j = cg.density_and_momentum(grid, snap["x"], snap["v"], snap["m"])
    return {"bridges": part(apart), "contacts": part(~apart), "kinetic": cg.kinetic_stress(rho, j, cg.momentum_flux(grid, snap["x"], snap["v"], snap["m"]))}


def run_band(rundir, heights=GLADKYY_HEIGHTS):
    """The band nodes (boolean (nr, nz) on cellanalysis.analysis_grid) of a complete run's fit from its reduced
    snapshots (the selection of mu and c of cellanalysis.fit_fields)."""
    with open(os.path.join(rundir, "run.json")) as f:
        run = json.load(f)
    fields = cellanalysis.average_fields(cellanalysis.load_reduced(rundir))
    return cellanalysis.fit_fields(cellanalysis.analysis_grid(run["cfg"]), fields, run, heights=heights)["band"]


def band_decomposition(parts, band, dry_line):
    """How the band's shear stress over the dry material's divides among the parts of the stress.

    parts: {name: sigma (3, 3, nr, nz) [Pa]} whose sum is the stress; band: boolean (nr, nz) of the band
    nodes; dry_line: (mu, c_Pa) of the dry material. At each band node the shear of every part is its
    (r theta, z theta) shear projected on the direction of the total's (so that the parts' shears add up
    to tau of cg.pressure_and_shear), p its tr/3. The excess tau - (c + mu p) then splits exactly into
    tau_k - mu p_k for every part but one, `contacts`, which also takes -c: for the contacts that is how
    far their own network departs from the dry line at their own pressure; for the bridges, their direct
    shear plus mu times their tension. Returns {"p_Pa", "tau_Pa", "excess_Pa", and per part "p_<k>_Pa",
    "tau_<k>_Pa", "excess_<k>_Pa"}, means over the band nodes."""
    mu, c = dry_line
    split = {k: cg.pressure_and_shear_components(s) for k, s in parts.items()}
    p = sum(p_k for p_k, _ in split.values())
    shear = sum(shear_k for _, shear_k in split.values())
    norm = np.hypot(shear[0], shear[1])
    u = np.divide(shear, norm, out=np.zeros_like(shear), where=norm > 0)
    out = {"p_Pa": float(p[band].mean()), "tau_Pa": float(norm[band].mean())}
    out["excess_Pa"] = out["tau_Pa"] - (c + mu * out["p_Pa"])
    for k, (p_k, shear_k) in split.items():
        p_k = float(p_k[band].mean())
        tau_k = float((u[0] * shear_k[0] + u[1] * shear_k[1])[band].mean())
        out.update({"p_%s_Pa" % k: p_k, "tau_%s_Pa" % k: tau_k, "excess_%s_Pa" % k: tau_k - mu * p_k - (c if k == "contacts" else 0.0)})
    return out
