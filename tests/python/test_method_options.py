# The methods' options are declared once, in the registry: the committed options table of
# docs/methods.md and fit's keywords in the type stubs are what scripts/method_options.py
# generates from the declarations; fit's signature and docstring are generated at import;
# and the package refuses a value with the library's words (the program's refusals are
# compared in test_faces.py's option test).
import inspect

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
