"""Type stubs of the Rust extension ``saltus._native`` (see ``saltus/__init__.py`` for the API)."""

from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Tuple, Union

import numpy as np

__version__: str

class SceneError(ValueError):
    file: Optional[str]
    key: Optional[str]

class RunError(RuntimeError):
    file: Optional[str]
    key: Optional[str]

_Overrides = Union[Mapping[str, Any], Iterable[str], None]

def check(scene: str, set: _Overrides = None, closures: Optional[str] = None) -> Tuple[Dict[str, Any], str]: ...
def run(
    scene: str,
    set: _Overrides = None,
    out: Optional[str] = None,
    quiet: bool = True,
    restart: Optional[str] = None,
    closures: Optional[str] = None,
    warm_start: Optional[str] = None,
) -> Dict[str, Any]: ...
def run_seeds(
    scene: str,
    seeds: int,
    set: _Overrides = None,
    out: Optional[str] = None,
    quiet: bool = True,
    closures: Optional[str] = None,
    warm_start: Optional[str] = None,
) -> Dict[str, Any]: ...
def diagnose(
    dir: str,
    closures: List[str],
    phi_min: float,
    fit: bool,
    z_min: Optional[float],
    z_max: Optional[float],
    out: Optional[str],
    pool: List[str],
) -> Dict[str, Any]: ...
def models(family: Optional[str] = None) -> List[Dict[str, Any]]: ...
def compare(file: str, set: _Overrides = None, out: Optional[str] = None) -> Dict[str, Any]: ...
def calibrate(file: str, set: _Overrides = None, out: Optional[str] = None, check: bool = False) -> Dict[str, Any]: ...

class Misfit:
    def __init__(self, file: str, set: _Overrides = None) -> None: ...
    @property
    def keys(self) -> List[str]: ...
    @property
    def bounds(self) -> List[Tuple[float, float]]: ...
    @property
    def start(self) -> List[float]: ...
    def anchor(self, params: List[float]) -> None: ...
    def chi2(self, params: List[float]) -> float: ...

def sweep_prepare(
    file: str, set: _Overrides, out: Optional[str], resume: bool
) -> Tuple[str, List[Dict[str, Any]]]: ...
def sweep_collect(file: str, set: _Overrides, out: str) -> Dict[str, Any]: ...

class Closure:
    def __init__(self, family: str, model: Union[Dict[str, Any], str]) -> None: ...
    @property
    def family(self) -> str: ...
    @property
    def name(self) -> str: ...
    @property
    def input_names(self) -> List[str]: ...
    @property
    def output_names(self) -> List[str]: ...
    def describe(self) -> Dict[str, Any]: ...
    def evaluate_arrays(self, inputs: Dict[str, np.ndarray], seed: int) -> Dict[str, np.ndarray]: ...

def register_closure(
    family: str,
    name: str,
    evaluate: Callable[..., Any],
    params: Optional[Dict[str, Any]],
    source: str,
    equation: str,
    limits: Optional[List[Any]],
    reynolds: str,
    depends_on_reynolds: bool,
) -> None: ...
def unregister_closure(family: str, name: str) -> bool: ...
def closure_check(family: str, model: Union[Dict[str, Any], str], cases: int = 256) -> Dict[str, Any]: ...

def register_faces(
    kind: str,
    name: str,
    functions: Dict[str, Any],
    params: Optional[Dict[str, Any]],
    source: str,
    equation: str,
    limits: Optional[List[Any]],
    options: Dict[str, Any],
) -> None: ...
def scene_modules(scene: Any, set: Any = ...) -> List[str]: ...
def cli_main(args: List[str]) -> int: ...
