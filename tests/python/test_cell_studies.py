"""The cause analysis's tools (scripts/studies: cell_fits, cell_contacts, cell_closure, cell_stress_parts,
cell_report) on synthetic data with known answers (synthetic_cell.py and tables written here)."""
import json
import os

import numpy as np
import pytest
from synthetic_cell import CFG, RC, contact_snapshot, make_run

from studies import cell_closure, cell_contacts, cell_fits, cell_report, cell_stress_parts, cell_study
from yade_capillary import cellanalysis, cg


@pytest.fixture(scope="module")
def rundir(tmp_path_factory):
    return make_run(tmp_path_factory.mktemp("cell"))


def test_block_fits(rundir, tmp_path):
    # Two blocks of one snapshot each of the steady synthetic band: each block recovers Rc (as the
    # whole run does, within 2e-4 m), so the mean does and the standard error of the blocks is below
    # that tolerance; the reduced snapshots go to `keep`. Three blocks of two snapshots: ValueError
    # naming the parameter and the allowed range.
    out = cell_fits.block_fits(str(rundir), 2, keep=str(tmp_path / "keep"))
    assert [b["snapshots"] for b in out["blocks"]] == [[1], [2]]
    assert out["Rc_mean_m"] == pytest.approx(RC, abs=2e-4) and out["Rc_mean_m_err"] < 2e-4
    assert sorted(os.listdir(tmp_path / "keep")) == ["cg_001.npz", "cg_002.npz"]
    with pytest.raises(ValueError, match=r"blocks: 3 is outside \[2, 2\]"):
        cell_fits.block_fits(str(rundir), 3, keep=str(tmp_path / "keep"))


def test_gap_classes(tmp_path):
    # Bins of 1 um centred at a = -1.5, -0.5, 0.5, 1.5, 2.5, 3.5 um (a_crit = 3.5 um) and one at 0
    # straddling a = 0 (centres need not be regular at 0 in this synthetic table; half a bin = the
    # median spacing / 2 = 0.5 um): contact (2 bins), straddling (1), short (centre <= 1.75: 2), long
    # (2); the densities are chosen so that each ratio is known.
    rows = [(-1.5e-6, 3, 1.0, 10, 1.0, 10), (-0.5e-6, 1, 1.0, 10, 1.0, 10), (0.0, 7, 1.0, 1, 1.0, 1), (0.5e-6, 2, 1.0, 5, 1.0, 5),
            (1.5e-6, 2, 1.0, 5, 1.0, 5), (2.5e-6, 1, 1.0, 6, 1.0, 3), (3.5e-6, 1, 1.0, 6, 1.0, 3)]
    path = tmp_path / "contacts_vs_a.csv"
    np.savetxt(path, np.array(rows), delimiter=",",
               header="a_m,contacts_per_snapshot,mean_force_N,band_contacts_per_m3,band_mean_force_N,outside_contacts_per_m3", comments="")
    g = cell_contacts.gap_classes(str(path))
    assert g["a_crit_m"] == pytest.approx(3.5e-6)
    assert (g["contact_per_snapshot"], g["straddling_per_snapshot"], g["short_per_snapshot"], g["long_per_snapshot"]) == (4, 7, 4, 2)
    assert g["short_share"] == pytest.approx(4 / 6)
    assert g["contact_band_over_outside"] == pytest.approx(1.0)
    assert g["short_band_over_outside"] == pytest.approx(1.0)
    assert g["long_band_over_outside"] == pytest.approx(2.0)


def test_gap_classes_computed_edges(tmp_path):
    # Bins as a histogram makes them: 12 edges of 7 um from -21 um, centres halfway, so that the edge at
    # a = 0 is computed (-4e-22 m here) and the last three bins are empty. Expected: no straddling bin;
    # contact = the 3 bins below 0 (15), a_crit = 38.5 um (the last bin with contacts, not the last
    # centre 59.5 um), short = centres 3.5-17.5 um <= a_crit/2 (9), long = 24.5-38.5 um (3).
    edges = np.linspace(-2.1e-5, 6.3e-5, 13)
    a = (edges[:-1] + edges[1:]) / 2
    n = [5, 5, 5, 4, 3, 2, 1, 1, 1, 0, 0, 0]
    path = tmp_path / "contacts_vs_a.csv"
    np.savetxt(path, np.column_stack([a, n, np.ones(12), n, np.ones(12), n]), delimiter=",",
               header="a_m,contacts_per_snapshot,mean_force_N,band_contacts_per_m3,band_mean_force_N,outside_contacts_per_m3", comments="")
    g = cell_contacts.gap_classes(str(path))
    assert g["a_crit_m"] == pytest.approx(38.5e-6)
    assert (g["contact_per_snapshot"], g["straddling_per_snapshot"], g["short_per_snapshot"], g["long_per_snapshot"]) == (15, 0, 9, 3)


