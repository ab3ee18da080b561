# No call of the package overwrites one of its inputs (issue 49): every call that writes
# refuses, as the program refuses a command's output, the colour tables, a data set's
# manifest and sample files (those set aside and both files of an n,k pair included), the
# file a model was loaded from and the model a refit started from, a spectrum's file, by
# any path (hard links too), and symlinks, devices and FIFOs; nothing is written, no
# temporary is left, and the words are the program's (compared with its line).
import hashlib
import os
import pathlib
import shutil
import subprocess
import sys

import pytest

import alloycolor as ac

DATA = pathlib.Path(__file__).resolve().parents[2] / "data"
INPUT = "it is one of this command's inputs"


def _yaml_table(path, kind, lam_um, *columns):
    rows = "\n".join("        " + " ".join("%.6g" % v for v in row)
                     for row in zip(lam_um, *columns))
    path.write_text("DATA:\n  - type: tabulated %s\n    data: |\n%s\n" % (kind, rows))


@pytest.fixture
def lab(tmp_path, monkeypatch):
    """A copy of Au-Ag whose x = 0.2 sample is an n,k pair of files and with a sample set
    aside; the working folder is tmp_path."""
    folder = tmp_path / "Au-Ag"
    shutil.copytree(DATA / "Au-Ag", folder)
    manifest = (folder / "dataset.json").read_text()
    pair = ac.read_nk(folder / "Rioux-Au20Ag80.yml")
    _yaml_table(folder / "n.yml", "n", pair.lambda_nm / 1000, pair.n)
    _yaml_table(folder / "k.yml", "k", pair.lambda_nm / 1000, pair.k)
    aside = ac.read_nk(folder / "Rioux-Au30Ag70.yml")
    _yaml_table(folder / "aside.yml", "nk", aside.lambda_nm / 1000, aside.n * 1.1, aside.k)
    manifest = manifest.replace('{"x": 0.2, "file": "Rioux-Au20Ag80.yml"}',
                                '{"x": 0.2, "n_file": "n.yml", "k_file": "k.yml"}')
    manifest = manifest.replace('"samples": [', '"samples": [\n    {"x": 0.35, "file": '
                                '"aside.yml", "exclude": "oxidised"},')
    (folder / "dataset.json").write_text(manifest)
    monkeypatch.chdir(tmp_path)
    data = ac.Dataset("Au-Ag")
    assert len(data.excluded) == 1 and len(data) == 11
    return data


def snapshot(folder):
    """Every file below folder with its bytes' digest."""
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(pathlib.Path(folder).rglob("*")) if p.is_file()}


INPUTS = ["Au-Ag/dataset.json", "Au-Ag/Rioux-Au50Ag50.yml", "Au-Ag/aside.yml", "Au-Ag/n.yml",
          "Au-Ag/k.yml"]
WRITERS = {
    "validate(html=)": lambda d, m, p: ac.validate(d, "paper", html=p),
    "validate(json=)": lambda d, m, p: ac.validate(d, "paper", html="r.html", json=p),
    "Model.save": lambda d, m, p: m.save(p),
    "Model.write_spd(eta)": lambda d, m, p: m.write_spd(0.5, p, "k.spd"),
    "Model.write_spd(k)": lambda d, m, p: m.write_spd(0.5, "eta.spd", p),
    "Model.explore": lambda d, m, p: m.explore(p, size=64),
    "Model.explore(data=)": lambda d, m, p: ac.load_model("m.json").explore(p, data=d, size=64),
}


@pytest.mark.parametrize("writer", sorted(WRITERS))
def test_no_input_of_a_data_set_is_written(lab, writer, tmp_path):
    model = ac.fit(lab, "paper")
    model.save("m.json")
    before = snapshot(tmp_path)
    for path in INPUTS + ["./Au-Ag/../Au-Ag/Rioux-Au70Ag30.yml"]:
        with pytest.raises(ac.Error, match=INPUT) as refused:
            WRITERS[writer](lab, model, path)
        assert str(refused.value).startswith("cannot write '%s'" % path)
    assert snapshot(tmp_path) == before  # nothing written, no temporary left


