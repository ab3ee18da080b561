# The methods' options are declared once, in the registry: the committed options table of
# docs/methods.md and fit's keywords in the type stubs are what scripts/method_options.py
# generates from the declarations; fit's signature and docstring are generated at import;
# and the package and the program accept or refuse every option at, inside and past its
# bounds alike, with the library's words (the program spelling options by flag).
import inspect
import subprocess

import numpy as np
import pytest

import alloycolor as ac
from conftest import load_script


def test_committed_docs_and_stubs_are_generated():
    script = load_script("method_options")
    assert script.stale_files(script.declared_options()) == []


def test_the_generated_table_has_every_option():
    script = load_script("method_options")
    options = script.declared_options()
    lines = script.markdown_lines(options)
    assert len(lines) == 2 + len(options)
    names = {o["name"] for o in options}
    assert {"degree", "smoothing", "space", "terms", "covariance", "lambda_step_nm"} <= names
    # Every option is declared once, whichever methods take it.
    assert len(names) == len(options)


def test_fit_signature_has_a_keyword_per_option():
    params = inspect.signature(ac.fit).parameters
    for option in ac._core._method_options():
        p = params[option["name"]]
        assert p.kind == inspect.Parameter.KEYWORD_ONLY
        assert p.default == option["default"]
        assert option["name"] in ac.fit.__doc__


def test_methods_list_their_options():
    by_name = {m["name"]: m for m in ac.methods()}
    assert "degree" in by_name["physical"]["options"]
    assert "degree" not in by_name["smooth"]["options"]
    assert by_name["paper"]["options"] == []
    for option in ac._core._method_options():
        for method in option["methods"]:
            assert option["name"] in by_name[method]["options"]


@pytest.mark.parametrize("method, options, needle", [
    ("smooth", dict(degree=2), "degree: an option of physical; smooth does not take it"),
    ("paper", dict(covariance=False), "covariance: an option of physical; paper does not"),
    ("eps-linear", dict(lambda_step_nm=2.0), "lambda_step_nm: an option of smooth, physical"),
    ("physical", dict(degree=7), "degree: 7 is not a whole number in [0, 6]"),
    ("physical", dict(degree=6.5), "degree: 6.5 is not a whole number in [0, 6]"),
    ("smooth", dict(smoothing=1e7), "smoothing: 10000000 is not a finite number in [0, 1000000]"),
    ("smooth", dict(nonsense=1), "'nonsense': no method takes this option"),
])
def test_options_are_refused_by_the_declaration(au_ag, method, options, needle):
    with pytest.raises(ac.Error) as e:
        ac.fit(au_ag, method, **options)
    assert needle in str(e.value)


def _option_cases():
    """(option, method, value) for every declared option: at, inside and past its bounds (a
    number), each choice and one that is not, its default and a bad text, the non-default
    flag; for the first method that takes it and for paper, which takes none."""
    cases = []
    for o in ac._core._method_options():
        kind = o["kind"]
        if kind in ("whole", "number"):
            lo, hi = o["range"]
            values = [lo, (lo + hi) / 2, hi, lo - 1 if lo >= 1 else lo / 2 - 1, hi * 2]
            if kind == "whole":
                values = [int(v) for v in values[:3]] + [int(values[3]), int(values[4]), lo + 0.5]
        elif kind == "choice":
            values = o["choices"] + ["bogus"]
        elif kind == "flag":
            values = [not o["default"]]  # the program can give only the other value
        else:
            values = [o["default"], "bogus"]
        for value in values:
            cases.append((o, o["methods"][0], value))
        cases.append((o, "paper", values[0]))
    return cases


def _program_words(text):
    """The program's one error line in the library's names (its flags spelt as keywords)."""
    line = text.strip().splitlines()[-1]
    line = line.removeprefix("alloycolor: error: ").removesuffix(" (see --help)")
    for o in ac._core._method_options():
        line = line.replace(o["flag"], o["name"])
    return line


@pytest.mark.parametrize("option, method, value", _option_cases(),
                         ids=lambda v: v["name"] if isinstance(v, dict) else repr(v))
def test_program_and_package_agree_on_every_option(binary, tmp_path, option, method, value):
    # Nb-Sn: infrared data, quick fits of every method.
    args = [binary, "fit", "--data", "Nb-Sn", "--method", method, "--quiet",
            "--out", str(tmp_path / "m.json")]
    text = value if isinstance(value, str) else repr(value)
    args += [option["flag"]] if option["kind"] == "flag" else [option["flag"], text]
    program = subprocess.run(args, capture_output=True, text=True)
    try:
        model = ac.fit("Nb-Sn", method, **{option["name"]: value})
        package = None
    except ac.Error as e:
        package = str(e)
    if program.returncode == 0:
        assert package is None, package
        # The same model: the program's file predicts what the package's fit does.
        written = ac.load_model(tmp_path / "m.json")
        assert written.method == model.method
        xs, lam = [0.0, 0.3, 0.7, 1.0], np.linspace(model.lambda_min_nm, model.lambda_max_nm, 7)
        np.testing.assert_allclose(written.permittivity(xs, lam), model.permittivity(xs, lam),
                                   rtol=1e-12, atol=0)
    else:
        assert program.returncode == 2, program.stderr
        assert package == _program_words(program.stderr)


def test_the_docs_list_the_registrys_methods():
    # The lists a new built-in method must join are checked against the registry.
    import re
    from conftest import REPO
    names = [m["name"] for m in ac.methods()]
    methods_md = (REPO / "docs" / "methods.md").read_text()
    table = re.findall(r"^\| `([a-z0-9-]+)` \|", methods_md.split("## Options")[0], re.M)
    assert table == ["auto"] + names
    model_format = (REPO / "docs" / "model-format.md").read_text()
    row = next(line for line in model_format.splitlines() if line.startswith("| `method` |"))
    assert re.findall(r"`([a-z0-9-]+)`", row.split("|")[3]) == names
