"""Shared fixtures: the repository root and the command-line program, for the identity
tests (Python == CLI)."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> Path:
    """The repository root (scenes are given relative to it)."""
    return ROOT


@pytest.fixture(scope="session")
def cli_bin() -> Path:
    """The `saltus` program: $SALTUS_BIN, else target/release/saltus. CI builds it before
    pytest runs, so there a missing program fails instead of skipping."""
    path = Path(os.environ.get("SALTUS_BIN", ROOT / "target" / "release" / "saltus"))
    if not path.is_file():
        message = f"{path} not found: cargo build --release (or set SALTUS_BIN)"
        if os.environ.get("CI"):
            pytest.fail(message)
        pytest.skip(message)
    return path


@pytest.fixture(scope="session")
def cli(cli_bin):
    """Run the program from the repository root: (exit code, stdout, stderr)."""

    def run(*args: str):
        p = subprocess.run([str(cli_bin), *args], cwd=ROOT, capture_output=True, text=True, timeout=300)
        return p.returncode, p.stdout, p.stderr

    return run


def cli_error(stderr: str) -> str:
    """The message the command line prints after `error: ` (to the end of stderr: after any
    warnings, and a message may hold several lines)."""
    text = "\n" + stderr
    i = text.rfind("\nerror: ")
    assert i >= 0, stderr
    return text[i + len("\nerror: ") :].rstrip("\n")
