"""One library, two faces: what the Python package and the ``alloycolor`` program compute
from the same input must be the same. Export files byte for byte (every format), render
pixels exactly, the render's table guard refusing the same material, colours to 1e-12."""
import json
import pathlib
import struct
import subprocess
import zlib

import numpy as np
import pytest

import alloycolor as ac
from conftest import DATA

GOLD = DATA / "pure" / "Au-Johnson.yml"
FORMATS = ["spd", "rgb-conductor", "f82", "gulbrandsen", "materialx", "gltf", "all"]


def run(binary, *args):
    return subprocess.run([binary, *map(str, args)], capture_output=True, text=True)


@pytest.fixture(scope="module")
def model_file(binary, tmp_path_factory):
    """A model the program fitted; the program reads it with --model, Python with load_model."""
    path = tmp_path_factory.mktemp("model") / "auag.json"
    subprocess.run([binary, "fit", "--data", "Au-Ag", "--method", "eps-linear", "--out",
                    str(path), "--quiet"], check=True)
    return path


# ---- export ---------------------------------------------------------------------------------

def files_of(written):
    """{path: bytes} of the files written, which are then removed for the other face."""
    out = {}
    for path in written:
        p = pathlib.Path(path)
        out[path] = p.read_bytes()
        p.unlink()
    return out


def compare_exports(binary, cli_args, python_export, prefix):
    """The program writes to prefix, then Python to the same prefix: same files, same bytes,
    and Python's result is the program's --json document plus the notes."""
    cli = run(binary, "export", *cli_args, "--out", prefix, "--json", "--quiet")
    assert cli.returncode == 0, cli.stderr
    doc = json.loads(cli.stdout)
    cli_files = files_of(doc["files"])
    result = python_export(str(prefix))
    py_files = files_of(result["files"])
    assert list(py_files) == list(cli_files)
    for path, content in cli_files.items():
        assert py_files[path] == content, path
    notes = result.pop("notes")
    assert isinstance(notes, list)
    assert result == doc
    return cli_files


@pytest.mark.parametrize("fmt", FORMATS)
def test_model_export_writes_the_programs_files(binary, model_file, tmp_path, fmt):
    model = ac.load_model(str(model_file))
    compare_exports(binary, ["--model", model_file, "--x", "18k", "--format", fmt,
                             "--roughness", "0.25"],
                    lambda prefix: model.export("18k", prefix, format=fmt, roughness=0.25),
                    tmp_path / "gold")


@pytest.mark.parametrize("fmt", FORMATS)
def test_spectrum_export_writes_the_programs_files(binary, tmp_path, fmt):
    scene = tmp_path / "scene"
    scene.mkdir()
    (tmp_path / "materials").mkdir()
    spectrum = ac.read_nk(str(GOLD))
    compare_exports(binary, ["--nk", GOLD, "--format", fmt, "--scene-dir", scene],
                    lambda prefix: spectrum.export(prefix, format=fmt, scene_dir=scene),
                    tmp_path / "materials" / "au")


def test_model_export_writes_the_programs_blender_table(binary, model_file, tmp_path):
    model = ac.load_model(str(model_file))
    compare_exports(binary, ["--model", model_file, "--format", "blender-table"],
                    lambda prefix: model.export("18k", prefix, format="blender-table"),
                    tmp_path / "gold")


def test_fitted_model_export_names_its_data_as_the_program_does(binary, tmp_path):
    model = ac.fit("Au-Ag", "paper")
    files = compare_exports(binary, ["--data", "Au-Ag", "--method", "paper", "--x", "0.75",
                                     "--format", "all"],
                            lambda prefix: model.export(0.75, prefix), tmp_path / "auag")
    eta = files[str(tmp_path / "auag.eta.spd")].decode()
    assert "paper model built from data Au-Ag" in eta
    assert model.spectra(0.75)["material"] in eta  # spectra and write_spd describe it so too


def test_export_refuses_bad_settings_and_writes_nothing(model_file, tmp_path):
    model = ac.load_model(str(model_file))
    for kwargs, culprit in [({"format": "obj"}, "format"), ({"roughness": 1.5}, "roughness"),
                            ({"scene_dir": tmp_path / "none"}, "scene_dir")]:
        with pytest.raises(ac.Error, match=culprit):
            model.export(0.5, tmp_path / "x", **kwargs)
    assert list(tmp_path.iterdir()) == []


# ---- render ---------------------------------------------------------------------------------

def read_png_rgba8(path):
    """The pixels of an 8-bit RGBA PNG (colour type 6, no interlace), as (h, w, 4) uint8."""
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (8, 6, 0)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride, bpp = 4 * width, 4
    rows, prev = [], bytearray(stride)
    for j in range(height):
        start = j * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return np.frombuffer(b"".join(rows), dtype=np.uint8).reshape(height, width, 4)