def test_count_ratio_vs_gap(tmp_path):
    # The bins of test_gap_classes_computed_edges (edge at a = 0 computed): dry pairs only in the 3 bins
    # below 0 (15 per snapshot), wet 18 there plus bridges 4, 3, 2, ... above. Expected by hand: wet
    # over dry at a_max = 0: 18/15; at 7 um: 22/15; at 21 um: 27/15; a_max off an edge, or bins of
    # another cell: ValueError.
    edges = np.linspace(-2.1e-5, 6.3e-5, 13)
    a = (edges[:-1] + edges[1:]) / 2
    header = "a_m,contacts_per_snapshot,mean_force_N,band_contacts_per_m3,band_mean_force_N,outside_contacts_per_m3"

    def write(name, n, centres=a):
        path = tmp_path / name
        np.savetxt(path, np.column_stack([centres, n, np.ones(12), n, np.ones(12), n]), delimiter=",", header=header, comments="")
        return str(path)

    dry = write("dry.csv", [5, 5, 5, 0, 0, 0, 0, 0, 0, 0, 0, 0])
    wet = write("wet.csv", [6, 6, 6, 4, 3, 2, 1, 1, 1, 0, 0, 0])
    rows = cell_contacts.count_ratio_vs_gap(wet, dry, [0.0, 7e-6, 2.1e-5])
    assert [r[3] for r in rows] == pytest.approx([18 / 15, 22 / 15, 27 / 15])
    assert (rows[2][1], rows[2][2]) == (27, 15)
    with pytest.raises(ValueError, match="not a bin edge"):
        cell_contacts.count_ratio_vs_gap(wet, dry, [3e-6])
    other = write("other.csv", [6] * 12, centres=2 * a)
    with pytest.raises(ValueError, match="different separation bins"):
        cell_contacts.count_ratio_vs_gap(other, dry, [0.0])


def test_force_against_model(tmp_path):
    # A table whose separated bins (9 of 2e-5 m, the bin centred at 0 straddles a = 0) hold exactly the
    # model's bin-averaged force, one bin doubled: the median ratio is 1, the mean weighted by the
    # contacts (one per bin) is 10/9.
    from yade_capillary import kernels
    R, V, gamma = 2.381e-3, 13.6e-12, 20.6e-3
    centres = np.arange(-1, 10) * 2e-5
    half = 1e-5
    rows = []
    for k, x in enumerate(centres):
        f = np.mean(kernels.force("willett_full", np.linspace(x - half, x + half, 21), R1=R, R2=R, volume=V, gamma=gamma, theta=0.0)) if x > half else 1.0
        rows.append((x, 1.0, f * (2.0 if k == 5 else 1.0), 0, 0, 0))
    path = tmp_path / "contacts_vs_a.csv"
    np.savetxt(path, np.array(rows), delimiter=",",
               header="a_m,contacts_per_snapshot,mean_force_N,band_contacts_per_m3,band_mean_force_N,outside_contacts_per_m3", comments="")
    fm = cell_contacts.force_against_model(str(path), "willett_full", R, V, gamma)
    assert fm["bins"] == 9
    assert fm["median"] == pytest.approx(1.0, rel=1e-12)
    assert fm["weighted_mean"] == pytest.approx(10 / 9, rel=1e-12)


def _profiles(path, z, p, tau, nodes=3):
    """A profiles.csv whose band has `nodes` nodes at each height z with pressure p and shear stress tau
    (and one node outside the band that must be ignored)."""
    rows = []
    for zi, pi, ti in zip(z, p, tau):
        rows += [(0.05 + 1e-3 * k, zi, 100.0, 0.5, 0.2, pi, ti, 1.0) for k in range(nodes)]
        rows.append((0.02, zi, 100.0, 0.0, 0.0, pi, 100.0, 0.0))
    np.savetxt(path, np.array(rows), delimiter=",", header="r_m,z_m,rho_kg_m3,omega_over_Omega,gamma_dot_1_s,p_Pa,tau_Pa,in_band", comments="")
    return str(path)


