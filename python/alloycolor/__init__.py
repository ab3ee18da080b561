"""alloycolor: optical constants, reflectance and colour of binary metal alloys.

Predicts n + ik, the Fresnel reflectance and the CIE colour of a binary alloy at any
composition from measurements at a few compositions, with the same C++ libraries as the
``alloycolor`` program (Kuboshima & Furukawa's chain: n, k -> permittivity -> Drude model
-> Fresnel reflectance, eq. 2-4 -> CIE XYZ, eq. 5 -> CIELAB, sRGB per IEC 61966-2-1).

    >>> import alloycolor as ac
    >>> data = ac.Dataset("Au-Ag")                      # a bundled data set, or a folder
    >>> model = ac.fit(data, "smooth")                  # methods: ac.methods()
    >>> model.nk([0.5, 0.75], [400.0, 550.0, 700.0])    # complex array, shape (2, 3)
    >>> ac.color(model, x=np.linspace(0, 1, 11))["srgb8"]

Units live in the names: ``x`` is the atomic fraction of the system's first element (strings
such as ``"75wt%"`` or ``"18k"`` are parsed by ``model.parse_composition``), ``lambda_nm``
in nanometres, ``angle_deg`` the angle of incidence in degrees. Bad input raises
:class:`alloycolor.Error` (a ``ValueError``) with the library's one-line message naming the
file, field or value at fault. Long work runs without the GIL, and Ctrl-C stops it at its next
step with KeyboardInterrupt, nothing written; ``progress`` callbacks receive one-line
messages, and an exception raised in one stops the work and propagates.
"""

from __future__ import annotations

import os
import pathlib
from typing import Callable, Iterable, Optional, Sequence, Union

import numpy as np

from . import _alloycolor as _core
from . import _paths
from ._alloycolor import Error, illuminants
from ._args import (_broadcast_x, _callable, _columns_text, _export_args, _flag, _observer, _output_guard, _path, _real, _real_array, _render_args, _setting,
                    _text, _texts, _whole)
from ._options import fit_doc as _fit_doc, fit_options as _fit_options
from ._options import fit_signature as _fit_signature

__version__ = _paths.VERSION
__all__ = [
    "Error", "Dataset", "Model", "Spectrum", "color", "data_root", "fit", "illuminants",
    "load_model", "methods", "read_nk", "validate",
]


def _find_data_root() -> str:
    env = os.environ.get("ALLOYCOLOR_DATA_DIR")
    if env:
        return env
    installed = (pathlib.Path(__file__).resolve().parent / _paths.INSTALLED_DATA_RELPATH)
    if (installed / "cie").is_dir():
        return str(installed.resolve())
    return _paths.SOURCE_DATA_DIR


_core._set_data_root(_find_data_root())


def data_root() -> str:
    """The folder holding the bundled data sets and the CIE tables: $ALLOYCOLOR_DATA_DIR,
    else share/alloycolor/data of the installation, else the source tree's data/."""
    return _core._data_root()


def methods() -> list:
    """The model methods of the registry: [{"name", "summary", "auto_rank" (its place in
    auto's order, -1: not a candidate), "validate_default" (validate runs it by default),
    "options" (the names of the options it takes: see :func:`fit`)}]."""
    return _core.methods()


class Spectrum:
    """Measured optical constants: ``lambda_nm`` (increasing), ``n``, ``k`` as numpy arrays
    and ``nk = n + ik``; ``source`` names the file, ``warnings`` what the reader noticed."""

    def __init__(self, core, warnings=()):
        self._core = core
        self.source: str = core.source
        self.lambda_nm: np.ndarray = core.lambda_nm
        self.n: np.ndarray = core.n
        self.k: np.ndarray = core.k
        self.warnings: list = list(warnings)

    @property
    def nk(self) -> np.ndarray:
        return self.n + 1j * self.k

    def color(self, angle_deg=0.0, illuminant="D65", observer=2) -> dict:
        """Colour of the polished metal; see :func:`alloycolor.color`."""
        return color(self, angle_deg=angle_deg, illuminant=illuminant, observer=observer)

    def render(self, shape="sphere", size=256, lighting="studio", roughness=0.0,
               background=None, illuminant="D65", observer=2, linear=False,
               direct=False) -> np.ndarray:
        """An image of a solid of the measured metal; see :meth:`Model.render`."""
        return self._core._render(*_render_args(shape, size, lighting, roughness, background,
                                                illuminant, observer, direct, linear))

    def export(self, prefix: Union[str, os.PathLike], format: str = "all",
               scene_dir: Union[None, str, os.PathLike] = None, roughness: float = 0.0) -> dict:
        """Writes exactly the files ``alloycolor export --nk FILE`` writes; see
        :meth:`Model.export`."""
        return self._core._export(*_export_args(prefix, format, scene_dir, roughness),
                                  _output_guard(self))

    def _note_inputs(self, guard) -> None:
        guard.note(self.source)

    def __repr__(self):
        return "Spectrum(%r, %d wavelengths, %g-%g nm)" % (
            self.source, len(self.lambda_nm), self.lambda_nm[0], self.lambda_nm[-1])


