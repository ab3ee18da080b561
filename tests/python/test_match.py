# model.match and model.tolerance (color/match.h through the Python package): round trip
# over many targets at once, the same answers as the program, errors as alloycolor.Error.
import json
import subprocess

import numpy as np
import pytest

import alloycolor


@pytest.fixture(scope="module")
def model(au_ag):
    return au_ag.fit("smooth")


def test_round_trip_vectorised(model):
    xs = np.linspace(0.05, 0.95, 37)
    labs = model.color(xs, exact=True)["lab"]
    out = model.match(labs, sigma=False)
    assert out["x"].shape == xs.shape
    np.testing.assert_allclose(out["x"], xs, atol=5e-4)
    assert np.all(out["de00"] < 1e-6)
    assert np.all(out["reachable"])
    assert np.all(out["n_minima"] >= 1)
    # one target keeps a scalar shape
    single = model.match(labs[3])
    assert single["x"].shape == ()
    assert np.isfinite(single["x_sigma"]) and single["x_sigma"] > 0


def test_agrees_with_the_program(model, binary, tmp_path):
    path = tmp_path / "m.json"
    model.save(path)
    lab = model.color(0.6, exact=True)["lab"]
    out = model.match(lab, target_sigma=0.3, all_minima=True)
    run = subprocess.run([binary, "match", "--model", str(path), "--lab",
                          ",".join("%.12f" % v for v in lab), "--target-sigma", "0.3", "--json"],
                         capture_output=True, text=True, check=True)
    doc = json.loads(run.stdout)
    assert doc["matches"][0]["x_atomic"] == pytest.approx(float(out["x"]), abs=1e-9)
    assert doc["matches"][0]["x_sigma"] == pytest.approx(float(out["x_sigma"]), rel=1e-9)
    assert out["matches"][0][0]["x_atomic"] == pytest.approx(float(out["x"]))


def test_hex_xyz_and_unreachable(model):
    blue = model.match(hex=["#2040c0", "#3050d0"])
    assert blue["x"].shape == (2,)
    assert not blue["reachable"].any()
    assert np.all(blue["de00"] > 1)
    xyz = model.color(0.4, exact=True)["xyz"]
    assert float(model.match(xyz=xyz, sigma=False)["x"]) == pytest.approx(0.4, abs=5e-4)


def test_tolerance(model, binary, tmp_path):
    out = model.tolerance([0.5, "18k"], de=1.0, angles_deg=[0, 45], illuminants=["D65", "A"])
    assert out["x_low"].shape == (2,)
    assert np.all(out["x_low"] < out["x_high"])
    assert np.all(out["de00_per_at_percent"] > 0)
    path = tmp_path / "m.json"
    model.save(path)
    run = subprocess.run([binary, "tolerance", "--model", str(path), "--x", "0.5", "--angles",
                          "0,45", "--illuminants", "D65,A", "--json"],
                         capture_output=True, text=True, check=True)
    doc = json.loads(run.stdout)
    assert doc["x_low"] == pytest.approx(float(out["x_low"][0]), abs=1e-12)
    assert doc["x_high"] == pytest.approx(float(out["x_high"][0]), abs=1e-12)


def test_errors(model):
    with pytest.raises(alloycolor.Error, match="shape"):
        model.match([1.0, 2.0])
    with pytest.raises(alloycolor.Error, match="#12345g"):
        model.match(hex="#12345g")
    with pytest.raises(alloycolor.Error, match="exactly one"):
        model.match([50, 0, 0], hex="#ffffff")
    with pytest.raises(alloycolor.Error):
        model.tolerance(0.5, illuminants=["Q"])
    with pytest.raises(alloycolor.Error):
        model.tolerance(1.5)


def test_many_targets_over_threads(model):
    # 5000 targets without the one-sigma run in blocks over the cores: the same answers
    # as one at a time.
    xs = np.linspace(0.0, 1.0, 5000)
    labs = model.color(xs, exact=True)["lab"]
    out = model.match(labs, sigma=False)
    np.testing.assert_allclose(out["x"], xs, atol=5e-4)
    for i in (0, 2047, 2048, 4999):
        assert float(model.match(labs[i], sigma=False)["x"]) == out["x"][i]
