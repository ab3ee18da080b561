# The lab's loop in Python: a refit's verdicts and history, suspect and set-aside samples,
# where to measure next and models without error bars, each against the program's own
# answer for the same data (the CLI is the reference the package must agree with).
import json
import os
import shutil
import subprocess

import pytest

import alloycolor as ac
from conftest import DATA

FIRST = [{"x": 0.0, "file": "Werner-Zn100.yml"}, {"x": 0.7, "file": "Querry-Cu70Zn30.yml"},
         {"x": 0.85, "file": "Querry-Cu85Zn15.yml"}, {"x": 1.0, "file": "Querry-Cu100.yml"}]


def ciede2000(lab1, lab2):
    """CIEDE2000 (Sharma, Wu and Dalal 2005), written here apart from the library."""
    from math import atan2, cos, degrees, exp, hypot, radians, sin, sqrt
    (L1, a1, b1), (L2, a2, b2) = lab1, lab2
    c_bar = (hypot(a1, b1) + hypot(a2, b2)) / 2
    g = 0.5 * (1 - sqrt(c_bar ** 7 / (c_bar ** 7 + 25 ** 7)))
    a1p, a2p = (1 + g) * a1, (1 + g) * a2
    c1p, c2p = hypot(a1p, b1), hypot(a2p, b2)
    h1p = degrees(atan2(b1, a1p)) % 360 if c1p else 0.0
    h2p = degrees(atan2(b2, a2p)) % 360 if c2p else 0.0
    dl, dc = L2 - L1, c2p - c1p
    dh = 0.0 if c1p * c2p == 0 else (h2p - h1p + 180) % 360 - 180
    dH = 2 * sqrt(c1p * c2p) * sin(radians(dh / 2))
    l_bar, c_barp = (L1 + L2) / 2, (c1p + c2p) / 2
    if c1p * c2p == 0:
        h_bar = h1p + h2p
    elif abs(h1p - h2p) <= 180:
        h_bar = (h1p + h2p) / 2
    else:
        h_bar = (h1p + h2p + 360) / 2 if h1p + h2p < 360 else (h1p + h2p - 360) / 2
    t = (1 - 0.17 * cos(radians(h_bar - 30)) + 0.24 * cos(radians(2 * h_bar))
         + 0.32 * cos(radians(3 * h_bar + 6)) - 0.20 * cos(radians(4 * h_bar - 63)))
    sl = 1 + 0.015 * (l_bar - 50) ** 2 / sqrt(20 + (l_bar - 50) ** 2)
    sc, sh = 1 + 0.045 * c_barp, 1 + 0.015 * c_barp * t
    rt = (-2 * sqrt(c_barp ** 7 / (c_barp ** 7 + 25 ** 7))
          * sin(radians(60 * exp(-((h_bar - 275) / 25) ** 2))))
    return sqrt((dl / sl) ** 2 + (dc / sc) ** 2 + (dH / sh) ** 2 + rt * dc / sc * dH / sh)


def test_ciede2000_here_is_sharmas():
    # Two of Sharma, Wu and Dalal's published pairs (their table 1: pairs 1 and 17).
    assert ciede2000((50, 2.6772, -79.7751), (50, 0, -82.7485)) == pytest.approx(2.0425, abs=1e-4)
    assert ciede2000((50, 2.5, 0), (73, 25, -18)) == pytest.approx(27.1492, abs=1e-4)


def brasses(folder, samples):
    for f in os.listdir(DATA / "Cu-Zn"):
        if f.endswith(".yml") and not (folder / f).exists():
            shutil.copy(DATA / "Cu-Zn" / f, folder)
    (folder / "dataset.json").write_text(json.dumps(
        {"system": {"a": "Cu", "b": "Zn"}, "composition": "weight_fraction_a",
         "samples": samples}))
    return folder