def read_nk(path: Union[str, os.PathLike], columns=None) -> Spectrum:
    """Reads optical constants: refractiveindex.info YAML or a delimited lab export (CSV,
    TSV, whitespace; wavelength, energy or wavenumber; n, k or eps1, eps2). ``columns``
    chooses one n,k pair of a multi-sample file: ``"n6,k6"``, ``("n6", "k6")`` or 1-based
    ``(2, 3)``. Raises Error naming the file and line on bad input."""
    core, warnings = _core._read_nk(_path("path", path), _columns_text(columns))
    return Spectrum(core, warnings)


class Dataset:
    """An alloy system and its samples: a folder with a ``dataset.json``, the manifest
    itself, or a bundled set's name (``"Au-Ag"``, ``"Cu-Zn"``, ``"Nb-Sn"``)."""

    def __init__(self, path_or_name: Union[str, os.PathLike, None] = None, *, _core_set=None,
                 _read=None):
        if _core_set is None:
            arg = _path("path_or_name", path_or_name)
            self._given = arg  # as `alloycolor --data` would be given it
            bundled = pathlib.Path(data_root()) / arg
            if not os.path.exists(arg) and arg and not os.path.isabs(arg) and bundled.exists():
                arg = str(bundled)
            _core_set = _core._Dataset(arg)
        else:
            self._given = _core_set.manifest_path
        self._core = _core_set
        # The set as read from its files (select and without keep it): all of them inputs.
        self._read = _core_set if _read is None else _read

    name = property(lambda self: self._core.name)
    system = property(lambda self: self._core.system, doc='"Au-Ag": elements a and b')
    composition = property(lambda self: self._core.composition)
    manifest_path = property(lambda self: self._core.manifest_path)
    warnings = property(lambda self: list(self._core.warnings))
    precision = property(lambda self: dict(self._core.precision),
                         doc='{"n", "k"}: the standard deviations the manifest states for a '
                             'measured n and k (0 where not stated; a manifest stating none '
                             "takes 0.01 each, a typical measurement's, as the error bars' "
                             "floor)")
    x_atomic = property(lambda self: self._core.x_atomic,
                        doc="samples' compositions, sorted (repeated for replicates)")
    excluded = property(lambda self: [dict(s, spectrum=Spectrum(s["spectrum"]))
                                      for s in self._core.excluded],
                        doc='the samples the manifest sets aside ("exclude"): as samples, '
                            'with "excluded", the reason')

    @property
    def samples(self) -> list:
        """[{"x_atomic", "x_given", "file", "path", "spectrum": Spectrum}, ...]"""
        out = []
        for s in self._core.samples:
            s = dict(s)
            s["spectrum"] = Spectrum(s["spectrum"])
            out.append(s)
        return out

    def _match(self, x) -> float:
        value = self._core.parse_composition(x) if isinstance(x, str) else _real("x", x)
        known = self._core.sample_x(value)
        if known is not None:
            return known
        raise Error("%s has no sample at x = %s (samples at %s)" % (
            self.manifest_path, x, ", ".join("%g" % v for v in self.x_atomic)))

    def without(self, x: Iterable) -> "Dataset":
        """The data set without the samples at compositions x (every replicate there): each a
        sample's atomic fraction, the number its manifest gives it, or a string such as "85wt%"."""
        return Dataset(_core_set=self._core.without([self._match(v) for v in x]),
                       _read=self._read)

    def select(self, x: Iterable) -> "Dataset":
        """The data set with only the samples at compositions x (as in :meth:`without`)."""
        keep = [self._match(v) for v in x]
        drop = [v for v in self.x_atomic if all(abs(v - k) > 1e-9 for k in keep)]
        return Dataset(_core_set=self._core.without(drop), _read=self._read)

    def fit(self, method: str = "auto", **options) -> "Model":
        """Fits a model; see :func:`alloycolor.fit`."""
        return fit(self, method, **options)

    def _note_inputs(self, guard) -> None:
        guard.note_dataset(self._read)

    def __len__(self):
        return len(self.x_atomic)

    def __repr__(self):
        return "Dataset(%r, %s, %d samples)" % (self.name, self.system, len(self))


