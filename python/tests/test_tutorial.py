"""The Python session of docs/tutorial.md ("The same from Python") runs as it stands and
prints what the page shows: each `>>>` line is executed (doctest), in a scratch folder that
sees the repository's `cases/`, after the short DEM run of the tutorial's step 6 that
`saltus.diagnose` reads. A changed result or a changed signature therefore fails here until
the page follows it."""

import doctest
import re
import subprocess

from conftest import ROOT

TUTORIAL = ROOT / "docs" / "tutorial.md"


def python_session():
    """The fenced python blocks of the tutorial that hold `>>>` lines, joined."""
    blocks = re.findall(r"```python\n(.*?)```", TUTORIAL.read_text(), flags=re.S)
    session = "\n".join(b for b in blocks if ">>> " in b)
    assert session, "docs/tutorial.md has no python session with >>> lines"
    return session


def step6_dem_command():
    """The `saltus run` of step 6 as the page prints it (a shell block, lines joined at `\\`)."""
    text = TUTORIAL.read_text().replace("\\\n", " ")
    m = re.search(r"^saltus run cases/chassagne2023/case01\.toml (--set solver\.type=lagrangian.*?)$", text, flags=re.M)
    assert m, "docs/tutorial.md step 6 runs case 1 in the DEM"
    return ["run", "cases/chassagne2023/case01.toml", *m.group(1).split()]


def test_the_tutorials_python_session_prints_what_the_page_shows(cli_bin, tmp_path, monkeypatch):
    (tmp_path / "cases").symlink_to(ROOT / "cases")
    args = step6_dem_command()
    assert args[-2:] == ["--out", "out/case01_dem"], args
    p = subprocess.run([str(cli_bin), *args, "--quiet"], cwd=tmp_path, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    monkeypatch.chdir(tmp_path)
    parser = doctest.DocTestParser()
    test = parser.get_doctest(python_session(), {}, "docs/tutorial.md", str(TUTORIAL), 0)
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    report = []
    runner.run(test, out=report.append)
    assert runner.failures == 0 and runner.tries == len(test.examples) > 0, "".join(report)
