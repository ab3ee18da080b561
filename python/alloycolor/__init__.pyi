# Type stubs of the alloycolor package (python/alloycolor/__init__.py documents each call).
import os
from typing import Any, Callable, Iterable, Optional, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str
_Path = Union[str, os.PathLike]
_Progress = Optional[Callable[[str], None]]
_X = Union[float, str, npt.ArrayLike]

class Error(ValueError): ...

class MethodInfo(TypedDict):
    name: str
    summary: str
    auto_rank: int          # its place in auto's order; -1: not a candidate
    validate_default: bool  # validate runs it when no method is named
    options: list[str]      # the options it takes (fit's keywords)

class ColorResult(TypedDict):
    xyz: np.ndarray          # shape S + (3,), float64; a perfect reflector has Y = 1
    lab: np.ndarray          # CIELAB, the illuminant's white
    linear_srgb: np.ndarray  # IEC 61966-2-1 matrix, no chromatic adaptation
    srgb8: np.ndarray        # uint8, clamped and gamma-encoded
    paper_rgb: np.ndarray    # the paper's eq. 6 matrix
    sigma: Optional[np.ndarray]  # one-sigma CIEDE2000, shape S

def data_root() -> str: ...
def methods() -> list[MethodInfo]: ...
def illuminants() -> list[str]: ...

class Spectrum:
    source: str
    lambda_nm: np.ndarray
    n: np.ndarray
    k: np.ndarray
    warnings: list[str]
    @property
    def nk(self) -> np.ndarray: ...
    def color(self, angle_deg: npt.ArrayLike = ..., illuminant: Union[str, Sequence[str]] = ...,
              observer: npt.ArrayLike = ...) -> ColorResult: ...
    def render(self, shape: str = ..., size: int = ..., lighting: str = ..., roughness: float = ...,
               background: Optional[str] = ..., illuminant: str = ..., observer: int = ...,
               linear: bool = ..., direct: bool = ...) -> np.ndarray: ...
    def export(self, prefix: _Path, format: str = ..., scene_dir: Optional[_Path] = ...,
               roughness: float = ...) -> dict[str, Any]: ...

def read_nk(path: _Path, columns: Union[None, str, Sequence[Union[str, int]]] = ...) -> Spectrum: ...

class Dataset:
    def __init__(self, path_or_name: _Path) -> None: ...
    name: str
    system: str
    composition: str
    manifest_path: str
    warnings: list[str]
    precision: dict[str, float]
    x_atomic: np.ndarray
    samples: list[dict[str, Any]]
    excluded: list[dict[str, Any]]
    def without(self, x: Iterable[Union[float, str]]) -> Dataset: ...
    def select(self, x: Iterable[Union[float, str]]) -> Dataset: ...
    def fit(self, method: str = ..., **options: Any) -> Model: ...
    def __len__(self) -> int: ...

class Model:
    method: str
    system: str
    composition: str
    x_min: float
    x_max: float
    lambda_min_nm: float
    lambda_max_nm: float
    warnings: list[str]
    has_uncertainty: bool
    no_error_bar: str
    training_x: np.ndarray
    history: list[dict[str, Any]]
    suspect_samples: list[dict[str, Any]]
    excluded_samples: list[dict[str, Any]]
    parameter_curves: Optional[dict[str, Any]]
    def suggest(self, count: int = ..., rule: str = ..., illuminant: str = ...,
                observer: int = ...) -> list[dict[str, Any]]: ...
    def parse_composition(self, text: str) -> float: ...
    def nk(self, x: _X, lambda_nm: npt.ArrayLike) -> np.ndarray: ...
    def permittivity(self, x: _X, lambda_nm: npt.ArrayLike) -> np.ndarray: ...
    def color(self, x: _X, angle_deg: npt.ArrayLike = ..., illuminant: Union[str, Sequence[str]] = ...,
              observer: npt.ArrayLike = ..., sigma: bool = ..., exact: bool = ...) -> ColorResult: ...
    def match(self, lab: Optional[npt.ArrayLike] = ..., *, hex: Union[None, str, Sequence[str]] = ...,
              xyz: Optional[npt.ArrayLike] = ..., angle_deg: float = ..., illuminant: str = ...,
              observer: int = ..., target_sigma: float = ..., margin: float = ...,
              sigma: bool = ..., all_minima: bool = ...) -> dict[str, Any]: ...
    def tolerance(self, x: _X, de: float = ..., angles_deg: npt.ArrayLike = ...,
                  illuminants: Union[str, Sequence[str]] = ..., observer: int = ...) -> dict[str, np.ndarray]: ...
    def save(self, path: _Path) -> None: ...
    def to_json(self) -> dict[str, Any]: ...
    def render(self, x: Union[float, str], shape: str = ..., size: int = ..., lighting: str = ...,
               roughness: float = ..., background: Optional[str] = ..., illuminant: str = ...,
               observer: int = ..., linear: bool = ..., direct: bool = ...) -> np.ndarray: ...
    def export(self, x: Union[float, str], prefix: _Path, format: str = ...,
               scene_dir: Optional[_Path] = ..., roughness: float = ...) -> dict[str, Any]: ...
    def spectra(self, x: Union[float, str], material: Optional[str] = ...) -> dict[str, Any]: ...
    def write_spd(self, x: Union[float, str], eta_path: _Path, k_path: _Path,
                  material: Optional[str] = ...) -> None: ...
    def explore(self, path: _Path, data: Union[None, Dataset, _Path] = ...,
                illuminants: Union[str, Sequence[str]] = ..., observer: int = ...,
                roughness: npt.ArrayLike = ..., size: int = ..., tolerance: float = ...,
                threads: int = ...) -> dict[str, Any]: ...

def fit(dataset: Union[Dataset, _Path], method: str = ..., *,
        # options: generated from the registry by scripts/method_options.py; do not edit
        smoothing: Optional[float] = ...,
        space: Optional[str] = ...,
        lambda_from_nm: Optional[float] = ...,
        lambda_to_nm: Optional[float] = ...,
        lambda_step_nm: Optional[float] = ...,
        degree: Optional[int] = ...,
        terms: Optional[str] = ...,
        covariance: Optional[bool] = ...,
        # end of options
        lambda_range_nm: Optional[Sequence[float]] = ..., refit: Optional[Model] = ...,
        progress: _Progress = ...) -> Model: ...
def load_model(path: _Path) -> Model: ...
def color(source: Union[Model, Spectrum, _Path], x: Optional[_X] = ..., angle_deg: npt.ArrayLike = ...,
          illuminant: Union[str, Sequence[str]] = ..., observer: npt.ArrayLike = ...,
          sigma: bool = ..., exact: bool = ...) -> ColorResult: ...
def validate(dataset: Union[Dataset, _Path], methods: Union[str, Sequence[str]] = ...,
             holdout: Optional[Iterable[Union[float, str]]] = ..., angles_deg: npt.ArrayLike = ...,
             illuminant: str = ..., observer: int = ..., html: Optional[_Path] = ...,
             json: Optional[_Path] = ..., progress: _Progress = ...) -> dict[str, Any]: ...