class Model:
    """A fitted or loaded model of permittivity eps(lambda, x). Evaluate with :meth:`nk`,
    :meth:`permittivity` and :meth:`color`; save with :meth:`save`."""

    def __init__(self, core, origin: str = "built in Python", source: str = "built in Python",
                 data: Optional["Dataset"] = None, inputs: tuple = ()):
        self._core = core
        self._origin = origin  # how export describes the model: "from m.json", ...
        self._source = source  # how the explorer page names it, as `alloycolor explore`
        self._data = data      # the data set it was fitted to (explore draws its spectra)
        # What it was made from, which no output may replace: the file it was loaded from,
        # or the data set it was fitted to and the model it refitted.
        self._inputs = inputs

    def _note_inputs(self, guard) -> None:
        for source in self._inputs:
            _output_guard(source, guard=guard)

    method = property(lambda self: self._core.method)
    system = property(lambda self: self._core.system)
    composition = property(lambda self: self._core.composition)
    x_min = property(lambda self: self._core.x_min)
    x_max = property(lambda self: self._core.x_max)
    lambda_min_nm = property(lambda self: self._core.lambda_min_nm)
    lambda_max_nm = property(lambda self: self._core.lambda_max_nm)
    warnings = property(lambda self: list(self._core.warnings))
    has_uncertainty = property(lambda self: self._core.has_uncertainty)
    no_error_bar = property(lambda self: self._core.no_error_bar,
                            doc='why the model has no error bar ("no error bar: 2 '
                                'compositions ..."); "" where it has one')
    training_x = property(lambda self: self._core.training_x)
    history = property(lambda self: self.to_json().get("history", []),
                       doc="the model's lineage, oldest first: one dict per fit (date, method, "
                           "the samples added, with the previous model's delta_e00, "
                           "sigma_de00 and verdict there, removed and changed); "
                           "docs/model-format.md")
    suspect_samples = property(
        lambda self: self.to_json()["fit"].get("suspect_samples", []),
        doc="the samples the fit found out of line with the rest of the series: dicts with "
            "file, x, check, figure, reason")
    excluded_samples = property(
        lambda self: self.to_json().get("excluded_samples", []),
        doc="the samples the manifest set aside, each with its reason and the model's "
            "delta_e00 and sigma_de00 on it (held out)")
    parameter_curves = property(
        lambda self: self.to_json()["parameters"].get("curves"),
        doc="tau(x), m*(x), plasma energy and damping with their one-sigma, as "
            "``alloycolor params --format json`` (None for a model file written before)")

    def suggest(self, count: int = 1, rule: str = "largest-sigma", illuminant: str = "D65",
                observer: int = 2) -> list:
        """Where to measure next, as ``alloycolor suggest --json``: ``count`` compositions
        (1-20) chosen jointly where a new sample would remove the most of the one-sigma
        (rule "largest-sigma"; "widest-gap": the middle of the widest gap, also for a model
        without error bars), each a dict with "x" (atomic fraction), "x_given" (the data
        set's units), "sigma_de00" (the one-sigma there now, as :meth:`color` gives it),
        "max_sigma_before"/"max_sigma_after" and "mean_sigma_before"/"mean_sigma_after" over
        the composition range, and "rule"."""
        return self._core._suggest(int(_setting("count", count)), _text("rule", rule),
                                   _text("illuminant", illuminant),
                                   _observer("observer", observer))

    def parse_composition(self, text: str) -> float:
        """x_atomic from "0.75", "75at%", "75wt%" or "18k" (gold alloys)."""
        return self._core.parse_composition(_text("text", text))

    def _optics(self, x, lambda_nm, index: bool) -> np.ndarray:
        xs = _broadcast_x(self, x)
        lam = _real_array("lambda_nm", lambda_nm)
        out = self._core._optics(xs.ravel(), lam.ravel(), index)
        return out.reshape(xs.shape + lam.shape)

    def nk(self, x, lambda_nm) -> np.ndarray:
        """Complex index N = n + ik (eq. 13, 14, n, k >= 0); shape x.shape + lambda_nm.shape."""
        return self._optics(x, lambda_nm, True)

    def permittivity(self, x, lambda_nm) -> np.ndarray:
        """Complex permittivity eps1 + i eps2; shape x.shape + lambda_nm.shape."""
        return self._optics(x, lambda_nm, False)

    def color(self, x, angle_deg=0.0, illuminant="D65", observer=2, sigma=False,
              exact=False) -> dict:
        """Colour at compositions x; see :func:`alloycolor.color`."""
        return color(self, x, angle_deg=angle_deg, illuminant=illuminant, observer=observer,
                     sigma=sigma, exact=exact)

    def match(self, lab=None, *, hex=None, xyz=None, angle_deg=0.0, illuminant="D65",
              observer=2, target_sigma=0.0, margin=1.0, sigma=True,
              all_minima=False) -> dict:
        """The composition whose colour is closest to each target (color/match.h): targets
        as CIELAB ``lab`` (shape S + (3,), e.g. (N, 3)), ``xyz`` (S + (3,), a perfect
        reflector has Y = 1) or ``hex`` ("#rrggbb" or a sequence of them, sRGB), under
        ``illuminant`` and ``observer``, seen at ``angle_deg``. Returns arrays of shape S:
        "x" (atomic fraction), "x_sigma" (its one-sigma: the model's colour uncertainty and
        ``target_sigma`` (CIEDE2000) over the rate colour changes with composition; NaN
        when neither is known), "de00" (CIEDE2000 left), "reachable" (de00 <= 1),
        "n_minima" (local minima within ``margin`` dE00 of the best); "lab" (S + (3,), the
        model's colour at x); with ``all_minima``, "matches": per target (flattened) a list
        of {"x_atomic", "x_sigma", "de00"} sorted by de00. ``sigma=False`` skips the
        uncertainty draws (much faster for many targets). Raises Error on bad input."""
        given = [v is not None for v in (lab, hex, xyz)]
        if sum(given) != 1:
            raise Error("match: give exactly one of lab, hex or xyz")
        settings = (_real("angle_deg", angle_deg), _text("illuminant", illuminant),
                    _observer("observer", observer), _setting("target_sigma", target_sigma),
                    _setting("margin", margin), _flag("sigma", sigma),
                    _flag("all_minima", all_minima))
        colorimeter = settings[1:3]
        if hex is not None:
            texts = np.asarray(hex, dtype=object)
            flat = [_core._lab_from_hex(_text("hex", t), *colorimeter) for t in texts.ravel()]
            targets = np.asarray(flat, dtype=float).reshape(texts.shape + (3,))
        else:
            name = "lab" if lab is not None else "xyz"
            targets = _real_array(name, lab if lab is not None else xyz)
            if targets.ndim == 0 or targets.shape[-1] != 3:
                raise Error("%s: targets must have shape (..., 3), not %s" % (name,
                                                                              targets.shape))
            if xyz is not None:
                flat = [_core._lab_from_xyz(float(t[0]), float(t[1]), float(t[2]), *colorimeter)
                        for t in targets.reshape(-1, 3)]
                targets = np.asarray(flat, dtype=float).reshape(targets.shape)
        shape = targets.shape[:-1]
        target = "lab" if lab is not None else "xyz" if xyz is not None else "hex"
        out = self._core._match(targets.reshape(-1, 3), target, *settings)
        for key in ("x", "x_sigma", "de00", "reachable", "n_minima"):
            out[key] = out[key].reshape(shape)
        out["lab"] = out["lab"].reshape(shape + (3,))
        return out

    def tolerance(self, x, de=1.0, angles_deg=(0.0,), illuminants=("D65",),
                  observer=2) -> dict:
        """The composition window around each x (array or "18k"-style text) within which the
        colour stays within ``de`` (CIEDE2000) of its own at every angle and illuminant
        given (color/match.h). Returns arrays of x's shape: "x_low", "x_high" (atomic
        fraction), "clipped_low", "clipped_high" (the window reaches the model's range) and
        "de00_per_at_percent" (the fastest rate of colour change at x)."""
        xs = _broadcast_x(self, x)
        angles = [float(a) for a in np.atleast_1d(_real_array("angles_deg", angles_deg))]
        out = self._core._tolerance(xs.ravel(), _setting("de", de), angles,
                                    _texts("illuminants", illuminants),
                                    _observer("observer", observer))
        return {key: value.reshape(xs.shape) for key, value in out.items()}

    def save(self, path: Union[str, os.PathLike]) -> None:
        """Writes the versioned JSON model file (atomically: all or nothing). Refuses to
        replace one of the model's inputs (the file it was loaded from, its data set's files,
        the model it refitted), as ``alloycolor fit`` refuses ``--out`` there."""
        self._core._save(_path("path", path), _output_guard(self))

    def to_json(self) -> dict:
        """The model file's content as Python objects."""
        return self._core.to_json()

    def render(self, x, shape="sphere", size=256, lighting="studio", roughness=0.0,
               background=None, illuminant="D65", observer=2, linear=False,
               direct=False) -> np.ndarray:
        """An image of a solid of the alloy at x, as ``alloycolor render`` draws one tile:
        (size, size, 4), a sphere or ring (``shape``) in "studio" or "uniform" ``lighting``,
        GGX ``roughness`` 0-1, a "backdrop" or "transparent" ``background`` (default: as the
        program, transparent in uniform light, else the backdrop); uint8 sRGBA, or
        float32 linear sRGB with alpha when ``linear``. Shaded from the table of XYZ against
        cos(angle) checked against direct spectral evaluation (Error when no table is
        accurate enough, as the program refuses), or with ``direct`` from the spectral
        Fresnel reflectance at every pixel (slow; roughness 0 only)."""
        xv = float(_broadcast_x(self, x))
        return self._core._render(xv, *_render_args(shape, size, lighting, roughness,
                                                    background, illuminant, observer, direct,
                                                    linear))

    def spectra(self, x, material: Optional[str] = None) -> dict:
        """n, k on the export grid (360-830 nm, 5 nm): {"lambda_nm", "n", "k", "notes"}."""
        xv = float(_broadcast_x(self, x))
        return self._core._spectra(xv, self._material(xv) if material is None
                                   else _text("material", material))

    def write_spd(self, x, eta_path, k_path, material: Optional[str] = None) -> None:
        """Writes the eta and k .spd files (wavelength_nm value) pbrt-v4 and Mitsuba 3 read."""
        xv = float(_broadcast_x(self, x))
        self._core._write_spd(xv, self._material(xv) if material is None
                              else _text("material", material), _path("eta_path", eta_path),
                              _path("k_path", k_path), _output_guard(self))

    def export(self, x, prefix: Union[str, os.PathLike], format: str = "all",
               scene_dir: Union[None, str, os.PathLike] = None, roughness: float = 0.0) -> dict:
        """Writes exactly the files ``alloycolor export --x X --out PREFIX`` writes, as a set
        (all or none replaced): ``format`` "spd" (PREFIX.eta.spd, .k.spd, .pbrt, .xml),
        "rgb-conductor" (.rgb.xml, .blender.py), "f82" (.f82.json), "gulbrandsen"
        (.gulbrandsen.json), "materialx" (.mtlx), "gltf" (.gltf), "all" or
        "blender-table" (.alloy-table.png and .json over the model's whole range, ``x``
        ignored: the Blender add-on's table, docs/blender.md); ``scene_dir``:
        name the .spd files relative to that folder (spd); ``roughness`` in [0, 1]
        (materialx, gltf). The files describe the model by where it came from
        (``load_model``'s path, ``fit``'s data set). Returns ``--json``'s document: every
        fitted number and error, "format", "files" (the paths written) and "notes"."""
        xv = float(_broadcast_x(self, x))
        return self._core._export(xv, self._origin, *_export_args(prefix, format, scene_dir,
                                                                  roughness),
                                  _output_guard(self))

    def explore(self, path: Union[str, os.PathLike], data: Union[None, "Dataset", str] = None,
                illuminants: Union[str, Sequence[str]] = ("A", "D50", "D65"), observer: int = 2,
                roughness=(0.0, 0.2), size: int = 320, tolerance: float = 0.02,
                threads: int = 0) -> dict:
        """Writes the explorer page (atomically), as ``alloycolor explore`` does: the same
        bytes for the same model and options (docs/explorer.md). ``data``: the data set whose
        measured spectra the page draws (default: the one a model from :func:`fit` was
        fitted to, as ``alloycolor explore --data``; a loaded model draws the spectra its
        file keeps, or itself at its training compositions); ``illuminants`` offered by
        the page's selector, one ``observer``; ``roughness``: the finishes (GGX alpha 0-1,
        0 always offered); ``size``: pixels of each picture (64-1024); ``tolerance``: the
        tables' largest CIEDE2000; ``threads``: 0 for all. Returns what the tables
        measured: "compositions", "angles", "illuminants", "finishes", "check_points",
        "max_de00", "max_srgb8_difference", "tolerance_met" and the page's "bytes"."""
        if data is None:
            data = self._data
        elif not isinstance(data, Dataset):
            data = Dataset(data)
        names = _texts("illuminants", illuminants)
        rough = [_real("roughness", r) for r in np.atleast_1d(_real_array("roughness", roughness))]
        return self._core._explore(
            _path("path", path), names, _observer("observer", observer), rough,
            _whole("size", size), _real("tolerance", tolerance), _whole("threads", threads),
            self._source,
            None if data is None else data._core, "" if data is None else data._given,
            _output_guard(self, data))

    def _material(self, x: float) -> str:
        return self._core._description(x, self._origin)  # as the export files say

    def __repr__(self):
        return "Model(%s, %s, x %g-%g, %g-%g nm)" % (
            self.method, self.system, self.x_min, self.x_max, self.lambda_min_nm,
            self.lambda_max_nm)


