"""Unequal contact angles: the mean of the cosines (Elskamp 2018 eq. 14, 15)
against the cosine of the mean angle (the kernels' former form), measured against the exact solver.
The facts asserted here are the ones scripts/mixed_angles.py reports, on a reduced set of V*."""
import csv
import math
import os

import numpy as np
import pytest

from studies import mixedangles
from yade_capillary import kernels

EQ = mixedangles.EXACT_EQUAL
MODELS = ("willett_full", "willett_reduced", "rabinovich_lambert", "richefeu", "young_laplace_table", EQ)
DERJAGUIN_SCALED = ("willett_reduced", "rabinovich_lambert", "richefeu")  # F(0) = 2 pi R gamma cos(theta)


@pytest.fixture(scope="module")
def comp():
    _, summary = mixedangles.evaluate(vstars=(1e-4, 1e-2), models=MODELS, n_gaps=12)
    rows = mixedangles.comparison(summary, MODELS)
    assert len(rows) == 2 * 2 * 2 * len(MODELS)  # nothing refused in the emulated forms
    return summary, rows


def rows_of(rows, model, pair=None):
    """The comparison rows of one model (and pair)."""
    return [r for r in rows if r["model"] == model and (pair is None or r["pair"] == pair)]


def test_pairs_are_elskamp_table1():
    # Elskamp 2018 Table 1, contact angle with water: POM 40, glass 15, steel 45, PVC 50 deg.
    pairs = {(p.body1, p.theta1_deg, p.body2, p.theta2_deg) for p in mixedangles.PAIRS}
    assert pairs == {("glass", 15, "steel", 45), ("POM", 40, "PVC", 50)}
    assert "Table 1" in mixedangles.SOURCE


def test_kernels_use_the_mean_of_cosines(comp):
    # pair_of: theta = acos((cos theta1 + cos theta2) / 2) for the forces (the rupture rules keep the
    # mean angle). Called with both angles, every closed-form model gives the F(0) of the mean-of-cosines
    # emulation; the table takes the two angles separately (the exact bridge).
    summary, _ = comp
    for r in summary:
        if r["form"] != "native":
            continue
        if r["model"] == "young_laplace_table":  # the exact mixed bridge, within the table's 5e-4
            assert r["status"] == "ok" and r["F0_model_N"] == pytest.approx(r["F0_exact_N"], rel=5e-4)
            continue
        m = next(q for q in summary if q["form"] == "mean_cos" and all(q[k] == r[k] for k in ("pair", "geometry", "vstar", "model")))
        assert r["F0_model_N"] == pytest.approx(m["F0_model_N"], rel=1e-12)


@pytest.mark.parametrize("pair", mixedangles.PAIRS, ids=lambda p: p.name)
def test_solver_sphere_plane_tends_to_derjaguin(pair):
    # Exact F(0) of the mixed sphere-plane bridge -> 2 pi R1 gamma (cos theta1 + cos theta2) as
    # V* -> 0, from below; the deficit falls like V*^(1/4) (the filling angle), measured slope
    # 0.253 for both pairs between V* = 1e-7 and 1e-5.
    rows = mixedangles.derjaguin_limit(pairs=(pair,), vstars=(1e-7, 1e-5, 1e-3))
    t1, t2 = math.radians(pair.theta1_deg), math.radians(pair.theta2_deg)
    FD = 2 * math.pi * mixedangles.R1 * mixedangles.GAMMA * (math.cos(t1) + math.cos(t2))
    assert rows[0]["F0_derjaguin_N"] == pytest.approx(FD, rel=1e-14)
    deficits = [r["deficit"] for r in rows]
    assert all(d > 0 for d in deficits) and deficits[0] < deficits[1] < deficits[2]
    assert deficits[0] < 0.012  # within 1.2 % at V* = 1e-7 (measured 0.8 % glass-steel, 1.0 % POM-PVC)
    assert mixedangles.deficit_exponent(rows)[(pair.name, "sphere-wall")] == pytest.approx(0.25, abs=0.02)


def test_mean_angle_limit_error_is_the_cosine_ratio():
    # As V* -> 0 the equal-angle bridge of the mean angle overestimates F(0) by
    # cos(mean angle) / mean of cosines - 1 (+3.53 % glass-steel); the mean of cosines by ~0.
    p = mixedangles.PAIRS[0]
    t1, t2 = math.radians(p.theta1_deg), math.radians(p.theta2_deg)
    r1, r2, R = mixedangles.geometry("sphere-wall")
    V = 1e-6 * R ** 3
    F0 = mixedangles.exact_curve(r1, r2, V, t1, t2, [0.0])[0]
    err = {f: mixedangles.model_curve(EQ, f, r1, r2, V, t1, t2, np.array([0.0]))[0][0] / F0 - 1 for f in ("mean_cos", "mean_angle")}
    limit = math.cos((t1 + t2) / 2) / ((math.cos(t1) + math.cos(t2)) / 2) - 1
    assert limit == pytest.approx(0.0353, abs=1e-4)
    assert err["mean_angle"] == pytest.approx(limit, abs=1e-3)  # measured +3.57 %
    assert abs(err["mean_cos"]) < 1e-3  # measured -0.03 %


