"""docs/cases.md lists every file under cases/, and its tables are the ones docs/cases/generate
writes from the files' own headers. A new or changed file under cases/ therefore fails here
until `docs/cases/generate` has rewritten the page.

The listing is read the way tests/cases.rs reads it: the first cell of each table row names
files relative to `cases/` in backticks, a name without a folder being in the folder of the
name before it, a name ending in `/` covering its folder, and `...` between two names
covering the files of that folder between them in name order.
"""

import importlib.machinery
import importlib.util
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASES = ROOT / "cases"
PAGE = ROOT / "docs" / "cases.md"
GENERATOR = ROOT / "docs" / "cases" / "generate"


def generator_module():
    loader = importlib.machinery.SourceFileLoader("saltus_cases_generate", str(GENERATOR))
    spec = importlib.util.spec_from_loader(loader.name, loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def listed(text):
    """(files, folders, ranges) that the tables of the page name."""
    files, folders, ranges = [], [], []
    for line in text.splitlines():
        if not line.startswith("| `"):
            continue
        first = line.split("|")[1]
        folder, previous, in_range = "", None, False
        for i, part in enumerate(first.split("`")):
            if i % 2 == 0:
                in_range |= "..." in part
                continue
            if part.endswith("/"):
                folders.append(part)
                continue
            if "/" in part:
                folder = part.rsplit("/", 1)[0] + "/"
                full = part
            else:
                full = folder + part
            if in_range and previous is not None:
                ranges.append((previous, full))
                previous = None
            in_range = False
            files.append(full)
            previous = full
    return files, folders, ranges


def is_listed(rel, files, folders, ranges):
    parent = rel.rsplit("/", 1)[0]
    return (rel in files or any(rel.startswith(f) for f in folders)
            or any(a.rsplit("/", 1)[0] == parent and a <= rel <= b for a, b in ranges))


def test_every_file_under_cases_is_listed_in_the_cases_page():
    files, folders, ranges = listed(PAGE.read_text())
    every = sorted(p.relative_to(CASES).as_posix() for p in CASES.rglob("*") if p.is_file())
    assert every, "no files under cases/"
    missing = [rel for rel in every if not is_listed(rel, files, folders, ranges)]
    assert not missing, f"docs/cases.md does not list: {missing} (run docs/cases/generate)"


def test_the_cases_page_names_no_file_that_is_not_under_cases():
    files, folders, _ = listed(PAGE.read_text())
    gone = [f for f in files if not (CASES / f).is_file()] + [f for f in folders if not (CASES / f).is_dir()]
    assert not gone, f"docs/cases.md names files that are not under cases/: {gone}"


def test_the_cases_page_is_the_one_the_generator_writes():
    gen = generator_module()
    text = PAGE.read_text()
    block = gen.generated_block(text)
    assert block is not None, "docs/cases.md: no <!-- cases:files --> ... <!-- /cases --> block"
    assert text[block[0]:block[1]] == gen.render(), "docs/cases.md differs from the files under cases/ (run docs/cases/generate)"


def test_the_generator_check_passes():
    p = subprocess.run([sys.executable, str(GENERATOR), "--check"], cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stdout + p.stderr


def test_every_toml_file_of_the_case_tree_has_a_header_or_a_meta_description():
    gen = generator_module()
    run_folders = {p.parent for p in CASES.rglob("manifest.json")}
    for path in sorted(CASES.rglob("*.toml")):
        if any(f in path.parents for f in run_folders):
            continue
        row = gen.toml_row(path.relative_to(CASES).as_posix())
        assert row["what"], f"{path.relative_to(ROOT)}: no [meta] description and no leading # comment"
        assert gen.comment_header(path.read_text()), f"{path.relative_to(ROOT)}: no leading # comment"
