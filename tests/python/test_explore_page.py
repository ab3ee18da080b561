# The explorer page is written by the library (export/explorer_page.h): Python's
# Model.explore and `alloycolor explore` write the same bytes for the same model and
# options, and refuse the same values with the same words.
import subprocess

import pytest

import alloycolor as ac


def run(binary, *args):
    return subprocess.run([binary, *args], capture_output=True, text=True)


def test_a_loaded_model_gives_the_programs_page(binary, tmp_path):
    model = str(tmp_path / "m.json")
    assert run(binary, "fit", "--data", "Au-Ag", "--method", "eps-linear", "--out", model,
               "--quiet").returncode == 0
    cli = tmp_path / "cli.html"
    out = run(binary, "explore", "--model", model, "--size", "64", "--roughness", "0,0.3",
              "--illuminants", "D65,A", "--out", str(cli), "--quiet")
    assert out.returncode == 0, out.stderr
    py = tmp_path / "py.html"
    figures = ac.load_model(model).explore(py, size=64, roughness=[0, 0.3],
                                           illuminants=["D65", "A"])
    assert py.read_bytes() == cli.read_bytes()
    assert figures["bytes"] == len(py.read_bytes())
    assert figures["illuminants"] == 2 and figures["finishes"] == 2
    assert figures["max_de00"] <= 0.02 or not figures["tolerance_met"]


def test_a_fitted_model_gives_the_programs_page_with_its_data(binary, tmp_path):
    cli = tmp_path / "cli.html"
    out = run(binary, "explore", "--data", "Au-Ag", "--method", "paper", "--size", "64",
              "--roughness", "0", "--observer", "10", "--out", str(cli), "--quiet")
    assert out.returncode == 0, out.stderr
    py = tmp_path / "py.html"
    ac.fit("Au-Ag", "paper").explore(py, size=64, roughness=0, observer=10)
    page = py.read_bytes()
    assert page == cli.read_bytes()
    assert b"Measured spectra from the data set Au-Ag." in page


@pytest.mark.parametrize("flag, keyword, value, words", [
    ("--size", "size", "50", "50 lies outside 64-1024 pixels"),
    ("--tolerance", "tolerance", "0.6", "0.6 lies outside 0.0001-0.5 (dE00)"),
    ("--roughness", "roughness", "1.5", "1.5 lies outside 0-1 (GGX alpha)"),
    ("--threads", "threads", "-1", "-1 is negative"),
])
def test_the_same_values_are_refused_in_the_same_words(binary, tmp_path, flag, keyword, value,
                                                       words):
    model = str(tmp_path / "m.json")
    assert run(binary, "fit", "--data", "Au-Ag", "--method", "eps-linear", "--out", model,
               "--quiet").returncode == 0
    out = run(binary, "explore", "--model", model, flag, value, "--out",
              str(tmp_path / "no.html"))
    assert out.returncode == 2
    assert f"{flag}: {words}" in out.stderr
    with pytest.raises(ac.Error) as e:
        ac.load_model(model).explore(tmp_path / "no.html", **{keyword: float(value)})
    assert str(e.value) == f"{keyword}: {words}"
    assert not (tmp_path / "no.html").exists()