@pytest.mark.parametrize("model", ("young_laplace_table", EQ))
def test_exact_equivalent_angle_is_the_mean_of_cosines(comp, model):
    # The equal-angle exact bridge (solver or table) at acos(mean of cosines) is within 1 % of the
    # mixed bridge at contact in every case (measured <= 0.74 %); the mean angle overestimates by
    # 3.7-4.9 % (glass-steel) and 0.4-0.7 % (POM-PVC). Margins: 2.5 % and 0.2 %.
    _, rows = comp
    for r in rows_of(rows, model):
        cos_err, ang_err = abs(r["F0_rel_error_mean_cos"]), abs(r["F0_rel_error_mean_angle"])
        assert cos_err < 0.01, r
        assert ang_err - cos_err > (0.025 if r["pair"] == "glass-steel" else 0.002), r


@pytest.mark.parametrize("model", ("young_laplace_table", EQ, "willett_full"))
def test_mean_of_cosines_closer_over_the_gaps_glass_steel(comp, model):
    # Over the attached gaps the mean of cosines is closer for the exact-based models and Willett's
    # full fit, by >= 1.2 percentage points RMS in every glass-steel case (margin 0.5).
    _, rows = comp
    for r in rows_of(rows, model, "glass-steel"):
        assert r["rms_rel_error_attached_mean_cos"] < r["rms_rel_error_attached_mean_angle"] - 0.005, r


def test_forms_equivalent_for_pom_pvc(comp):
    # 40/50 deg: cos(45 deg) vs mean of cosines differ by 0.38 %; every model's RMS error moves by
    # less than 0.5 percentage points between the forms (measured <= 0.2).
    _, rows = comp
    for r in (r for r in rows if r["pair"] == "POM-PVC"):
        assert abs(r["rms_rel_error_mean_cos"] - r["rms_rel_error_mean_angle"]) < 0.005, r


@pytest.mark.parametrize("model", DERJAGUIN_SCALED)
def test_derjaguin_scaled_models(comp, model):
    # F(0) = 2 pi R gamma cos(theta_eff): with the mean of cosines it is Elskamp's eq. (14)/(15)
    # prefactor, pi R gamma (cos theta1 + cos theta2), exactly. The exact F(0) lies below it at
    # finite V*, so both forms overestimate and the mean angle more.
    summary, rows = comp
    for s in summary:
        if s["model"] == model and s["form"] == "mean_cos":
            assert s["F0_model_N"] == pytest.approx(s["F0_derjaguin_N"], rel=1e-12)
    for r in rows_of(rows, model):
        assert 0 < r["F0_rel_error_mean_cos"] < r["F0_rel_error_mean_angle"], r


@pytest.mark.parametrize("model", ("willett_reduced", "rabinovich_lambert"))
def test_fast_decaying_models_prefer_the_larger_force(comp, model):
    # Over the gaps these two fall off too fast (RMS 13-36 %); the larger cos(mean angle)
    # compensates a little: their RMS error is lower with the mean angle, by less than 3 points,
    # a fifth or less of the model's own error. Not an argument for the mean angle.
    _, rows = comp
    for r in rows_of(rows, model):
        gain = r["rms_rel_error_mean_cos"] - r["rms_rel_error_mean_angle"]
        assert 0 < gain < 0.03 and r["rms_rel_error_mean_cos"] > 5 * gain, r


def test_mixed_sphere_sphere_bridge_ruptures_earlier(comp):
    # Equal spheres, unequal angles: the exact bridge breaks before either equal-angle bridge
    # (measured: their rupture gaps are 17-38 % longer), so a rupture rule with one effective
    # angle overestimates the range of such bridges.
    _, rows = comp
    for r in rows_of(rows, EQ):
        if r["geometry"] == "sphere-sphere":
            assert r["rupture_rel_error_mean_cos"] > 0.1 and r["rupture_rel_error_mean_angle"] > 0.1, r


def test_run_writes_outputs(tmp_path):
    summary, derj, text = mixedangles.run(str(tmp_path), vstars=(1e-3,), n_gaps=5, derjaguin_vstars=(1e-3,))
    for name in ("summary.csv", "curves.csv", "comparison.csv", "derjaguin.csv", "mixed_angles.png"):
        assert os.path.getsize(os.path.join(tmp_path, name)) > 0, name
    with open(os.path.join(tmp_path, "summary.csv")) as f:
        header = next(csv.reader(f))
    assert {"vstar", "volume_m3", "gamma_N_m", "theta1_deg", "F0_exact_N", "rupture_exact_m", "rms_rel_error"} <= set(header)
    assert "young_laplace_equal" in text and len(derj) == 2
    assert {r["model"] for r in summary} == set(kernels.MODEL_NAMES) - {"linear_irreversible"} | {EQ}