def test_excess_shear_against_known_lines(tmp_path):
    """Wet band tau = 0.13 p + 1.3 Pa (Gladkyy's 13.6 nl line), dry band tau = 0.137 p - 0.25 Pa (our dry
    validation fit) at other heights and pressures: the excess at every wet height within the dry
    pressures is the difference of the two lines there (the interpolation of a straight dry line is
    exact), and the intercept with the slope 0.13 is 1.3 Pa."""
    z = np.linspace(0.005, 0.035, 13)
    p_dry = np.linspace(25.0, 1.0, 13)
    dry = _profiles(tmp_path / "dry.csv", z, p_dry, 0.137 * p_dry - 0.25)
    p_wet = np.linspace(30.0, 2.0, 13)  # the deepest three lie beyond the dry pressures
    wet = _profiles(tmp_path / "wet.csv", z, p_wet, 0.13 * p_wet + 1.3)
    e = cell_fits.excess_shear(wet, dry)
    p = np.array([r[1] for r in e["rows"]])
    assert len(p) == 10 and p.max() <= 25.0
    np.testing.assert_allclose([r[4] for r in e["rows"]], 1.3 + 0.25 - 0.007 * p, rtol=0, atol=1e-12)
    np.testing.assert_allclose(e["excess_Pa"], np.mean(1.55 - 0.007 * p), rtol=0, atol=1e-12)
    assert e["excess_low_Pa"] > e["excess_high_Pa"]
    assert abs(e["c_fixed_mu_Pa"] - 1.3) < 1e-12 and e["c_fixed_mu_err_Pa"] < 1e-12
    line = cell_fits.excess_shear(wet, (0.137, -0.25, 1.0, 25.0))  # the dry band given as its fitted line
    np.testing.assert_allclose([r[4] for r in line["rows"]], [r[4] for r in e["rows"]], rtol=0, atol=1e-12)


def test_excess_shear_needs_overlapping_pressures(tmp_path):
    z = np.linspace(0.005, 0.035, 5)
    dry = _profiles(tmp_path / "dry.csv", z, np.linspace(10.0, 1.0, 5), np.linspace(1.0, 0.1, 5))
    wet = _profiles(tmp_path / "wet.csv", z, np.linspace(50.0, 20.0, 5), np.linspace(6.0, 3.0, 5))
    with pytest.raises(ValueError, match="dry band's pressures"):
        cell_fits.excess_shear(wet, dry)


def test_fit_variants_gladkyy_slope():
    # Band stresses on Gladkyy's 13.6 nl line tau = 0.13 p + 1.3 Pa (§4.1), pressures 2-20 Pa over the
    # heights, nodes outside the band (gamma_dot below 80 % of the peak) on another line: the free fit
    # and the fit with his slope both give c = 1.3 Pa, the latter over the band's mean pressure.
    nr, nz = 6, 5
    p = np.linspace(2.0, 20.0, nz)[None, :] * np.ones((nr, 1))
    band = np.zeros((nr, nz), bool)
    band[2:4] = True
    tau = np.where(band, 0.13 * p + 1.3, 0.5 * p)
    sigma = np.zeros((3, 3, nr, nz))
    for k in range(3):
        sigma[k, k] = p
    sigma[0, 1] = sigma[1, 0] = tau
    gdot = np.where(band, 1.0, 0.1)
    out = cell_fits.fit_variants(sigma, gdot, np.ones((nr, nz), bool), 0.5)
    assert out["baseline"]["mu"] == pytest.approx(0.13, abs=1e-12) and out["baseline"]["c_Pa"] == pytest.approx(1.3, abs=1e-12)
    g = out["baseline_gladkyy_slope"]
    assert g["mu"] == 0.13 and g["c_Pa"] == pytest.approx(1.3, abs=1e-12) and g["c_err_Pa"] < 1e-12
    assert g["points"] == 10 and g["p_mean_Pa"] == pytest.approx(11.0, abs=1e-12)


def test_report_of_reduced_fits(tmp_path):
    # cell_report.report on what analyse_reduced writes (no CG torque at Rs: it needs every contact) with
    # a fixed-slope variant (no mu_err): the table must show the run's numbers, "n/a" for the missing
    # torque and the fixed slope as such (both raised KeyError before).
    cfg = dict(CFG, dt_over_tc=0.05, tc=5.4e-4, run_s=5.0)
    d = tmp_path / "dry"
    d.mkdir()
    band = [{"z_m": 0.01, "Rc_m": 0.04, "W_m": 0.006}]
    fit = {"mu": 0.134, "mu_err": 0.001, "c_Pa": 0.76, "c_err_Pa": 0.04, "mu_threshold": 0.14, "c_Pa_threshold": 0.5, "band_points": 40,
           "band_points_threshold": 50, "band_fits": band, "torque_Nm": 0.1106, "torque_static_Nm": -0.11,
           "fit_variants": {"baseline": {"mu": 0.134, "mu_err": 0.001, "c_Pa": 0.76, "c_err_Pa": 0.04, "points": 40},
                            "baseline_gladkyy_slope": {"mu": 0.13, "c_Pa": 0.91, "c_err_Pa": 0.02, "points": 40}}}
    (d / "fits.json").write_text(json.dumps(fit))
    (d / "run.json").write_text(json.dumps({"cfg": cfg, "steps": 185185, "wall_s": 24000.0, "particle_steps_per_s": 1.3e6}))
    md = cell_report.report(str(tmp_path))
    row = next(line for line in md.splitlines() if line.startswith("| dry |"))
    assert "0.134 ± 0.001 (0.13)" in row and "0.76 ± 0.04 (0.0)" in row
    assert "110.60 / -110.00 / n/a" in row
    assert "| baseline_gladkyy_slope | 0.130 (fixed), 0.91 ± 0.02 (40) |" in md


