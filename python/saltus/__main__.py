"""``python -m saltus ARGS``: the ``saltus`` command line, run in this Python process
after importing the ``[python] modules`` of the scene it is given, so that a scene naming
closures written in Python runs, checks and compares as any other (``python -m saltus run
SCENE``, ``check SCENE``, ``compare FILE``: the scene of ``run`` and ``check``, the
``base`` scene of a compare file, with the ``--set`` overrides). Every other command is
passed on unchanged. The exit code is the program's."""

import sys
from pathlib import Path
from typing import List, Optional

from . import _native
from ._run import import_modules


def _scene_and_overrides(args: List[str]) -> "tuple[Optional[str], List[str]]":
    # the first positional argument after the command, and every --set value
    scene, overrides, i = None, [], 1
    while i < len(args):
        a = args[i]
        if a == "--set" and i + 1 < len(args):
            overrides.append(args[i + 1])
            i += 2
            continue
        if a.startswith("--set="):
            overrides.append(a[len("--set=") :])
        elif a in ("--out", "--restart", "--max-wall", "--log-interval") and i + 1 < len(args):
            i += 2
            continue
        elif not a.startswith("-") and scene is None:
            scene = a
        i += 1
    return scene, overrides


def _compare_base(path: str) -> Optional[str]:
    # the `base` scene of a compare file, relative to it
    try:
        import tomllib  # Python >= 3.11
    except ImportError:  # pragma: no cover - older Pythons read no compare file here
        return None
    try:
        with open(path, "rb") as f:
            base = tomllib.load(f).get("base")
    except (OSError, ValueError):
        return None  # the program itself reports the file's error
    return None if not isinstance(base, str) else str(Path(path).parent / base)


def main(argv: Optional[List[str]] = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    if args and args[0] in ("run", "check", "compare"):
        scene, overrides = _scene_and_overrides(args)
        if scene is not None and args[0] == "compare":
            scene = _compare_base(scene)
        if scene is not None and Path(scene).is_file():
            try:
                import_modules(_native.scene_modules(scene, overrides))
            except _native.SceneError:
                pass  # the program reports the scene's error, as the saltus binary does
    return _native.cli_main(["saltus", *args])


if __name__ == "__main__":
    sys.exit(main())
