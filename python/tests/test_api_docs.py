"""docs/python.md documents every public name of the package, and each function heading
("### `saltus.f(a, b=None, ...)`") lists exactly the parameters of the function."""

import inspect
import re
from pathlib import Path

import saltus

DOC = (Path(__file__).resolve().parents[2] / "docs" / "python.md").read_text()


def test_every_public_name_is_in_the_python_page():
    missing = [n for n in saltus.__all__ if n != "__version__" and not re.search(rf"\b{re.escape(n)}\b", DOC)]
    assert not missing, f"docs/python.md does not name {missing}"


def test_function_headings_list_the_signature():
    headings = re.findall(r"^### `saltus\.(\w+)\(([^)]*)\)", DOC, flags=re.M)
    assert len(headings) >= 8, headings
    for name, params in headings:
        f = getattr(saltus, name)
        documented = [p.strip().split("=")[0].strip() for p in params.split(",") if p.strip() and p.strip() != "*"]
        actual = [p for p in inspect.signature(f).parameters if p != "self"]
        assert documented == actual, f"saltus.{name}: docs say {documented}, the function takes {actual}"
