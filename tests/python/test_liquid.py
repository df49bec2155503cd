"""The plain-Python parts of yade_capillary.liquid: the VTK files ParaView reads (legacy ASCII
polydata: counts, connectivity and field values as written) and the CSV round trip of a migration
time series."""
import math

import pytest

from yade_capillary import liquid


def _tokens(path):
    with open(path) as f:
        return f.read().split()


def test_vtk_points(tmp_path):
    path = str(tmp_path / "p.vtk")
    liquid.write_vtk_points(path, [(0, 0, 0), (1e-3, 2e-3, 3e-3)], {"radius_m": [1e-3, 2e-3], "film_m3": [0.0, 4.5e-11]})
    t = _tokens(path)
    assert t[t.index("POINTS") + 1] == "2"
    assert [float(x) for x in t[t.index("POINTS") + 3:t.index("POINTS") + 9]] == [0, 0, 0, 1e-3, 2e-3, 3e-3]
    assert t[t.index("VERTICES") + 1:t.index("VERTICES") + 7] == ["2", "4", "1", "0", "1", "1"]
    i = t.index("film_m3")
    assert [float(x) for x in t[i + 5:i + 7]] == [0.0, 4.5e-11]


def test_vtk_lines(tmp_path):
    path = str(tmp_path / "b.vtk")
    liquid.write_vtk_lines(path, [((0, 0, 0), (1, 0, 0)), ((0, 1, 0), (0, 2, 0))], {"volume_m3": [1e-12, 2e-12]})
    t = _tokens(path)
    assert t[t.index("POINTS") + 1] == "4"
    assert t[t.index("LINES") + 1:t.index("LINES") + 9] == ["2", "6", "2", "0", "1", "2", "2", "3"]
    assert t[t.index("CELL_DATA") + 1] == "2"
    i = t.index("volume_m3")
    assert [float(x) for x in t[i + 5:i + 7]] == [1e-12, 2e-12]


def test_vtk_field_length_checked(tmp_path):
    with pytest.raises(ValueError, match="'film_m3' has 1 values for 2 items"):
        liquid.write_vtk_points(str(tmp_path / "p.vtk"), [(0, 0, 0), (1, 1, 1)], {"film_m3": [1.0]})


def test_csv_round_trip(tmp_path):
    row = {k: 0.0 for k in liquid.MIGRATION_COLUMNS}
    row.update(t_s=0.05, films_m3=3.1e-9, drift_rel=-1.3e-16, n_bridges=42, dry_mean_carried_m3=math.pi * 1e-13)
    path = str(tmp_path / "m.csv")
    liquid.write_csv([row, row], path)
    back = liquid.read_csv(path)
    assert len(back) == 2 and back[1]["dry_mean_carried_m3"] == math.pi * 1e-13 and back[0]["n_bridges"] == 42