def fit(dataset: Union[Dataset, str], method: str = "auto", *,
        lambda_range_nm: Optional[Sequence[float]] = None, refit: Optional[Model] = None,
        progress: Optional[Callable[[str], None]] = None, **options) -> Model:
    method = _text("method", method)
    _callable("progress", progress)
    if refit is not None and not isinstance(refit, Model):
        raise Error("refit: give the earlier Model (load_model(path)), not %s"
                    % type(refit).__name__)
    given = _fit_options(options, lambda_range_nm)
    if not isinstance(dataset, Dataset):
        dataset = Dataset(dataset)
    try:
        core = _core._fit(dataset._core, method, given, progress,
                          None if refit is None else refit._core)
    except Error as e:
        if lambda_range_nm is None:
            raise
        # The fit grid's joint checks name the options lambda_range_nm stands for.
        message = str(e).replace("lambda_from_nm, lambda_to_nm: ", "lambda_range_nm: ")
        raise Error(message.replace("lambda_step_nm: ", "lambda_range_nm: ")) from None
    return Model(core, "built from data " + dataset._given,
                 "data %s, %s fit" % (dataset._given, core.method), dataset, (dataset, refit))


fit.__signature__ = _fit_signature(Dataset, Model)
fit.__doc__ = _fit_doc()


