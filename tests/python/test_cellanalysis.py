"""End-to-end shear-cell analysis (yade_capillary.cellanalysis) on synthetic snapshots with a known answer
(synthetic_cell.py): particles on a lattice moving with omega/Omega = 1/2 + 1/2 erf((r - Rc)/W) and no
contacts; the analysis must recover Rc and W at every height and write its outputs with the conventions.
The kinetic stress is the one of the coarse-graining literature; the reduced snapshots give the same fits."""
import json
import os

import numpy as np
import pytest
from synthetic_cell import CFG, RC, W, contact_snapshot, make_run

from yade_capillary import cellanalysis, cg


@pytest.fixture(scope="module")
def rundir(tmp_path_factory):
    return make_run(tmp_path_factory.mktemp("cell"))


def test_recovers_band_centre_and_width(rundir):
    out = cellanalysis.analyse(str(rundir))
    # The kernel (width R) smooths the erf profile: W_fit^2 = W^2 + 2 R^2 for a Gaussian kernel of
    # width R convolved with erf((r - Rc)/W) (the widths add in quadrature, erf scale W/sqrt(2)).
    for rc, w in zip(out["Rc_m"], out["W_m"]):
        assert rc == pytest.approx(RC, abs=2e-4)
        assert w == pytest.approx(np.sqrt(W ** 2 + 2 * CFG["R"] ** 2), rel=0.03)


def test_outputs_and_conventions(rundir):
    for name in ("fits.json", "profiles.csv", "contacts_vs_a.csv", "profiles.png", "contacts_vs_a.png"):
        assert os.path.getsize(rundir / name) > 0
    with open(rundir / "fits.json") as f:
        out = json.load(f)
    for key in ("mu", "mu_err", "c_Pa", "c_err_Pa", "Rc_m", "W_m", "torque_Nm", "conventions"):
        assert key in out
    assert "compression positive" in out["conventions"]["stress"]


def test_reduced_snapshots_give_the_same_fits(rundir, tmp_path):
    # analyse_reduced on the reduced snapshots against analyse on the snapshots themselves: one pipeline,
    # so the same band centres and widths and the same stresses up to the float32 round-off of the
    # kept fields (6e-8 relative; 1e-5 through the erf fit).
    full = cellanalysis.analyse(str(rundir))
    red_dir = tmp_path / "reduced"
    red_dir.mkdir()
    (red_dir / "run.json").write_text((rundir / "run.json").read_text())
    for snap in sorted(rundir.glob("snap_*.npz")):
        cellanalysis.reduce_snapshot(str(snap), CFG, str(red_dir / snap.name.replace("snap_", "cg_")))
    reduced = cellanalysis.analyse_reduced(str(red_dir))
    assert reduced["snapshots"] == full["snapshots"] == 2
    for key in ("Rc_m", "W_m"):
        assert reduced[key] == pytest.approx(full[key], rel=1e-5)
    a = np.genfromtxt(rundir / "profiles.csv", delimiter=",", names=True)
    b = np.genfromtxt(red_dir / "profiles.csv", delimiter=",", names=True)
    for col in ("p_Pa", "tau_Pa"):
        assert np.nanmax(np.abs(a[col] - b[col])) <= 1e-5 * np.nanmax(np.abs(a[col]))


