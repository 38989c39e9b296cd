"""Every figure that README.md and docs/ quote from a fast run is the figure of its results
file in docs/results/ (written by docs/results/regenerate from the release binary), and
every table the docs generate from a results file is the one the file gives. A changed
result therefore fails here until the file is regenerated and the text follows it.

The expected values are not copied into this test: they are read from the results files,
whose own check (`docs/results/regenerate --check` in .ci/run) runs the program again and
compares to a relative 1e-9. What is asserted here is the text: each quoted figure,
formatted as the page prints it, must appear on that page.
"""

import importlib.machinery
import importlib.util
import json
import pathlib
import re

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
RESULTS = ROOT / "docs" / "results"


def regenerate_module():
    path = RESULTS / "regenerate"
    loader = importlib.machinery.SourceFileLoader("saltus_results_regenerate", str(path))
    spec = importlib.util.spec_from_loader(loader.name, loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def results(name):
    return json.loads((RESULTS / f"{name}.json").read_text())["results"]


def sci(x, digits):
    """1 significant digit after the point, exponent without padding: 3.8e-5."""
    mantissa, exponent = f"{x:.{digits}e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def quotes():
    """(page, text) pairs: each text is a figure of a results file as the page prints it."""
    c1 = results("chassagne2023_case01")
    qs, diff, steps, t = c1["qs_star"], c1["difference_to_dem_percent"], c1["steps"], c1["sim_time_s"]
    rb = results("revil_baudard2015_sheet_flow")["kinetic theory + mixing length"]
    rouse = results("cheng_rouse_numbers")
    cal = results("chassagne2023_case14_calibration")
    n = cal["parameters"]["closures.granular.g0.exponent"]
    m0, m1 = cal["misfit_over_scatter"]["start"], cal["misfit_over_scatter"]["optimum"]
    stokes = results("stokes_layer")["max_phase_error_over_u0"]
    dem = results("chassagne2023_case01_dem_diagnose")
    return [
        ("README.md", f"| 2.337 | {qs:.3f} | +{diff:.1f} % (target 15 %, gated) |"),
        ("README.md", f"runs from a bed at rest to steady state in {steps} steps and 8.6 ms and gives qs* = {qs:.2f} against 2.34"),
        ("README.md", f"# {c1['ending']} {qs!r}"),
        ("README.md", f"| 0.86 | {rouse['dilute_muste_ns1']['rouse_number']:.3f} |"),
        ("README.md", f"| 0.049 m/s (peer two-fluid code) | {rb['aligned_rms_u_f']:.3f} m/s |"),
        ("README.md", f"{n['value']:.2f} -{n['profile_minus']:.2f} +{n['profile_plus']:.2f}; phi, u_p, qs* at "
                      f"{m1['phi']:.2f}, {m1['u_p']:.2f}, {m1['qs_star']:.2f}x the seed scatter "
                      f"({m0['phi']:.2f}, {m0['u_p']:.2f}, {m0['qs_star']:.2f}x before)"),
        ("docs/validation.md", f"| 2.337 | {qs:.3f} | +{diff:.1f} % (paper's target 15 %) | gated |"),
        ("docs/validation.md", f"| 0.86 | {rouse['dilute_muste_ns1']['rouse_number']:.3f} / "),
        ("docs/validation.md", f"| 1.44 | {rouse['dilute_kiger_pan']['rouse_number']:.3f} |"),
        ("docs/validation.md", f"{rb['aligned_rms_u_f']:.3f} m/s / {rb['aligned_rms_phi']:.4f}"),
        ("docs/validation/chassagne2023.md", f"| qs*, d/4 cells (120) | 2.337 | {qs:.3f} | +{diff:.1f} % |"),
        ("docs/validation/cheng.md", f"| Muste NS1 | 0.86 | {rouse['dilute_muste_ns1']['rouse_number']:.3f} ("),
        ("docs/performance.md", f"| `9266597` | 8.63 ms [8.47, 8.84] | {steps} | {t:.0f} s | {qs!r} |"),
        ("docs/performance.md", f"8.6 ms to steady state ({steps} steps, {t:.0f} s simulated)"),
        ("docs/performance.md", f"| 0.5 (default) | {steps} | {c1['rejected_steps']} | {qs!r} |"),
        ("docs/performance.md", f"qs* of case 1 is 2.531727275329304 against {qs!r}"),
        ("docs/tutorial.md", f"steady after {t:.6f} s simulated ({steps} steps, {c1['rejected_steps']} rejected)"),
        ("docs/tutorial.md", f"qs* = {qs:.4f} (qs = "),
        ("docs/tutorial.md", f"qs* = {qs:.2f} is +{diff:.1f} % on the coupled fluid-DEM's 2.337"),
        ("docs/tutorial.md", f"point_0002  theta = 0.6  done         qs* = {qs:.6f}"),
        ("docs/tutorial.md", f"proposed               eulerian   {qs:.4f}"),
        ("docs/tutorial.md", f"closures.granular.g0.a = {cal['parameters']['closures.granular.g0.a']['value']:.6f} +- "),
        ("docs/tutorial.md", f"closures.granular.g0.exponent = {n['value']:.6f} +- {sci(n['stderr'], 2)}"),
        ("docs/tutorial.md", f'`"qs_star": {qs!r}`'),
        ("docs/tutorial.md", f'`"steps": {steps}`'),
        ("docs/tutorial.md", f"\nsteady {qs!r} {steps}\n" if c1["ending"] == "steady" else c1["ending"]),
        ("docs/tutorial.md", f"(qs* {dem['run']['qs_star']:.3f} at the end, against 2.4 at"),
        ("docs/verification.md", f"| as shipped: exact solution at t = 0, T/1000 | {sci(stokes, 1)} |"),
    ]


@pytest.mark.parametrize("page,text", quotes(), ids=lambda v: v if len(v) < 40 else v[:40])
def test_each_quoted_figure_is_its_results_file(page, text):
    body = (ROOT / page).read_text()
    # a figure may be wrapped onto the next line: compare with runs of white space as one
    flat = lambda s: re.sub(r"\s+", " ", s)
    assert flat(text) in flat(body), f"{page} does not quote {text!r} (docs/results/regenerate, then the text)"


def test_every_generated_table_is_the_one_its_file_gives():
    reg = regenerate_module()
    for name, (page, render) in reg.TABLES.items():
        text = (ROOT / page).read_text()
        block = reg.generated_block(text, name)
        assert block is not None, f"{page}: no <!-- results:{name} --> block"
        doc = json.loads((RESULTS / f"{name}.json").read_text())
        assert text[block[0]:block[1]] == render(doc), f"{page}: table of {name} differs from its results file"


def test_every_results_file_is_stamped_and_regenerated_by_the_script():
    reg = regenerate_module()
    files = sorted(p.stem for p in RESULTS.glob("*.json") if p.stem != "slow")
    assert files == sorted(reg.FAST), (files, sorted(reg.FAST))
    for name in files:
        doc = json.loads((RESULTS / f"{name}.json").read_text())
        assert doc["name"] == name and doc["results"] and doc["command"].startswith("saltus ")
        s = doc["stamp"]
        assert re.fullmatch(r"[0-9a-f]{7,40}(\+changes)?", s["commit"]), s
        assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", s["date"]), s
        assert s["host"], s


def test_the_slow_results_name_their_commands():
    slow = json.loads((RESULTS / "slow.json").read_text())
    assert slow["figures"]
    for f in slow["figures"]:
        assert f["figure"] and f["value"] and f["command"] and f["measured"] and f["quoted_in"], f
        for page in f["quoted_in"]:
            assert (ROOT / page).exists(), page


# superseded figures of case 1 and case MB that the pages once quoted
SUPERSEDED = [
    "2.531727575827865",
    "2.5317276754350617",
    "2.5317277 after",
    "(504 steps",
    "(506 steps",
    "504 steps, 120 cells",
    "in about 13 ms",
    "| 13 ms |",
    "90 s averaged over 45-90 s",
    "qs* identical bit for bit",
]


def test_no_page_quotes_a_superseded_figure():
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    found = [(p.relative_to(ROOT), s) for p in pages for s in SUPERSEDED if s in p.read_text()]
    assert not found, found
