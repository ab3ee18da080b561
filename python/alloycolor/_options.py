"""fit's keywords from the methods' options as the registry declares them (name, kind, range,
choices, default, help, the methods that take them): the values given checked against
their declarations, fit's signature and its docstring. The stubs and docs/methods.md's
table come from the same declarations (scripts/method_options.py)."""

import inspect
from typing import Callable, Optional, Sequence, Union

import numpy as np

from . import _alloycolor as _core
from ._alloycolor import Error
from ._args import _flag, _real, _text

# Every method's options, by name.
_METHOD_OPTIONS = {o["name"]: o for o in _core._method_options()}

_OPTION_TYPES = {"whole": int, "number": float, "choice": str, "text": str, "flag": bool}

# The fit grid as one keyword, (from, to, step) in nm: the options it stands for.
_LAMBDA_RANGE = ("lambda_from_nm", "lambda_to_nm", "lambda_step_nm")
_LAMBDA_LABELS = ("lambda_range_nm[0] (from)", "lambda_range_nm[1] (to)",
                  "lambda_range_nm[2] (step)")


def _option_value(option: dict, label: str, value):
    """value as the option's kind takes it (a real number, text, True or False), checked
    against the option's declaration by the library; errors name ``label``."""
    kind = option["kind"]
    if kind in ("whole", "number"):
        v = _real(label, value)
    elif kind == "flag":
        v = _flag(label, value)
    else:
        v = _text(label, value)
    _core._check_option(option["name"], v, label)
    return v


def fit_options(options: dict, lambda_range_nm) -> dict:
    """The options given (None: not given, the method's to choose), by the registry's
    names; an unknown name goes on to the library, which refuses it naming the options."""
    given = {}
    for name, value in options.items():
        if value is None:
            continue
        option = _METHOD_OPTIONS.get(name)
        given[name] = value if option is None else _option_value(option, name, value)
    if lambda_range_nm is not None:
        if any(name in given for name in _LAMBDA_RANGE):
            raise Error("lambda_range_nm: give it or %s, not both" % ", ".join(_LAMBDA_RANGE))
        if (isinstance(lambda_range_nm, (str, bytes)) or np.ndim(lambda_range_nm) != 1
                or len(lambda_range_nm) != 3):
            raise Error("lambda_range_nm: give (from, to, step) in nm, three numbers, not %r"
                        % (lambda_range_nm,))
        for name, label, value in zip(_LAMBDA_RANGE, _LAMBDA_LABELS, lambda_range_nm):
            given[name] = _option_value(_METHOD_OPTIONS[name], label, value)
    return given


def fit_signature(dataset_type, model_type) -> inspect.Signature:
    """fit's signature with a keyword per declared option (its default: the declared one, or
    None where the method chooses)."""
    P = inspect.Parameter
    params = [P("dataset", P.POSITIONAL_OR_KEYWORD, annotation=Union[dataset_type, str]),
              P("method", P.POSITIONAL_OR_KEYWORD, default="auto", annotation=str)]
    for name, o in _METHOD_OPTIONS.items():
        python_type = _OPTION_TYPES[o["kind"]]
        params.append(P(name, P.KEYWORD_ONLY, default=o["default"],
                        annotation=Optional[python_type]))
    params.append(P("lambda_range_nm", P.KEYWORD_ONLY, default=None,
                    annotation=Optional[Sequence[float]]))
    params.append(P("refit", P.KEYWORD_ONLY, default=None, annotation=Optional[model_type]))
    params.append(P("progress", P.KEYWORD_ONLY, default=None,
                    annotation=Optional[Callable[[str], None]]))
    return inspect.Signature(params, return_annotation=model_type)


def fit_doc() -> str:
    lines = ["""Fits ``method`` (see :func:`methods`) to a data set, as ``alloycolor fit`` does.

    method: one of :func:`methods`, or "auto" (the default): every method scored by
    leave-one-composition-out on the samples and the best chosen, as ``alloycolor fit``
    chooses; the table behind the choice is in ``model.to_json()["fit"]["selection"]``.
    Every method fitted to three compositions or more carries a cross-validated
    uncertainty.

    The methods' options, as the registry declares them (an option the method does not
    take is refused, naming the methods that do; None: not given, the method chooses):
"""]
    for name, o in _METHOD_OPTIONS.items():
        default = "" if o["default"] is None else "; default %r" % (o["default"],)
        lines.append("    %s (%s; %s%s): %s\n" % (name, ", ".join(o["methods"]), o["values"],
                                                   default, o["help"]))
    lines.append("""
    lambda_range_nm: (from, to, step) of the fit grid, for lambda_from_nm, lambda_to_nm and
    lambda_step_nm together; progress: called with one-line messages.

    refit: an earlier Model of the data set, as ``alloycolor fit --refit``: the new model's
    ``history`` is the earlier one's and an entry for this fit, which gives for each sample
    added since the earlier model that model's error there (``delta_e00`` at normal
    incidence, D65, 2 degrees, ``reflectance_rms``), its one-sigma (``sigma_de00``) and the
    verdict (within one sigma, within two, or beyond). Every fit checks the samples against
    the rest of the series (``suspect_samples``) and scores those the manifest sets aside
    (``excluded_samples``).""")
    return "".join(lines)