def test_kinetic_stress_is_the_fluctuation_about_the_streaming_velocity():
    """cg.kinetic_stress is sum m v' (x) v' K with v' = v - V(node), V = j/rho (Goldhirsch 2010): for particles
    all moving with one velocity (a drift along r, theta and z at once) it is zero to round-off, whatever the
    drift; with velocities +-u about that drift in equal numbers at the same points it is rho u (x) u. Then
    through the pipeline: a solid-body rotation that also sinks at a uniform speed has no kinetic stress
    but sigma_theta_theta = Omega^2 times the kernel-weighted variance of r about the node, the velocity
    varying over the kernel (the former per-particle definition, about omega r e_theta only, counted the
    uniform sinking as sigma_zz = rho v_z^2)."""
    grid = cg.Grid(np.linspace(0.03, 0.05, 5), np.linspace(0.01, 0.02, 4), 4e-3)
    rng = np.random.default_rng(11)
    n = 4000
    r, t, z = rng.uniform(0.02, 0.06, n), rng.uniform(0, 2 * np.pi, n), rng.uniform(0.0, 0.03, n)
    x = np.stack([r * np.cos(t), r * np.sin(t), z], axis=1)
    m = rng.uniform(1e-6, 2e-6, n)
    er, et, ez = cg.cylindrical_basis(x)
    drift = 0.3 * er + 0.2 * et - 0.1 * ez  # one velocity in each particle's cylindrical basis
    rho, j = cg.density_and_momentum(grid, x, drift, m)
    sk = cg.kinetic_stress(rho, j, cg.momentum_flux(grid, x, drift, m))
    assert np.abs(sk).max() <= 1e-12 * (rho * 0.3 ** 2).max()
    u = 0.05 * et + 0.02 * ez
    x2, m2 = np.concatenate([x, x]), np.concatenate([m, m])
    v2 = np.concatenate([drift + u, drift - u])
    rho2, j2 = cg.density_and_momentum(grid, x2, v2, m2)
    sk2 = cg.kinetic_stress(rho2, j2, cg.momentum_flux(grid, x2, v2, m2))
    uu = np.outer([0.0, 0.05, 0.02], [0.0, 0.05, 0.02])
    np.testing.assert_allclose(sk2, uu[:, :, None, None] * rho2[None, None], rtol=1e-10, atol=1e-12 * rho2.max() * 0.05 ** 2)

    Omega, sink = 2.0, 0.05
    d = {"x": x, "v": Omega * np.cross([0.0, 0.0, 1.0], x) - [0.0, 0.0, sink], "m": m, "xP": np.zeros((0, 3)), "xI": np.zeros((0, 3)),
         "F": np.zeros((0, 3))}
    sigma = cellanalysis.stress(cellanalysis.snapshot_fields(grid, d))
    m0, m1, m2r = grid.accumulate(r, z, np.column_stack([m, m * r, m * r * r]))
    expected = Omega ** 2 * (m2r - m1 * m1 / m0)  # rho Omega^2 <(r_i - <r_i>)^2>, weights m K
    scale = (m0 * sink ** 2).max()
    np.testing.assert_allclose(sigma[1, 1], expected, rtol=1e-6, atol=1e-12 * scale)
    assert 0 < expected.max() < 0.1 * scale
    others = [sigma[a, b] for a in range(3) for b in range(3) if (a, b) != (1, 1)]
    assert np.abs(others).max() <= 1e-12 * scale


def test_reduced_contacts(tmp_path):
    # Contacts of known gaps and forces in known coarse cells (2 x 2 R): the reduced histograms must hold
    # them exactly, and a band chosen afterwards must select them by their cells: with the band = coarse
    # row ic = 2 and the first two of the four node rows of coarse row 5, and the bulk = rows 2, 5 and 6,
    # the band density times the band's volume gives the contacts of row 2 plus the share s of row 5's
    # (s = the volume of its band nodes over the volume of its nodes), the outside one the rest of rows
    # 5-6 (row 8: neither). Bins: gap_edges, edges at integer multiples of 1e-3 R, gaps at bin centres.
    grid = cellanalysis.analysis_grid(CFG)
    edges = cellanalysis.gap_edges(CFG)
    centre = lambda k: (edges[50 + k] + edges[51 + k]) / 2  # bin k above a = 0 (k < 0: overlap)
    cells = [(2, 1)] * 3 + [(2, 5)] * 2 + [(5, 2)] * 4 + [(6, 6)] + [(8, 3)] * 2
    gaps = [centre(-3), centre(10), centre(10), centre(10), centre(40), centre(-3), centre(10), centre(40), centre(40), centre(100), centre(10), centre(0)]
    forces = np.arange(1, 13) * 1e-4
    rng = np.random.default_rng(3)
    contact_snapshot(tmp_path / "snap.npz", grid, cells, gaps, forces, 0.0, rng)
    cellanalysis.reduce_snapshot(str(tmp_path / "snap.npz"), CFG, str(tmp_path / "cg.npz"))
    red = dict(np.load(tmp_path / "cg.npz"))
    all_n, all_f = red["gap_n"][-1], red["gap_f"][-1]
    for k in (-3, 0, 10, 40, 100):
        sel = [g == centre(k) for g in gaps]
        assert all_n[50 + k] == sum(sel)
        assert all_f[50 + k] == pytest.approx(forces[sel].sum(), rel=1e-6)  # float32 sums
    assert all_n[49] == 3 and all_n.sum() == 15  # the wall contacts (off the grid) at -1e-6 m = -0.5e-3 R, in bin -1
    band = np.zeros(grid.R.shape, bool)
    band[8:12] = True  # coarse row 2
    band[20:22] = True  # half the node rows of coarse row 5
    bulk = band.copy()
    bulk[20:28] = True  # coarse rows 5-6
    out = cellanalysis._reduced_contacts(str(tmp_path), grid, [red], band, bulk, CFG)
    A = np.genfromtxt(tmp_path / "contacts_vs_a.csv", delimiter=",", names=True)
    vol = grid.volume_elements()
    v_in, v_out = vol[band].sum(), vol[bulk & ~band].sum()
    sh = vol[20:22, 8:12].sum() / vol[20:24, 8:12].sum()  # of the cell (5, 2): nodes k = 8..11
    assert 0.4 < sh < 0.5
    assert A["band_contacts_per_m3"].sum() * v_in == pytest.approx(5 + 4 * sh, rel=1e-12)
    assert A["outside_contacts_per_m3"].sum() * v_out == pytest.approx(4 * (1 - sh) + 1, rel=1e-12)
    assert out["wet_contact_density_band_1_m3"] * v_in == pytest.approx(4 + 3 * sh, rel=1e-12)  # (5, 2): 3 of 4 separated
    assert out["wet_contact_density_outside_1_m3"] * v_out == pytest.approx(3 * (1 - sh) + 1, rel=1e-12)
    k = 50 + 10
    assert A["band_mean_force_N"][k] == pytest.approx((forces[1:4].sum() + sh * forces[6]) / (3 + sh), rel=1e-6)  # row 2's, share of (5, 2)'s
    assert A["contacts_per_snapshot"][k] == 5 and out["contacts_beyond_gap_bins_per_snapshot"] == 0