def load_model(path: Union[str, os.PathLike]) -> Model:
    """Reads a model file written by ``alloycolor fit --out`` or :meth:`Model.save`."""
    path = _path("path", path)
    return Model(_core._load_model(path), "from " + path, path, inputs=(os.path.abspath(path),))


_COLOR_KEYS = ("xyz", "lab", "linear_srgb", "srgb8", "paper_rgb")


def color(source, x=None, angle_deg=0.0, illuminant="D65", observer=2, sigma=False,
          exact=False) -> dict:
    """Colour of a polished metal: a :class:`Model` at compositions ``x``, or a measured
    :class:`Spectrum` (or the path of an n,k file).

    x, angle_deg, illuminant ("A", "C", "D50", "D65", "E", "F2", "F11") and observer (2 or
    10) broadcast together to a shape S. Returns numpy arrays: "xyz" (S + (3,), a perfect
    reflector has Y = 1), "lab" (CIELAB with the illuminant's white), "linear_srgb" and
    "paper_rgb" (S + (3,)), "srgb8" (uint8, S + (3,)), and "sigma", the one-sigma CIEDE2000
    from the model's covariance (S; None unless sigma=True and the model has uncertainty).
    Many compositions at one angle are interpolated from an XYZ table whose error is below
    1e-7 (checked while it is built); exact=True evaluates every composition."""
    if isinstance(source, (str, os.PathLike)):
        source = read_nk(source)
    is_model = isinstance(source, Model)
    if not is_model and not isinstance(source, Spectrum):
        raise Error("color: source must be a Model, a Spectrum or an n,k file, not %s"
                    % type(source).__name__)
    if is_model:
        if x is None:
            raise Error("color: give the composition(s) x for a model")
        xs = _broadcast_x(source, x)
    else:
        if x is not None:
            raise Error("color: a measured spectrum has one composition; x must be None")
        xs = np.zeros(())
    sigma = _flag("sigma", sigma)
    exact = _flag("exact", exact)
    ill = np.asarray(illuminant, dtype=object)
    for name in ill.ravel():
        _text("illuminant", name)
    obs = np.asarray(observer, dtype=object)
    obs = np.asarray([_observer("observer", o) for o in obs.ravel()]).reshape(obs.shape)
    xs, ang, ill_b, obs_b = np.broadcast_arrays(xs, _real_array("angle_deg", angle_deg), ill, obs)
    shape = xs.shape
    n = xs.size
    flat_x, flat_a = xs.ravel(), ang.ravel()
    flat_i, flat_o = ill_b.ravel(), obs_b.ravel().astype(int)
    out = {key: np.zeros((n, 3), dtype=np.uint8 if key == "srgb8" else float)
           for key in _COLOR_KEYS}
    sig = np.zeros(n)
    any_sigma = False
    if ill.ndim == 0 and obs.ndim == 0:  # one colorimeter: no grouping needed
        groups = {(str(ill), int(obs)): slice(None)}
    else:
        pairs, inverse = np.unique(np.char.add(np.char.add(flat_i.astype(str), "/"),
                                               flat_o.astype(str)), return_inverse=True)
        groups = {}
        for j, key in enumerate(pairs):
            name, deg = key.rsplit("/", 1)
            groups[(name, int(deg))] = np.nonzero(inverse == j)[0]
    for (ill_name, obs_deg), idx in groups.items():
        if is_model:
            r = source._core._color(np.ascontiguousarray(flat_x[idx]),
                                    np.ascontiguousarray(flat_a[idx]), ill_name, obs_deg,
                                    sigma, exact)
        else:
            r = source._core._color(np.ascontiguousarray(flat_a[idx]), ill_name, obs_deg)
        for key in _COLOR_KEYS:
            out[key][idx] = r[key]
        if r["sigma"] is not None:
            sig[idx] = r["sigma"]
            any_sigma = True
    result = {key: out[key].reshape(shape + (3,)) for key in _COLOR_KEYS}
    result["sigma"] = sig.reshape(shape) if any_sigma else None
    return result


