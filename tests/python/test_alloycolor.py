"""Tests of the alloycolor Python package against independent references: the command-line
program's output (the same libraries driven through another front end, compared at the
precision it prints), an independent numpy colour chain written here from the CIE tables
(Fresnel eq. 2-4, XYZ eq. 5, CIELAB), the measured spectra themselves, and analytic
identities. Bad input must raise alloycolor.Error naming the culprit; a failing progress
callback must leave no file behind."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import alloycolor as ac
from conftest import DATA


def run_json(binary, *args):
    out = subprocess.run([binary, *args, "--json", "--quiet"], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


# ---- an independent colour chain in numpy -------------------------------------------------

def read_cie(name):
    rows = [line for line in (DATA / "cie" / name).read_text().splitlines()
            if line and not line.startswith("#")]
    table = np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    return table[:, 0], table[:, 1:]


def read_rioux_yaml(path):
    """The three-column rows of a refractiveindex.info 'tabulated nk' entry, um -> nm."""
    rows = []
    for line in pathlib.Path(path).read_text().splitlines():
        parts = line.split()
        if len(parts) == 3:
            try:
                rows.append([float(p) for p in parts])
            except ValueError:
                pass
    t = np.array(rows)
    return 1000.0 * t[:, 0], t[:, 1] + 1j * t[:, 2]


def fresnel_r(N, angle_deg):
    c = np.cos(np.radians(angle_deg))
    s2 = np.sin(np.radians(angle_deg)) ** 2
    root = np.sqrt(N * N - s2 + 0j)
    rp = np.abs((N * N * c - root) / (N * N * c + root)) ** 2
    rs = np.abs((c - root) / (c + root)) ** 2
    return 0.5 * (rp + rs)


def numpy_chain(lambda_nm, N, angle_deg, illuminant="D65", observer=2):
    lam_cmf, cmf = read_cie("cmf-1931-2.csv" if observer == 2 else "cmf-1964-10.csv")
    lam_p, p = read_cie("illuminant-%s.csv" % illuminant)
    lo, hi = max(lam_cmf[0], lam_p[0]), min(lam_cmf[-1], lam_p[-1])
    grid = np.arange(lo, hi + 0.5, 5.0)
    cmf_g = np.stack([np.interp(grid, lam_cmf, cmf[:, i]) for i in range(3)], axis=1)
    p_g = np.interp(grid, lam_p, p[:, 0])
    n = np.interp(grid, lambda_nm, N.real)
    k = np.interp(grid, lambda_nm, N.imag)
    R = fresnel_r(n + 1j * k, angle_deg)
    norm = np.sum(p_g * cmf_g[:, 1])
    xyz = (p_g * R) @ cmf_g / norm
    white = p_g @ cmf_g / norm
    t = xyz / white
    f = np.where(t > (6 / 29) ** 3, np.cbrt(t), t / (3 * (6 / 29) ** 2) + 4 / 29)
    lab = np.array([116 * f[1] - 16, 500 * (f[0] - f[1]), 200 * (f[1] - f[2])])
    m = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415],
                  [0.0557, -0.2040, 1.0570]])
    return xyz, lab, m @ xyz


@pytest.mark.parametrize("angle", [0.0, 60.0])
@pytest.mark.parametrize("illuminant,observer", [("D65", 2), ("A", 10)])
def test_measured_colour_equals_numpy_chain(angle, illuminant, observer):
    path = DATA / "Au-Ag" / "Rioux-Au50Ag50.yml"
    lam, N = read_rioux_yaml(path)
    xyz, lab, _ = numpy_chain(lam, N, angle, illuminant, observer)
    c = ac.color(str(path), angle_deg=angle, illuminant=illuminant, observer=observer)
    np.testing.assert_allclose(c["xyz"], xyz, atol=1e-6, rtol=0)
    np.testing.assert_allclose(c["lab"], lab, atol=1e-4, rtol=0)


def test_model_colour_equals_numpy_chain_over_arrays(au_ag):
    model = ac.fit(au_ag, "smooth")
    xs = np.array([0.05, 0.33, 0.75])
    angles = np.array([[0.0], [45.0]])
    c = model.color(xs, angle_deg=angles)
    assert c["xyz"].shape == (2, 3, 3) and c["srgb8"].dtype == np.uint8
    grid = np.arange(360.0, 831.0, 5.0)
    for i, a in enumerate(angles[:, 0]):
        for j, x in enumerate(xs):
            N = model.nk(x, grid)
            xyz, lab, lin = numpy_chain(grid, N, a)
            np.testing.assert_allclose(c["xyz"][i, j], xyz, atol=1e-6, rtol=0)
            np.testing.assert_allclose(c["lab"][i, j], lab, atol=1e-4, rtol=0)
            np.testing.assert_allclose(c["linear_srgb"][i, j], lin, atol=1e-3, rtol=0)


def test_many_compositions_table_within_tolerance(au_ag):
    model = ac.fit(au_ag, "eps-linear")
    xs = np.linspace(0, 1, 2001)
    table = model.color(xs)["xyz"]
    exact = model.color(xs[::50], exact=True)["xyz"]
    np.testing.assert_allclose(table[::50], exact, atol=1e-6, rtol=0)


# ---- the command line as a reference ---------------------------------------------------------

def test_colour_of_paper_model_equals_command_line(binary, au_ag):
    cli = run_json(binary, "color", "--data", "Au-Ag", "--method", "paper", "--x", "0.3,0.75", "--angle", "30")
    model = ac.fit(au_ag, "paper")
    c = model.color([0.3, 0.75], angle_deg=30, sigma=True)
    for i, r in enumerate(cli["results"]):
        np.testing.assert_allclose(c["xyz"][i], r["XYZ"], atol=1e-9)
        np.testing.assert_allclose(c["lab"][i], r["Lab"], atol=1e-9)
        assert list(c["srgb8"][i]) == r["srgb8"]
    assert (c["sigma"] is None) == ("delta_e00_sigma" not in cli["results"][0])


def test_smooth_fit_save_and_colour_equal_command_line(binary, au_ag, tmp_path):
    cli_model = tmp_path / "cli.json"
    subprocess.run([binary, "fit", "--data", "Au-Ag", "--method", "smooth", "--out",
                    str(cli_model), "--quiet"], check=True)
    cli = run_json(binary, "color", "--model", str(cli_model), "--x", "0.55,18k")
    model = ac.fit(au_ag, "smooth")
    xs = [0.55, model.parse_composition("18k")]
    c = model.color(xs, sigma=True)
    for i, r in enumerate(cli["results"]):
        assert r["x"] == pytest.approx(xs[i], abs=1e-12)
        np.testing.assert_allclose(c["xyz"][i], r["XYZ"], atol=1e-8)
        assert list(c["srgb8"][i]) == r["srgb8"]
        assert c["sigma"][i] == pytest.approx(r["delta_e00_sigma"], rel=1e-6)
    # The model the program wrote and the one Python fitted predict the same n, k.
    loaded = ac.load_model(cli_model)
    lam = np.linspace(380, 780, 41)
    np.testing.assert_allclose(loaded.nk(xs, lam), model.nk(xs, lam), atol=1e-9)
    saved = tmp_path / "py.json"
    model.save(saved)
    cli2 = run_json(binary, "color", "--model", str(saved), "--x", "0.55,18k")
    np.testing.assert_allclose([r["XYZ"] for r in cli2["results"]], c["xyz"], atol=1e-9)


def test_smooth_fit_in_the_space_given_equals_command_line(binary, au_ag, tmp_path):
    cli_model = tmp_path / "log.json"
    subprocess.run([binary, "fit", "--data", "Au-Ag", "--method", "smooth", "--space", "log_eps",
                    "--out", str(cli_model), "--quiet"], check=True)
    model = ac.fit(au_ag, "smooth", space="log_eps")
    lam = np.linspace(380, 780, 41)
    np.testing.assert_allclose(ac.load_model(cli_model).nk([0.3, 0.85], lam),
                               model.nk([0.3, 0.85], lam), atol=1e-9)
    with pytest.raises(ac.Error, match="^space: 'magic' is none of eps, log_eps$"):
        ac.fit(au_ag, "smooth", space="magic")


def assert_same(a, b, path="report"):
    """Equal structure; numbers equal to 1e-9 relative."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and sorted(a) == sorted(b), path
        for key in a:
            assert_same(a[key], b[key], path + "." + key)
    elif isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), path
        for i, (u, v) in enumerate(zip(a, b)):
            assert_same(u, v, "%s[%d]" % (path, i))
    elif isinstance(a, float):
        assert a == pytest.approx(b, rel=1e-9, abs=1e-12), path
    else:
        assert a == b, path


