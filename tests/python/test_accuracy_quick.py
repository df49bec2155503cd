"""The model-accuracy benchmark in reduced form (correctness only, no timing assertions):
it runs end to end, writes its outputs, and the facts it reports hold on a small seeded grid."""
import csv
import math
import os

import pytest

from studies import accuracy
from yade_capillary import kernels

BUILD = os.environ.get("BUILD_DIR", os.path.join(os.path.dirname(__file__), "..", "..", "build"))


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("model_accuracy")
    summary, rupture_rows, cost_ns, md = accuracy.run(str(out), os.path.join(BUILD, "model_cost"), n_grid=6, min_time="0.001")
    return out, summary, rupture_rows, cost_ns, md


def test_outputs_written(quick_run):
    out, _, _, cost_ns, md = quick_run
    for name in ("errors.csv", "rupture.csv", "summary.csv", "costs.csv", "summary.md", "pareto.png"):
        assert os.path.getsize(os.path.join(out, name)) > 0, name
    assert set(cost_ns) == set(kernels.MODEL_NAMES) | {"young_laplace"}
    assert all(v > 0 and math.isfinite(v) for v in cost_ns.values())
    assert "| young_laplace_table |" in md


def test_table_model_within_target(quick_run):
    # Target: young_laplace_table within 0.5 % of the solver at every gap (exact rupture).
    _, summary, _, _, _ = quick_run
    worst = max(s["worst"] for s in summary if s["model"] == "young_laplace_table")
    assert worst < 5e-3


def test_errors_are_relative_to_the_solver(quick_run):
    # Each row's error is |F_model - F_exact| / F_exact with F_exact from the solver, recomputed here.
    out = quick_run[0]
    with open(os.path.join(out, "errors.csv")) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == (13 + 6) * len(kernels.MODEL_NAMES) * len(kernels.RUPTURE_NAMES) * len(accuracy.FRACTIONS)
    for r in rows[:: max(1, len(rows) // 50)]:
        c = next(p for p in accuracy.table1_points() + accuracy.grid_points(6) if p[0] == r["point"])
        exact = kernels.YoungLaplaceBridge(c[1], c[2], c[3], c[4])
        F = exact.solve(float(r["fraction"]) * exact.rupture_gap, accuracy.GAMMA)["force_neck"]
        assert float(r["F_exact_N"]) == pytest.approx(F, rel=1e-9)
        assert float(r["rel_error"]) == pytest.approx(abs(float(r["F_model_N"]) - F) / F, rel=1e-6, abs=1e-15)