def validate(dataset: Union[Dataset, str], methods: Union[None, str, Sequence[str]] = None,
             holdout: Optional[Iterable] = None, angles_deg=(0.0, 45.0),
             illuminant: str = "D65", observer: int = 2, html=None, json=None,
             progress: Optional[Callable[[str], None]] = None) -> dict:
    """Held-out validation, as ``alloycolor validate``: each method is refitted without the
    held-out samples and scored against them, one result per held-out sample. ``holdout``:
    compositions (every replicate there) or sample files (that replicate alone), as
    ``alloycolor validate --holdout``; default: leave each interior composition out in turn,
    with all its replicates. Scored (CIEDE2000 per angle, reflectance and n, k errors).
    methods: names of :func:`methods` and "auto" (which runs its own leave-one-out inside
    every split, on the training samples only), a comma-separated string of them, or "all";
    default: those the registry marks ``validate_default``, as ``alloycolor validate``.
    Returns the report's JSON document as Python objects; writes the JSON and the
    self-contained HTML page to the paths given as ``json`` and ``html`` (atomically)."""
    if not isinstance(dataset, Dataset):
        dataset = Dataset(dataset)
    if holdout is None:
        names, mode = [], "loo"
    else:
        if isinstance(holdout, (str, os.PathLike)) or not isinstance(holdout, Iterable):
            holdout = [holdout]
        names = [os.fspath(v) if isinstance(v, (str, os.PathLike)) else repr(_real("holdout", v))
                 for v in holdout]
        if not names:
            raise Error("holdout: no composition given")
        mode = "holdout"
    if methods is None:
        methods = ""
    elif not isinstance(methods, str):
        listed = [_text("methods", m) for m in methods]
        if not listed:
            raise Error("methods: no method given")
        methods = ",".join(listed)
    methods = _core._method_list(methods, "methods")  # "all", defaults: the library's rule
    return _core._validate(dataset._core, list(methods), names, mode,
                           [float(a) for a in np.atleast_1d(_real_array("angles_deg",
                                                                        angles_deg))],
                           _text("illuminant", illuminant), _observer("observer", observer),
                           "" if html is None else _path("html", html),
                           "" if json is None else _path("json", json),
                           _callable("progress", progress), _output_guard(dataset))