def test_validation_equals_command_line(binary, au_ag, tmp_path):
    out = tmp_path / "cli-report"
    subprocess.run([binary, "validate", "--data", "Au-Ag", "--holdout", "0.3,0.7",
                    "--methods", "paper,eps-linear", "--out", str(out), "--quiet"], check=True)
    cli = json.loads((out / "report.json").read_text())
    html = tmp_path / "py.html"
    report = ac.validate(au_ag, methods=["paper", "eps-linear"], holdout=[0.3, "70at%"],
                         html=html)
    assert html.read_text().lstrip().lower().startswith("<!doctype html")
    assert len(report["holdouts"]) == 2
    for mine, theirs in zip(report["holdouts"], cli["holdouts"]):
        assert mine["x"] == theirs["x"]
        for method in ("paper", "eps-linear"):
            assert_same(mine["results"][method], theirs["results"][method])


def test_auto_is_the_default_fit_and_chooses_as_the_command_line(binary, tmp_path):
    # Cu-Zn (Werner's zinc): the same choice and table as `alloycolor fit` (whose default
    # is auto too), and validate takes "auto" and "all".
    data = os.path.join(DATA, "Cu-Zn", "dataset-werner-zn.json")
    subprocess.run([binary, "fit", "--data", data, "--out", str(tmp_path / "a.json"),
                    "--quiet"], check=True)
    cli = json.loads((tmp_path / "a.json").read_text())
    model = ac.fit(data)
    mine = model.to_json()
    assert model.method == cli["method"] != "auto"
    assert mine["fit"]["selection"]["reason"] == cli["fit"]["selection"]["reason"]
    assert [r.get("mean") for r in mine["fit"]["selection"]["scores"]] == \
        [r.get("mean") for r in cli["fit"]["selection"]["scores"]]
    report = ac.validate(data, methods="all", holdout=[0.85], angles_deg=[0])
    expected = {m["name"] for m in ac.methods()} | {"auto"}
    assert set(report["holdouts"][0]["results"]) == expected