def test_a_selection_keeps_every_file_of_its_data_set(lab, tmp_path):
    # As `fit --data D --exclude X` notes every file of D before leaving X out.
    before = snapshot(tmp_path)
    model = ac.fit(lab.select([0, 0.5, 1]), "paper")
    for path in ("Au-Ag/Rioux-Au70Ag30.yml", "Au-Ag/aside.yml", "Au-Ag/k.yml"):
        with pytest.raises(ac.Error, match=INPUT):
            model.save(path)
        with pytest.raises(ac.Error, match=INPUT):
            ac.validate(lab.without([0.7]).select([0, 0.5, 1]), "paper", json=path)
    assert snapshot(tmp_path) == before


def test_the_same_file_by_a_hard_link(lab, tmp_path):
    os.link("Au-Ag/Rioux-Au60Ag40.yml", "linked.yml")
    before = snapshot(tmp_path)
    with pytest.raises(ac.Error, match=INPUT + r" \('Au-Ag/Rioux-Au60Ag40.yml'\)"):
        ac.fit(lab, "paper").save("linked.yml")
    # A spectrum's file: export's .eta.spd is, by a hard link, the file it was read from.
    os.link("Au-Ag/Rioux-Au60Ag40.yml", "sp.eta.spd")
    before = snapshot(tmp_path)
    with pytest.raises(ac.Error, match=INPUT):
        ac.read_nk("Au-Ag/Rioux-Au60Ag40.yml").export("sp", format="spd")
    assert snapshot(tmp_path) == before


def test_a_loaded_model_is_not_replaced(lab, tmp_path):
    ac.fit(lab, "paper").save("m.json")
    model = ac.load_model("m.json")
    before = snapshot(tmp_path)
    with pytest.raises(ac.Error, match=r"cannot write 'm.json': " + INPUT):
        model.save("m.json")
    with pytest.raises(ac.Error, match=INPUT):
        model.save(os.path.abspath("m.json"))
    # The model a refit started from is an input of the refitted model.
    refit = ac.fit(lab, "paper", refit=model)
    with pytest.raises(ac.Error, match=INPUT):
        refit.save("m.json")
    with pytest.raises(ac.Error, match=INPUT):
        refit.save("Au-Ag/k.yml")
    assert snapshot(tmp_path) == before
    # Written elsewhere, then loaded from there: the export that would replace its file.
    refit.save("out.f82.json")
    again = ac.load_model("out.f82.json")
    before = snapshot(tmp_path)
    with pytest.raises(ac.Error, match=INPUT):
        again.export(0.5, "out", format="f82")
    assert snapshot(tmp_path) == before
    again.export(0.5, "other", format="f82")
    assert os.path.exists("other.f82.json")


def test_symlinks_devices_and_fifos_are_refused(lab, tmp_path):
    model = ac.fit(lab, "paper")
    os.symlink("elsewhere.json", "link.json")
    os.mkfifo("fifo.json")
    for path, words in (("link.json", "it is a symbolic link"),
                        ("/dev/null", "it is a device, FIFO or socket"),
                        ("fifo.json", "it is a device, FIFO or socket")):
        with pytest.raises(ac.Error, match=words):
            model.save(path)
        with pytest.raises(ac.Error, match=words):
            ac.validate(lab, "paper", json=path)
    assert not os.path.exists("elsewhere.json")


def test_the_colour_tables_are_inputs(tmp_path):
    # In a child interpreter whose data root is a copy, so that nothing real is at risk.
    shutil.copytree(DATA / "cie", tmp_path / "data" / "cie")
    shutil.copytree(DATA / "Au-Ag", tmp_path / "data" / "Au-Ag")
    table = tmp_path / "data" / "cie" / "illuminant-D65.csv"
    before = table.read_bytes()
    code = ("import alloycolor as ac\n"
            "m = ac.fit(ac.Dataset('Au-Ag'), 'paper')\n"
            "try:\n    m.save(%r)\nexcept ac.Error as e:\n    print(e)\n" % str(table))
    env = dict(os.environ, ALLOYCOLOR_DATA_DIR=str(tmp_path / "data"))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         check=True).stdout
    assert INPUT in out
    assert table.read_bytes() == before


def test_the_programs_words(lab, binary, tmp_path):
    """The program refuses the same outputs with the same line (after its prefix)."""
    model = ac.fit(lab, "paper")
    for path in INPUTS:
        with pytest.raises(ac.Error) as refused:
            model.save(path)
        run = subprocess.run([binary, "fit", "--data", "Au-Ag", "--method", "paper", "--out",
                              path], capture_output=True, text=True)
        assert run.returncode == 2
        assert run.stderr.strip() == "alloycolor: error: " + str(refused.value)