def test_reduced_torque_closure(rundir, tmp_path):
    # The torque balance kept in reduced snapshots (contact by contact, per snapshot) and averaged by
    # analyse_reduced must equal torque_closure over the same two snapshots (walls inside by contact point
    # and by centre, crossing torque) to float64 round-off.
    grid = cellanalysis.analysis_grid(CFG)
    red_dir = tmp_path / "reduced"
    red_dir.mkdir()
    (red_dir / "run.json").write_text((rundir / "run.json").read_text())
    rng = np.random.default_rng(5)
    cells = [(ic, kc) for ic in range(1, 11) for kc in range(0, 7)]
    data = []
    for s in range(2):
        snap = tmp_path / ("snap_%d.npz" % s)
        contact_snapshot(snap, grid, cells, rng.uniform(-1e-5, 1e-4, len(cells)), rng.uniform(1e-4, 1e-3, len(cells)), float(s), rng)
        with np.load(snap) as d:
            data.append(dict(d))
        cellanalysis.reduce_snapshot(str(snap), CFG, str(red_dir / ("cg_%03d.npz" % (s + 1))), more=cell_closure.reduced_closure)
    full = cell_closure.torque_closure(data, CFG, grid.w)
    reduced = cell_study.analyse_reduced(str(red_dir))["torque_closure"]
    assert len(full) == len(reduced) > 5
    assert any(abs(row["crossing_Nm"]) > 0 for row in full)
    for a, b in zip(full, reduced):
        for key in ("r0_m", "walls_inside_Nm", "walls_centre_inside_Nm", "crossing_Nm"):
            assert b[key] == pytest.approx(a[key], rel=1e-12, abs=1e-18)


def test_stress_parts_and_band_decomposition():
    """stress_parts splits the contact stress at a = 0 (bridges a > 0, contacts a <= 0; the two sum to the
    whole contact stress, as cg.contact_stress is linear in the contacts), and band_decomposition splits the
    excess over the dry line exactly: the parts' excesses sum to the total's, and a stress that lies on the
    dry line has no excess."""
    rng = np.random.default_rng(3)
    n = 400
    r, t, z = rng.uniform(0.02, 0.05, n), rng.uniform(0, 2 * np.pi, n), rng.uniform(0.004, 0.025, n)
    xP = np.stack([r * np.cos(t), r * np.sin(t), z], axis=1)
    xI = xP + rng.normal(scale=2e-3, size=(n, 3))
    snap = {"xP": xP, "xI": xI, "F": rng.normal(size=(n, 3)), "gap": rng.uniform(-1e-4, 1e-4, n), "x": xP, "v": rng.normal(scale=1e-3, size=(n, 3)),
            "m": np.full(n, 1e-4)}
    parts = cell_stress_parts.stress_parts(snap, CFG)
    whole = cg.contact_stress(cellanalysis.analysis_grid(CFG), xP, xI, snap["F"])
    assert np.allclose(parts["bridges"] + parts["contacts"], whole, rtol=1e-12, atol=1e-12 * np.abs(whole).max())
    assert np.abs(parts["bridges"]).max() > 0 and np.abs(parts["contacts"]).max() > 0

    band = np.zeros(parts["contacts"].shape[2:], bool)
    band[5:15, 3:8] = True
    out = cell_stress_parts.band_decomposition(parts, band, (0.12, -0.04))
    for q in ("p", "tau", "excess"):
        assert sum(out["%s_%s_Pa" % (q, k)] for k in parts) == pytest.approx(out["%s_Pa" % q], rel=1e-12, abs=1e-12)

    # One part on the dry line tau = c + mu p at every node (shear along r theta): no excess.
    mu, c = 0.12, 0.3
    p = np.full(band.shape, 20.0)
    line = np.zeros((3, 3) + band.shape)
    for k in range(3):
        line[k, k] = p
    line[0, 1] = line[1, 0] = c + mu * p
    out = cell_stress_parts.band_decomposition({"contacts": line}, band, (mu, c))
    assert out["excess_Pa"] == pytest.approx(0.0, abs=1e-12) and out["excess_contacts_Pa"] == pytest.approx(0.0, abs=1e-12)
    assert out["tau_Pa"] == pytest.approx(c + mu * 20.0, rel=1e-12)