# Without a background both take the lighting's default.
RENDER_SETTINGS = [
    dict(shape="sphere", lighting="studio", roughness=0.0),
    dict(shape="ring", lighting="studio", roughness=0.3, background="transparent"),
    dict(shape="sphere", lighting="uniform", roughness=0.0, illuminant="A", observer=10),
    dict(shape="ring", lighting="uniform", roughness=0.1, background="backdrop"),
]


def render_args(size, s):
    background = ["--background", s["background"]] if "background" in s else []
    return ["--size", size, "--shape", s["shape"], "--light", s["lighting"], "--roughness",
            s["roughness"], *background, "--illuminant", s.get("illuminant", "D65"),
            "--observer", s.get("observer", 2), "--quiet"]


@pytest.mark.parametrize("settings", RENDER_SETTINGS)
def test_model_render_gives_the_programs_pixels(binary, model_file, tmp_path, settings):
    size, xs = 40, ["0.3", "18k"]
    out = tmp_path / "tiles.png"
    cli = run(binary, "render", "--model", model_file, "--x", ",".join(xs), "--out", out,
              *render_args(size, settings))
    assert cli.returncode == 0, cli.stderr
    sheet = read_png_rgba8(out)
    model = ac.load_model(str(model_file))
    for m, x in enumerate(xs):
        tile = model.render(x, size=size, **settings)
        np.testing.assert_array_equal(tile, sheet[:, m * size:(m + 1) * size])


@pytest.mark.parametrize("direct", [False, True])
def test_spectrum_render_gives_the_programs_pixels(binary, tmp_path, direct):
    out = tmp_path / "gold.png"
    cli = run(binary, "render", "--nk", GOLD, "--size", 32, "--out", out, "--quiet",
              *(["--direct"] if direct else []))
    assert cli.returncode == 0, cli.stderr
    image = ac.read_nk(str(GOLD)).render(size=32, direct=direct)
    np.testing.assert_array_equal(image, read_png_rgba8(out))


def test_render_refuses_what_the_program_refuses(binary, tmp_path):
    # n barely above 1, k = 0: R(mu) falls as mu^-4 from grazing, too steep for any table.
    nearly_vacuum = tmp_path / "nearly-vacuum.csv"
    nearly_vacuum.write_text("lambda_nm,n,k\n" +
                             "".join("%d,1.00000001,0\n" % l for l in range(300, 901, 10)))
    cli = run(binary, "render", "--nk", nearly_vacuum, "--size", 16, "--out", tmp_path / "v.png")
    assert cli.returncode == 2
    spectrum = ac.read_nk(str(nearly_vacuum))
    with pytest.raises(ac.Error) as refusal:
        spectrum.render(size=16)
    message = str(refusal.value)
    assert "above the limit" in message
    assert cli.stderr.strip() == "alloycolor: error: %s (--direct)" % message
    assert not (tmp_path / "v.png").exists()
    # Both render it by direct spectral evaluation, to the same pixels.
    cli = run(binary, "render", "--nk", nearly_vacuum, "--size", 16, "--direct", "--quiet",
              "--out", tmp_path / "v.png")
    assert cli.returncode == 0, cli.stderr
    np.testing.assert_array_equal(spectrum.render(size=16, direct=True),
                                  read_png_rgba8(tmp_path / "v.png"))


# ---- colour ---------------------------------------------------------------------------------

@pytest.mark.parametrize("angle", [0.0, 45.0, 80.0])
@pytest.mark.parametrize("illuminant,observer", [("D65", 2), ("A", 10), ("F11", 2)])
def test_colours_equal_the_programs_to_1e_12(binary, model_file, angle, illuminant, observer):
    common = ["--angle", angle, "--illuminant", illuminant, "--observer", observer, "--json",
              "--quiet"]
    xs = [0.1, 0.5, 0.75, 0.95]
    cli = json.loads(run(binary, "color", "--model", model_file, "--x",
                         ",".join(map(str, xs)), *common).stdout)
    c = ac.load_model(str(model_file)).color(xs, angle_deg=angle, illuminant=illuminant,
                                             observer=observer)
    for i, r in enumerate(cli["results"]):
        np.testing.assert_allclose(c["xyz"][i], r["XYZ"], rtol=0, atol=1e-12)
        np.testing.assert_allclose(c["lab"][i], r["Lab"], rtol=0, atol=1e-12)
        assert list(c["srgb8"][i]) == r["srgb8"]
    cli = json.loads(run(binary, "color", "--nk", GOLD, *common).stdout)
    c = ac.read_nk(str(GOLD)).color(angle_deg=angle, illuminant=illuminant, observer=observer)
    r = cli["results"][0] if "results" in cli else cli
    np.testing.assert_allclose(c["xyz"], r["XYZ"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(c["lab"], r["Lab"], rtol=0, atol=1e-12)
    assert list(c["srgb8"]) == r["srgb8"]