def test_interim(rundir, tmp_path):
    # A run in segments before its end (what run_segment keeps: state.npz, torque.csv, cg_*.npz): interim
    # must give the fits of analyse_reduced on the same reduced snapshots, and the torques as the means of
    # the records since the first snapshot (t = 0 here; the record at t = -1 s is before it).
    keep = tmp_path / "keep"
    keep.mkdir()
    for k, snap in enumerate(sorted(rundir.glob("snap_*.npz"))):
        cellanalysis.reduce_snapshot(str(snap), CFG, str(keep / ("cg_%03d.npz" % (k + 1))))
    cfg = dict(CFG, run_s=4.0)
    meta = {"cfg": cfg, "config": "synthetic", "case": "none", "dt_s": 1e-3, "done_steps": 2000, "wall_s": 10.0, "time_s": 2.0}
    np.savez(keep / "state.npz", meta=json.dumps(meta), ids_flowing=np.arange(5))
    np.savetxt(keep / "torque.csv", [(-1.0, -9.0, 9.0), (0.5, -1e-4, 2e-4), (1.5, -3e-4, 4e-4)], delimiter=",",
               header="time_s,torque_rotating_Nm,torque_static_Nm", comments="")
    out = cellanalysis.interim(str(keep))
    ref = cellanalysis.analyse_reduced(str(keep), outdir=str(tmp_path), run=json.loads((rundir / "run.json").read_text()))
    assert out["Rc_m"] == pytest.approx(ref["Rc_m"], rel=1e-12) and out["W_m"] == pytest.approx(ref["W_m"], rel=1e-12)
    assert out["torque_Nm"] == pytest.approx(-2e-4, rel=1e-12) and out["torque_static_Nm"] == pytest.approx(3e-4, rel=1e-12)
    assert (out["done_steps"], out["steps"], out["t_s"]) == (2000, 4000, 2.0)
    assert out["particle_steps_per_s"] == pytest.approx(5 * 2000 / 10.0)
    assert os.path.getsize(keep / "interim" / "profiles.csv") > 0
    # before the first save after the first snapshot there is no torque record of the window: None, not NaN
    np.savetxt(keep / "torque.csv", [(-1.0, -9.0, 9.0)], delimiter=",", header="time_s,torque_rotating_Nm,torque_static_Nm", comments="")
    out = cellanalysis.interim(str(keep))
    assert out["torque_Nm"] is None and out["torque_static_Nm"] is None and out["Rc_m"] == pytest.approx(ref["Rc_m"], rel=1e-12)
    # the heights reach analyse_reduced: 13 band fits, the same as its own at 13 heights
    out = cellanalysis.interim(str(keep), heights=13)
    ref13 = cellanalysis.analyse_reduced(str(keep), heights=13, outdir=str(tmp_path), run=json.loads((rundir / "run.json").read_text()))
    assert len(out["band_fits"]) == 13 and out["Rc_m"] == pytest.approx(ref13["Rc_m"], rel=1e-12)