# ---- optical constants ---------------------------------------------------------------------

def test_samples_are_named_as_the_manifest_names_them():
    # Cu-Zn's manifest gives weight fractions: 0.85 is its 85wt% sample (85.4 at% Cu).
    brass = ac.Dataset("Cu-Zn")
    by_number, by_weight = brass.without([0.85]), brass.without(["85wt%"])
    assert len(by_number) == len(brass) - 1
    assert list(by_number.x_atomic) == list(by_weight.x_atomic)
    assert abs(brass.select([0.85]).x_atomic[0] - 0.854) < 1e-3


def test_read_nk_equals_file_rows():
    path = DATA / "Au-Ag" / "Rioux-Au50Ag50.yml"
    lam, N = read_rioux_yaml(path)
    s = ac.read_nk(path)
    np.testing.assert_allclose(s.lambda_nm, lam, rtol=1e-12)
    np.testing.assert_allclose(s.nk, N, rtol=1e-12)


def test_eps_linear_reproduces_samples_and_broadcasts(au_ag):
    model = ac.fit(au_ag, "eps-linear")
    lam = np.array([[400.0, 500.0], [600.0, 700.0]])
    sample = au_ag.samples[4]
    direct_lam, direct_N = read_rioux_yaml(sample["path"])
    got = model.nk(sample["x_atomic"], lam)
    assert got.shape == (2, 2)
    want = np.interp(lam, direct_lam, direct_N.real) + 1j * np.interp(lam, direct_lam,
                                                                      direct_N.imag)
    np.testing.assert_allclose(got, want, atol=1e-9)
    grid = model.nk([0.1, 0.2, 0.3], lam)
    assert grid.shape == (3, 2, 2)
    eps = model.permittivity([0.1, 0.2, 0.3], lam)
    np.testing.assert_allclose(grid ** 2, eps, atol=1e-9)  # eps = N^2 (eq. 9, 10)
    assert np.all(grid.real >= 0) and np.all(grid.imag >= 0)


def test_methods_come_from_the_registry():
    names = [m["name"] for m in ac.methods()]
    assert {"paper", "eps-linear", "smooth", "physical"} <= set(names)
    assert all(m["summary"] for m in ac.methods())


# ---- pictures and exports ------------------------------------------------------------------

def test_render_and_spd_exports(au_ag, tmp_path):
    model = ac.fit(au_ag, "eps-linear")
    img = model.render(0.75, size=64, lighting="uniform", background="transparent")
    assert img.shape == (64, 64, 4) and img.dtype == np.uint8
    assert img[32, 32, 3] == 255 and img[0, 0, 3] == 0
    lin = model.render(0.75, size=32, linear=True)
    assert lin.dtype == np.float32 and np.all(np.isfinite(lin))
    eta, k = tmp_path / "au.eta.spd", tmp_path / "au.k.spd"
    model.write_spd(0.75, eta, k)
    rows = lambda p: np.array([[float(v) for v in l.split()] for l in p.read_text().splitlines()
                               if l.strip() and not l.startswith("#")])
    e, kk = rows(eta), rows(k)
    N = model.nk(0.75, e[:, 0])
    np.testing.assert_allclose(e[:, 1], N.real, rtol=1e-5, atol=1e-6)
    np.testing.assert_allclose(kk[:, 1], N.imag, rtol=1e-5, atol=1e-6)
    s = model.spectra(0.75)
    np.testing.assert_allclose(s["lambda_nm"], e[:, 0])


