"""The figures README.md and docs/python.md quote from a run of Chassagne case 1 are the
figures that run gives today (to 1e-12 relative: the last digits may move with the
platform's libm, not with the code)."""

import math
import re
from pathlib import Path

import saltus

ROOT = Path(__file__).resolve().parents[2]


def test_case01_figures_quoted_in_readme_and_python_page():
    r = saltus.run(ROOT / "cases/chassagne2023/case01.toml", out=False)
    readme = (ROOT / "README.md").read_text()
    quoted = re.search(r"# steady (\d\.\d+)", readme)
    assert quoted, "README.md quotes case 1's qs* after '# steady'"
    assert math.isclose(float(quoted.group(1)), r.summary["qs_star"], rel_tol=1e-12)
    page = (ROOT / "docs" / "python.md").read_text()
    pair = re.search(r"^\((\d\.\d+), (\d\.\d+)\)$", page, flags=re.M)
    assert pair, "docs/python.md quotes (qs_star, shields) of case 1"
    assert math.isclose(float(pair.group(1)), r.summary["qs_star"], rel_tol=1e-12)
    assert math.isclose(float(pair.group(2)), r.summary["shields"], rel_tol=1e-12)
    shown = re.search(r"steady at t=([\d.]+) s, qs\*=([\d.]+)", page)
    assert shown and shown.groups() == re.search(r"steady at t=([\d.]+) s, qs\*=([\d.]+)", repr(r)).groups()
