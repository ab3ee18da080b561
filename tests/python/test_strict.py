"""The Python package is as strict as the program: every argument is checked by the
library's own checks, with its one-line messages, raised as alloycolor.Error naming the
keyword (never a command-line flag, never a pybind11 signature); outputs are written as
the program writes them (atomically, a set all or nothing), and reading a file leaves no
trace that would stop a later write to it."""
import numpy as np
import pytest

import alloycolor as ac


@pytest.fixture(scope="module")
def model():
    return ac.fit("Au-Ag", "eps-linear")


def error_of(f):
    with pytest.raises(ac.Error) as caught:
        f()
    message = str(caught.value)
    assert "\n" not in message
    assert "--" not in message, message  # no command-line flag
    assert "TypeError" not in message and "incompatible" not in message
    return message


def test_a_loaded_model_does_not_save_over_its_own_file(tmp_path, model):
    path = tmp_path / "m.json"
    model.save(path)
    before = path.read_bytes()
    loaded = ac.load_model(path)
    # Its file is its input, as `fit --refit M --out M` is refused (test_output_guard.py).
    with pytest.raises(ac.Error, match="it is one of this command's inputs"):
        loaded.save(path)
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["m.json"]


@pytest.mark.parametrize("options, needles", [
    (dict(method="smooth", smoothing=-1), ["smoothing", "-1", "[0, 1000000]"]),
    (dict(method="smooth", smoothing=float("nan")), ["smoothing", "nan"]),
    (dict(method="physical", degree=-3), ["degree", "-3", "whole number in [0, 6]"]),
    (dict(method="physical", degree=10**12), ["degree", "whole number in [0, 6]"]),
    (dict(method="physical", degree=2.5), ["degree", "2.5"]),
    (dict(method="physical", degree=True), ["degree", "boolean"]),
    (dict(method="physical", degree=2 + 0j), ["degree", "complex"]),
    (dict(method="smooth", lambda_range_nm=[400, 700]), ["lambda_range_nm", "three numbers"]),
    (dict(method="smooth", lambda_range_nm=[400, 700, 0.001]), ["lambda_range_nm[2] (step)"]),
    (dict(method="smooth", lambda_range_nm=[700, 400, 5]), ["lambda_range_nm", "below"]),
    (dict(method="smooth", lambda_range_nm=[400, 700, 0.01]),
     ["lambda_range_nm", "20000 grid nodes"]),
    (dict(method="smooth", space="cubic"), ["space", "cubic"]),
    (dict(method="smooth", covariance="yes"), ["covariance"]),
    (dict(method=3), ["method"]),
])
def test_fit_arguments_are_checked(au_ag, options, needles):
    message = error_of(lambda: ac.fit(au_ag, **options))
    for needle in needles:
        assert needle in message, message


def test_the_library_and_the_program_use_the_same_words(binary, tmp_path):
    import subprocess
    out = subprocess.run([binary, "fit", "--data", "Au-Ag", "--method", "smooth", "--smoothing",
                          "-1", "--out", str(tmp_path / "m.json")],
                         capture_output=True, text=True)
    assert out.returncode == 2
    assert "is not a finite number in [0, 1000000]" in out.stderr
    message = error_of(lambda: ac.fit("Au-Ag", "smooth", smoothing=-1))
    assert message == "smoothing: -1 is not a finite number in [0, 1000000]"


@pytest.mark.parametrize("x, needle", [
    (True, "boolean"), ([0.5, False], "boolean"), (0.5 + 1j, "complex"),
    (np.array([0.5 + 0j]), "complex"), ({"x": 1}, "composition"),
])
def test_compositions_are_real_numbers(model, x, needle):
    for f in (lambda: model.color(x), lambda: model.nk(x, [500.0])):
        message = error_of(f)
        assert "x:" in message and needle in message, message


def test_no_composition_is_named(model):
    assert "x" in error_of(lambda: model.color(None))
    assert "x: None" in error_of(lambda: model.nk(None, [500.0]))


def test_angles_are_real_numbers(model):
    assert "angle_deg" in error_of(lambda: model.color(0.5, angle_deg=True))
    assert "angle_deg" in error_of(lambda: model.color(0.5, angle_deg=1j))


def test_out_of_range_names_no_flag(model):
    message = error_of(lambda: model.nk(2.0, [500.0]))
    assert "x = 2" in message and "extrapolate" not in message


def test_write_spd_refuses_one_file_for_both(tmp_path, model):
    p = tmp_path / "one.spd"
    message = error_of(lambda: model.write_spd(0.5, p, p))
    assert str(p) in message and "two outputs" in message
    assert list(tmp_path.iterdir()) == []
    model.write_spd(0.5, tmp_path / "eta.spd", tmp_path / "k.spd")
    assert sorted(q.name for q in tmp_path.iterdir()) == ["eta.spd", "k.spd"]


def test_a_columns_message_names_the_keyword(tmp_path):
    path = tmp_path / "two.csv"
    path.write_text("lambda_nm,n1,k1,n2,k2\n500,1,2,1,2\n600,1,2,1,2\n")
    message = error_of(lambda: ac.read_nk(path))
    assert "columns=" in message, message


@pytest.mark.parametrize("call, needle", [
    # Past any whole number the program takes; within them, the program's range and words.
    (lambda m: m.render(0.5, size=10**12), "size: 1e+12 is not a whole number in [-2147483648"),
    (lambda m: m.render(0.5, size=5000), "size: 5000 lies outside 1-4096 pixels"),
    (lambda m: m.render(0.5, size=True), "size:"),
    (lambda m: m.render(0.5, shape=3), "shape:"),
    (lambda m: m.render(0.5, size=8, linear="no"), "linear:"),
    (lambda m: m.color(0.5, observer=10**12), "observer:"),
    (lambda m: m.color(0.5, observer=True), "observer:"),
    (lambda m: m.color(0.5, sigma="x"), "sigma:"),
    (lambda m: m.color(0.5, illuminant=3), "illuminant:"),
    (lambda m: m.nk(0.5, [500 + 1j]), "lambda_nm:"),
    (lambda m: m.nk(0.5, [True]), "lambda_nm:"),
    (lambda m: m.save(3), "path:"),
    (lambda m: m.write_spd(0.5, "a.spd", 3), "k_path:"),
    (lambda m: m.spectra(0.5, material=3), "material:"),
    (lambda m: ac.load_model(3), "path:"),
    (lambda m: ac.Dataset(3), "path_or_name:"),
    (lambda m: ac.Dataset("Au-Ag").without([True]), "x:"),
    (lambda m: ac.validate("Au-Ag", "paper", angles_deg=[1j]), "angles_deg:"),
    (lambda m: ac.validate("Au-Ag", "paper", observer=10**12), "observer:"),
    (lambda m: ac.validate("Au-Ag", "paper", progress=3), "progress:"),
    (lambda m: ac.fit("Au-Ag", "paper", progress=3), "progress:"),
])
def test_every_argument_is_checked(model, call, needle):
    message = error_of(lambda: call(model))
    assert needle in message, message