# ---- bad input -------------------------------------------------------------------------------

def test_errors_are_value_errors_naming_the_culprit(au_ag, tmp_path):
    assert issubclass(ac.Error, ValueError)
    missing = tmp_path / "no-such-file.yml"
    with pytest.raises(ac.Error, match="no-such-file.yml"):
        ac.read_nk(missing)
    bad = tmp_path / "bad.csv"
    bad.write_text("lambda_nm,n,k\n400,0.5,2.0\n500,abc,2.1\n")
    with pytest.raises(ac.Error, match="bad.csv"):
        ac.read_nk(bad)
    with pytest.raises(ac.Error, match="no-such-set"):
        ac.Dataset("no-such-set")
    with pytest.raises(ac.Error, match="bogus"):
        ac.fit(au_ag, "bogus")
    model = ac.fit(au_ag, "eps-linear")
    with pytest.raises(ac.Error, match="1.5"):
        model.nk(1.5, [500.0])
    with pytest.raises(ac.Error, match="D99"):
        model.color(0.5, illuminant="D99")
    with pytest.raises(ac.Error, match="95"):
        model.color(0.5, angle_deg=95)
    with pytest.raises(ac.Error, match="0.45"):
        ac.validate(au_ag, holdout=[0.45])
    with pytest.raises(ac.Error, match="0.5"):
        ac.Dataset("Cu-Zn").without([0.5])
    with pytest.raises(ac.Error, match="ellipse"):
        model.render(0.5, shape="ellipse")
    broken = tmp_path / "broken.json"
    broken.write_text('{"format": "alloycolor-model", "version": 1')
    with pytest.raises(ac.Error, match="broken.json"):
        ac.load_model(broken)


class Stop(Exception):
    pass


def test_interrupted_work_leaves_nothing_written(au_ag, tmp_path):
    messages = []

    def stop_at_first(message):
        messages.append(message)
        raise Stop("interrupted by the user")

    with pytest.raises(Stop):
        ac.fit(au_ag, "smooth", progress=stop_at_first)
    assert messages  # the fit did report progress before it stopped
    html, js = tmp_path / "report.html", tmp_path / "report.json"
    with pytest.raises(Stop):
        ac.validate(au_ag, methods=["paper"], html=html, json=js, progress=stop_at_first)
    assert os.listdir(tmp_path) == []
    # An existing model file is replaced whole or not at all.
    target = tmp_path / "model.json"
    model = ac.fit(au_ag, "eps-linear")
    model.save(target)
    before = target.read_text()
    with pytest.raises(ac.Error):
        model.save(tmp_path / "missing-dir" / "model.json")
    assert target.read_text() == before and sorted(os.listdir(tmp_path)) == ["model.json"]


def test_progress_messages_reach_the_callback(au_ag):
    seen = []
    model = ac.fit(au_ag, "smooth", progress=seen.append)
    assert model.method == "smooth" and seen and all(isinstance(m, str) for m in seen)


def test_illuminants_and_observers_broadcast(au_ag):
    model = ac.fit(au_ag, "eps-linear")
    c = model.color(0.6, illuminant=["D65", "A", "F11"], observer=[[2], [10]])
    assert c["xyz"].shape == (2, 3, 3)
    for i, obs in enumerate((2, 10)):
        for j, ill in enumerate(("D65", "A", "F11")):
            one = model.color(0.6, illuminant=ill, observer=obs)
            np.testing.assert_array_equal(c["xyz"][i, j], one["xyz"])
    assert c["xyz"][0, 0, 1] != c["xyz"][0, 1, 1]