def test_a_refit_judges_the_added_film_as_the_program_does(tmp_path, binary):
    folder = brasses(tmp_path, FIRST)
    old_py = ac.fit(folder)
    old_path = tmp_path / "old.json"
    old_py.save(old_path)
    brasses(tmp_path, FIRST + [{"x": 0.9, "file": "Querry-Cu90Zn10.yml"}])
    new_py = ac.fit(folder, refit=ac.load_model(old_path))
    new_path = tmp_path / "new.json"
    subprocess.run([binary, "fit", "--data", str(folder), "--refit", str(old_path), "--out",
                    str(new_path), "--quiet"], check=True, capture_output=True)
    cli = json.loads(new_path.read_text())["history"]
    assert len(new_py.history) == len(cli) == 2
    (added_py,), (added_cli,) = new_py.history[-1]["added"], cli[-1]["added"]
    assert added_py["file"] == added_cli["file"] == "Querry-Cu90Zn10.yml"
    for key in ("delta_e00", "sigma_de00", "reflectance_rms"):
        assert added_py[key] == pytest.approx(added_cli[key], rel=1e-9)
    assert added_py["verdict"] == added_cli["verdict"]
    # The figures are the old model's own: its colour at the film's composition against the
    # film's measured colour.
    film = ac.read_nk(folder / "Querry-Cu90Zn10.yml")
    lab_film = ac.color(film)["lab"]
    lab_old = old_py.color(added_py["x"], sigma=True)
    assert added_py["delta_e00"] == pytest.approx(ciede2000(lab_film, lab_old["lab"]), abs=0.02)
    assert added_py["sigma_de00"] == pytest.approx(float(lab_old["sigma"]), rel=1e-9)
    with pytest.raises(ac.Error, match="refit: give the earlier Model"):
        ac.fit(folder, refit=str(old_path))


def test_querrys_zinc_is_suspect_and_a_set_aside_film_is_scored(tmp_path):
    suspects = ac.fit("Cu-Zn").suspect_samples
    assert [s["file"] for s in suspects] == ["Querry-Zn100.yml"]
    assert suspects[0]["check"] == "not metallic"
    assert ac.fit(DATA / "Cu-Zn" / "dataset-werner-zn.json").suspect_samples == []
    aside = FIRST[1:] + [{"x": 0.0, "file": "Querry-Zn100.yml", "exclude": "n > k: oxidised"}]
    data = ac.Dataset(brasses(tmp_path, aside))
    assert [s["file"] for s in data.excluded] == ["Querry-Zn100.yml"]
    assert data.excluded[0]["excluded"] == "n > k: oxidised"
    model = ac.fit(data, "smooth")
    (note,) = model.excluded_samples
    assert note["reason"] == "n > k: oxidised" and note["delta_e00"] > 5


def test_suggest_is_the_programs(tmp_path, binary):
    model_path = tmp_path / "m.json"
    subprocess.run([binary, "fit", "--data", str(DATA / "Cu-Zn" / "dataset-werner-zn.json"),
                    "--out", str(model_path), "--quiet"], check=True, capture_output=True)
    cli = json.loads(subprocess.run([binary, "suggest", "--model", str(model_path), "--count",
                                     "2", "--json"], check=True, capture_output=True,
                                    text=True).stdout)
    py = ac.load_model(model_path).suggest(count=2)
    assert [s["x"] for s in py] == [s["x"] for s in cli]
    assert [s["sigma_de00"] for s in py] == pytest.approx([s["sigma_de00"] for s in cli])
    with pytest.raises(ac.Error, match="count"):
        ac.load_model(model_path).suggest(count=0)


def test_two_compositions_have_no_error_bar():
    two = ac.fit(ac.Dataset("Cu-Zn").select([0.7, 1.0]))
    assert two.no_error_bar.startswith("no error bar: 2 compositions")
    assert two.color(0.8, sigma=True)["sigma"] is None
    assert ac.fit("Au-Ag", "eps-linear").no_error_bar == ""
    # The design's parameters are in the model, as params --format json gives them.
    rows = ac.fit("Au-Ag", "eps-linear").parameter_curves["rows"]
    assert len(rows) == 11 and "tau_fs@550nm" in rows[5]
