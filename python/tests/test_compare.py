"""saltus.compare: the comparison and work-precision tables of a compare file."""

import math
from pathlib import Path

import pytest

import saltus

ROOT = Path(__file__).resolve().parents[2]


def _compare_file(tmp_path, text):
    base = ROOT / "cases" / "chassagne2023" / "case01.toml"
    p = tmp_path / "cmp.toml"
    p.write_text(f"base = '{base}'\n{text}")
    return p


def test_precision_table_of_a_grid_study(tmp_path):
    # case 1 at 30, 60 and 120 cells against 480: phi converges at second order, so the
    # RMS phi error falls by more than 2 per doubling; the reference has no error
    text = "[reference]\nvariant = \"480\"\n" + "".join(
        f"[[variant]]\nname = \"{n}\"\nset = ['domain.cells={n}']\n" for n in (30, 60, 120, 480)
    )
    r = saltus.compare(_compare_file(tmp_path, text), out=tmp_path / "out")
    assert r.failures == 0
    assert r.table["variant"] == ["30", "60", "120", "480"]
    p = r.precision
    assert p is not None and p["variant"] == r.table["variant"]
    assert p["qs_star_error"][3] == 0.0 and p["rms_phi"][3] == 0.0
    for k in range(2):
        assert p["rms_phi"][k] / p["rms_phi"][k + 1] > 2.2, p["rms_phi"]
    assert all(c > 0 for c in p["cpu_time_s"])
    assert math.isnan(p["qs_star_stderr"][0])
    assert r.precision_figure is not None and r.precision_figure.is_file()


def test_without_reference_there_is_no_precision_table(tmp_path):
    r = saltus.compare(_compare_file(tmp_path, "[[variant]]\nname = \"as is\"\n"), out=tmp_path / "out")
    assert r.precision is None and r.table["variant"] == ["as is"]


def test_a_bad_reference_is_a_scene_error_naming_the_key(tmp_path):
    p = _compare_file(tmp_path, "[reference]\nvariant = \"b\"\n[[variant]]\nname = \"a\"\n")
    with pytest.raises(saltus.SceneError, match="reference.variant"):
        saltus.compare(p, out=tmp_path / "out")