def test_stated_precision_sets_the_floor(au_ag, tmp_path):
    # The bundled Au-Ag samples at 0, 0.5, 1 with a stated precision of n and k: the data set
    # reports it, and the one-sigma at a training composition (where only the precision
    # is left) grows from what the printed digits resolve (a lab stating its data exact) to
    # what the lab states; stating none takes a typical measurement's, 0.01 in n and k.
    samples = [{"x": s["x_atomic"], "file": s["path"]} for s in au_ag.samples
               if round(s["x_atomic"], 6) in (0.0, 0.5, 1.0)]
    manifest = {"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
                "samples": samples}
    (tmp_path / "dataset.json").write_text(json.dumps(manifest))
    digits = ac.Dataset(tmp_path)
    assert digits.precision == {"n": 0.0, "k": 0.0}
    manifest["precision"] = {"n": 0.01, "k": 0.01}
    (tmp_path / "dataset.json").write_text(json.dumps(manifest))
    stated = ac.Dataset(tmp_path)
    assert stated.precision == {"n": 0.01, "k": 0.01}
    sigma_typical = ac.fit(digits, "eps-linear").color(0.5, sigma=True)["sigma"]
    sigma_stated = ac.fit(stated, "eps-linear").color(0.5, sigma=True)["sigma"]
    assert sigma_stated == pytest.approx(sigma_typical, rel=1e-9)
    manifest["precision"] = {"n": 0, "k": 0}
    (tmp_path / "dataset.json").write_text(json.dumps(manifest))
    sigma_digits = ac.fit(ac.Dataset(tmp_path), "eps-linear").color(0.5, sigma=True)["sigma"]
    assert sigma_stated > 10 * sigma_digits
    manifest["precision"] = {"n": -1}
    (tmp_path / "dataset.json").write_text(json.dumps(manifest))
    with pytest.raises(ac.Error, match="precision: n: '-1' is not a standard deviation"):
        ac.Dataset(tmp_path)


def test_every_property_of_dataset_and_model_reads(au_ag):
    # Each property the Python classes declare answers (none reaches into the core for an
    # attribute the binding lacks, as a Model.precision copied from Dataset once did).
    model = ac.fit(au_ag, "eps-linear")
    for obj in (au_ag, model):
        names = [n for n, v in vars(type(obj)).items() if isinstance(v, property)]
        assert names
        for name in names:
            getattr(obj, name)


# ---- replicates ----------------------------------------------------------------------------

def test_replicates_load_fit_and_validate(au_ag, tmp_path):
    # Two films at x = 0.5: the bundled one and a copy with k 12 % higher. The data set keeps
    # both; the interpolating methods pass through their mean; leave-one-out holds out both
    # films together, one result row each; a film is held out alone by its file name.
    samples = []
    for s in au_ag.samples:
        if round(s["x_atomic"], 6) not in (0.0, 0.2, 0.5, 0.8, 1.0):
            continue
        samples.append({"x": s["x_atomic"], "file": s["path"]})
        if abs(s["x_atomic"] - 0.5) < 1e-9:
            sp = s["spectrum"]
            rows = ["lambda_nm,n,k"] + ["%.17g,%.17g,%.17g" % (l, n, 1.12 * k)
                                            for l, n, k in zip(sp.lambda_nm, sp.n, sp.k)]
            (tmp_path / "film2.csv").write_text("\n".join(rows) + "\n")
            samples.append({"x": 0.5, "file": "film2.csv"})
    (tmp_path / "dataset.json").write_text(json.dumps(
        {"system": {"a": "Au", "b": "Ag"}, "composition": "atomic_fraction_a",
         "samples": samples}))
    data = ac.Dataset(tmp_path)
    assert len(data) == 6
    assert list(data.x_atomic).count(0.5) == 2
    assert data.samples[3]["file"] == "film2.csv"

    first, second = [s["spectrum"] for s in data.samples if s["x_atomic"] == 0.5]
    eps = (first.n + 1j * first.k) ** 2 / 2 + (second.n + 1j * second.k) ** 2 / 2
    model = ac.fit(data, "eps-linear")
    assert len(model.to_json()["training_samples"]) == 6
    np.testing.assert_allclose(model.permittivity(0.5, first.lambda_nm[10:-10]),
                               eps[10:-10], rtol=1e-9)
    smooth = ac.fit(data, "smooth")
    assert smooth.color(0.5, sigma=True)["sigma"] > 0

    loo = ac.validate(data, methods=["eps-linear"], angles_deg=[0])
    assert len(loo["holdouts"]) == 4
    assert [h["file"] for h in loo["holdouts"] if h["x"] == 0.5][1] == "film2.csv"
    assert len({h["split"] for h in loo["holdouts"]}) == 3
    one = ac.validate(data, methods=["eps-linear"], holdout=["film2.csv"], angles_deg=[0])
    assert [h["file"] for h in one["holdouts"]] == ["film2.csv"]
    assert one["splits"][0]["train_x"].count(0.5) == 1
    both = ac.validate(data, methods=["eps-linear"], holdout=[0.5], angles_deg=[0])
    assert len(both["holdouts"]) == 2
