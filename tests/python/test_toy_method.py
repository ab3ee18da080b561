# The Python module built with the toy method of tests/toy_method.h linked in (the same
# binding sources and package; tests/CMakeLists.txt builds it into tests/toy_python) knows
# the toy as it knows a built-in method: listed by methods(), a keyword of fit() with its
# declared default, fitted, its option checked with the library's words, validated. Run in
# a child interpreter, as the package in this one is the stock build.
import json
import os
import subprocess
import sys
import textwrap

import pytest

TOY_PATH = os.environ.get("ALLOYCOLOR_TOY_PYTHONPATH")

CHILD = textwrap.dedent("""
    import inspect, json
    import alloycolor as ac
    out = {}
    out["methods"] = {m["name"]: m for m in ac.methods()}
    p = inspect.signature(ac.fit).parameters["toy_eps1"]
    out["keyword"] = [p.kind == p.KEYWORD_ONLY, p.default]
    m = ac.fit("Au-Ag", "toy-constant", toy_eps1=-2.5)
    out["eps"] = [m.permittivity(0.5, [550.0]).real.item(), m.permittivity(0.5, [550.0]).imag.item()]
    def error(f):
        try:
            f()
        except ac.Error as e:
            return str(e)
        return None
    out["range"] = error(lambda: ac.fit("Au-Ag", "toy-constant", toy_eps1=5))
    out["other"] = error(lambda: ac.fit("Au-Ag", "smooth", toy_eps1=-2))
    out["auto"] = error(lambda: ac.fit("Au-Ag", toy_eps1=-2))
    report = ac.validate("Au-Ag", methods=["toy-constant", "eps-linear"], holdout=[0.5],
                         angles_deg=[0])
    out["validated"] = sorted(report["holdouts"][0]["results"])
    print(json.dumps(out))
""")


@pytest.mark.skipif(not TOY_PATH, reason="ALLOYCOLOR_TOY_PYTHONPATH unset (run through ctest)")
def test_the_package_built_with_the_toy_knows_it():
    env = dict(os.environ, PYTHONPATH=TOY_PATH)
    run = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True, env=env,
                         timeout=600)
    assert run.returncode == 0, run.stderr
    out = json.loads(run.stdout)
    toy = out["methods"]["toy-constant"]
    assert toy["auto_rank"] == -1 and toy["options"] == ["toy_eps1"]
    assert out["keyword"] == [True, -10.0]
    assert out["eps"] == [-2.5, 1.0]
    assert out["range"] == "toy_eps1: 5 is not a finite number in [-100, -0.01]"
    assert out["other"] == "toy_eps1: an option of toy-constant; smooth does not take it"
    assert out["auto"] == ("toy_eps1: an option of toy-constant; auto does not run it (not one "
                           "of its candidates)")
    assert out["validated"] == ["eps-linear", "toy-constant"]


def test_the_stock_package_does_not_know_the_toy():
    import alloycolor as ac
    assert "toy-constant" not in {m["name"] for m in ac.methods()}
