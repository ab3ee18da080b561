# Every keyword of every call takes the types and the range of the program's option it
# stands for, and refuses a value in the program's words (issue 49): each keyword is given a
# boolean, a string, a NaN and numbers at, inside and past its bounds (or the names it
# takes and one it does not); where the program has the option, it is given the same value
# as text (as Python spells it) and must accept or refuse it alike, with the same line
# (its flag spelt as the keyword) unless it refused the text before reading it as a number.
# The methods' options are walked in test_method_options.py, with a boolean, a string and
# a NaN here.
import math
import subprocess

import pytest

import alloycolor as ac

NAN = float("nan")


def numbers(lo, hi, whole=False):
    """At, inside and past the bounds, then NaN, a boolean and a string."""
    inside = (lo + hi) / 2
    values = [lo, int(inside) if whole else inside, hi, lo - 1 if lo >= 1 else lo - 0.5,
              hi * 2 + 1]
    if whole:
        values += [lo + 0.5]
    return values + [NAN, True, "1"]


def spelled(value):
    """The text the program is given for a value, as Python spells it."""
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, list):
        return ",".join(spelled(v) for v in value)
    return str(value)


@pytest.fixture(scope="module")
def work(tmp_path_factory, binary):
    """A paper model of Au-Ag fitted by the program, the same model loaded in Python, a
    measured spectrum, three samples for validate, and a folder for outputs."""
    folder = tmp_path_factory.mktemp("keywords")
    path = str(folder / "m.json")
    subprocess.run([binary, "fit", "--data", "Au-Ag", "--method", "paper", "--quiet", "--out",
                    path], check=True, capture_output=True)
    return {"dir": folder, "model_path": path, "model": ac.load_model(path),
            "spectrum": ac.read_nk(ac.data_root() + "/pure/Au-Johnson.yml"),
            "data": ac.Dataset("Au-Ag").select([0, 0.5, 1])}


# keyword: (the call given a value, the program's arguments before the flag, the flag or
# None, the values to walk). The program's arguments name {model} and {dir}.
def _cases():
    M = ["--model", "{model}"]
    return {
        "color(angle_deg)": (lambda w, v: ac.color(w["model"], 0.5, angle_deg=v),
                             ["color"] + M + ["--x", "0.5"], "--angle", numbers(0, 90)),
        "color(observer)": (lambda w, v: ac.color(w["model"], 0.5, observer=v),
                            ["color"] + M + ["--x", "0.5"], "--observer",
                            [2, 10, 5, 2.5, NAN, True, "2"]),
        "color(illuminant)": (lambda w, v: ac.color(w["model"], 0.5, illuminant=v),
                              ["color"] + M + ["--x", "0.5"], "--illuminant",
                              ["D65", "f11", "X", True, 65]),
        "color(sigma)": (lambda w, v: ac.color(w["model"], 0.5, sigma=v), None, None,
                         [True, False, 1, "True", None]),
        "color(exact)": (lambda w, v: ac.color(w["model"], 0.5, exact=v), None, None,
                         [True, False, 0, "False"]),
        "Spectrum.color(angle_deg)": (lambda w, v: w["spectrum"].color(angle_deg=v), None, None,
                                      numbers(0, 90)),
        "match(angle_deg)": (lambda w, v: w["model"].match([80, 5, 30], angle_deg=v),
                             ["match"] + M + ["--lab", "80,5,30"], "--angle", numbers(0, 90)),
        "match(target_sigma)": (lambda w, v: w["model"].match([80, 5, 30], target_sigma=v),
                                ["match"] + M + ["--lab", "80,5,30"], "--target-sigma",
                                numbers(0, 100)),
        "match(margin)": (lambda w, v: w["model"].match([80, 5, 30], margin=v),
                          ["match"] + M + ["--lab", "80,5,30"], "--margin", numbers(0, 1000)),
        "match(observer)": (lambda w, v: w["model"].match([80, 5, 30], observer=v),
                            ["match"] + M + ["--lab", "80,5,30"], "--observer",
                            [2, 10, 5, 2.5, NAN, True, "2"]),
        "match(illuminant)": (lambda w, v: w["model"].match([80, 5, 30], illuminant=v),
                              ["match"] + M + ["--lab", "80,5,30"], "--illuminant",
                              ["A", "X", True, 65]),
        "match(hex)": (lambda w, v: w["model"].match(hex=v), ["match"] + M, "--hex",
                       ["#faefb3", "#ggg", True, 0xfaefb3]),
        "match(lab)": (lambda w, v: w["model"].match(v), ["match"] + M, "--lab",
                       [[80, 5, 30], [-1, 0, 0], [1e308, 0, 0], [NAN, 5, 30], [True, 5, 30],
                        ["80", "5", "30"]]),
        "match(xyz)": (lambda w, v: w["model"].match(xyz=v), ["match"] + M, "--xyz",
                       [[0.5, 0.5, 0.4], [-1, 0.5, 0.5], [1e300, 1, 1], [False, 1, 1]]),
        "match(sigma)": (lambda w, v: w["model"].match([80, 5, 30], sigma=v), None, None,
                         [True, False, 1, "True"]),
        "match(all_minima)": (lambda w, v: w["model"].match([80, 5, 30], all_minima=v), None,
                              None, [True, False, 1, "True"]),
        "tolerance(de)": (lambda w, v: w["model"].tolerance(0.5, de=v),
                          ["tolerance"] + M + ["--x", "0.5"], "--de", numbers(1e-6, 100)),
        "tolerance(angles_deg)": (lambda w, v: w["model"].tolerance(0.5, angles_deg=v),
                                  ["tolerance"] + M + ["--x", "0.5"], "--angles",
                                  numbers(0, 90)),
        "tolerance(illuminants)": (lambda w, v: w["model"].tolerance(0.5, illuminants=v),
                                   ["tolerance"] + M + ["--x", "0.5"], "--illuminants",
                                   ["D65", "X", True, 65]),
        "tolerance(observer)": (lambda w, v: w["model"].tolerance(0.5, observer=v),
                                ["tolerance"] + M + ["--x", "0.5"], "--observer",
                                [2, 10, 5, NAN, True, "10"]),
        "suggest(count)": (lambda w, v: w["model"].suggest(count=v), ["suggest"] + M, "--count",
                           numbers(1, 20, whole=True)),
        "suggest(observer)": (lambda w, v: w["model"].suggest(observer=v), ["suggest"] + M,
                              "--observer", [10, 5, True]),
        "render(size)": (lambda w, v: w["model"].render(0.5, size=v),
                         ["render"] + M + ["--x", "0.5", "--out", "{dir}/r.png"], "--size",
                         numbers(1, 4096, whole=True)),
        "render(roughness)": (lambda w, v: w["model"].render(0.5, size=16, roughness=v),
                              ["render"] + M + ["--x", "0.5", "--size", "16", "--out",
                                                "{dir}/r.png"], "--roughness", numbers(0, 1)),
        "render(shape)": (lambda w, v: w["model"].render(0.5, size=16, shape=v),
                          ["render"] + M + ["--x", "0.5", "--size", "16", "--out",
                                            "{dir}/r.png"], "--shape", ["ring", "cube", True]),
        "render(lighting)": (lambda w, v: w["model"].render(0.5, size=16, lighting=v),
                             ["render"] + M + ["--x", "0.5", "--size", "16", "--out",
                                               "{dir}/r.png"], "--light",
                             ["uniform", "dark", 1]),
        "render(background)": (lambda w, v: w["model"].render(0.5, size=16, background=v),
                               ["render"] + M + ["--x", "0.5", "--size", "16", "--out",
                                                 "{dir}/r.png"], "--background",
                               ["transparent", "green", True]),
        "render(observer)": (lambda w, v: w["model"].render(0.5, size=16, observer=v),
                             ["render"] + M + ["--x", "0.5", "--size", "16", "--out",
                                               "{dir}/r.png"], "--observer", [10, 5, True]),
        "render(direct)": (lambda w, v: w["model"].render(0.5, size=16, direct=v), None, None,
                           [True, 1, "True"]),
        "Spectrum.render(roughness)": (lambda w, v: w["spectrum"].render(size=16, roughness=v),
                                       None, None, numbers(0, 1)),
        "export(roughness)": (lambda w, v: w["model"].export(0.5, str(w["dir"] / "ex"),
                                                             format="gltf", roughness=v),
                              ["export"] + M + ["--x", "0.5", "--format", "gltf", "--out",
                                                "{dir}/ex"], "--roughness", numbers(0, 1)),
        "export(format)": (lambda w, v: w["model"].export(0.5, str(w["dir"] / "ex"), format=v),
                           ["export"] + M + ["--x", "0.5", "--out", "{dir}/ex"], "--format",
                           ["f82", "obj", True]),
        "explore(size)": (lambda w, v: w["model"].explore(str(w["dir"] / "e.html"), size=v,
                                                          illuminants="D65", roughness=[0]),
                          ["explore"] + M + ["--out", "{dir}/e.html", "--illuminants", "D65",
                                             "--roughness", "0"], "--size",
                          numbers(64, 1024, whole=True)),
        "explore(tolerance)": (lambda w, v: w["model"].explore(str(w["dir"] / "e.html"),
                                                               tolerance=v, size=64,
                                                               illuminants="D65",
                                                               roughness=[0]),
                               ["explore"] + M + ["--out", "{dir}/e.html", "--size", "64",
                                                  "--illuminants", "D65", "--roughness", "0"],
                               "--tolerance", [0.01, 0.5, 0.00005, 0.6, NAN, True, "0.1"]),
        "explore(threads)": (lambda w, v: w["model"].explore(str(w["dir"] / "e.html"),
                                                             threads=v, size=64,
                                                             illuminants="D65", roughness=[0]),
                             ["explore"] + M + ["--out", "{dir}/e.html", "--size", "64",
                                                "--illuminants", "D65", "--roughness", "0"],
                             "--threads", [0, 2, -1, 1.5, NAN, True, "2"]),
        "explore(illuminants)": (lambda w, v: w["model"].explore(str(w["dir"] / "e.html"),
                                                                 illuminants=v, size=64,
                                                                 roughness=[0]),
                                 ["explore"] + M + ["--out", "{dir}/e.html", "--size", "64",
                                                    "--roughness", "0"], "--illuminants",
                                 ["A", "X", True]),
        "validate(angles_deg)": (lambda w, v: ac.validate(w["data"], "paper", angles_deg=v),
                                 ["validate", "--data", "{dir}/three", "--methods", "paper",
                                  "--out", "{dir}/v"], "--angles", numbers(0, 90)),
        "validate(observer)": (lambda w, v: ac.validate(w["data"], "paper", observer=v),
                               ["validate", "--data", "{dir}/three", "--methods", "paper",
                                "--out", "{dir}/v"], "--observer", [10, 5, NAN, True]),
        "validate(illuminant)": (lambda w, v: ac.validate(w["data"], "paper", illuminant=v),
                                 ["validate", "--data", "{dir}/three", "--methods", "paper",
                                  "--out", "{dir}/v"], "--illuminant", ["A", "X", True]),
        "read_nk(columns)": (lambda w, v: ac.read_nk(ac.data_root() + "/pure/Au-Johnson.yml",
                                                     columns=v), None, None,
                             [None, True, 2, ("n", True)]),
        "parse_composition(text)": (lambda w, v: w["model"].parse_composition(v), None, None,
                                    ["18k", 0.5, True]),
    }


CASES = _cases()
PARSE_FAILURES = ("Could not convert", "cannot read")


def _package(work, call, value):
    try:
        call(work, value)
    except ac.Error as e:
        return str(e)
    return None


def _program(work, binary, args, flag, value):
    argv = [binary] + [a.format(model=work["model_path"], dir=work["dir"]) for a in args]
    run = subprocess.run(argv + [flag, spelled(value)], capture_output=True, text=True,
                         timeout=120)
    if run.returncode == 0:
        return None
    assert run.returncode == 2, run.stderr
    line = run.stderr.strip().splitlines()[-1]
    return line.removeprefix("alloycolor: error: ").removesuffix(" (see --help)")


@pytest.fixture(scope="module")
def three(work):
    """validate's data set for the program: Au-Ag at 0, 0.5 and 1, as work["data"]."""
    import json
    import shutil
    folder = work["dir"] / "three"
    shutil.copytree(ac.data_root() + "/Au-Ag", folder)
    manifest = json.loads((folder / "dataset.json").read_text())
    manifest["samples"] = [s for s in manifest["samples"] if s["x"] in (0.0, 0.5, 1.0)]
    (folder / "dataset.json").write_text(json.dumps(manifest))
    return folder


def _wrong_type(values, value):
    """Whether value is of another type than the keyword takes (its first value's)."""
    first = values[0]
    if isinstance(first, bool):
        return not isinstance(value, bool)
    if isinstance(first, str):
        return not isinstance(value, str)
    if isinstance(first, (int, float)):
        return isinstance(value, (bool, str)) or value is None
    if isinstance(first, list):
        return any(isinstance(v, (bool, str)) for v in value)
    return isinstance(value, bool)


@pytest.mark.parametrize("name", sorted(CASES))
def test_keyword_as_the_program_takes_it(work, three, binary, name):
    call, args, flag, values = CASES[name]
    keyword = name[name.index("(") + 1:-1]
    assert _package(work, call, values[0]) is None
    for value in values:
        package = _package(work, call, value)
        if _wrong_type(values, value):
            # Refused by its type, naming the keyword (the program reads text only).
            assert package is not None and package.startswith(keyword + ": "), (value, package)
            continue
        if args is None or isinstance(value, tuple):
            continue
        program = _program(work, binary, args, flag, value)
        assert (package is None) == (program is None), (value, package, program)
        if program is None or any(words in program for words in PARSE_FAILURES):
            continue  # the program refused its text before reading a number
        assert package == program.replace(flag + ":", keyword + ":"), value


@pytest.mark.parametrize("option", [o["name"] for o in ac._core._method_options()])
def test_method_options_refuse_booleans_text_and_nan(binary, tmp_path, option):
    declared = next(o for o in ac._core._method_options() if o["name"] == option)
    method = declared["methods"][0]
    kind = declared["kind"]
    wrong = {"flag": [1, "true", NAN], "choice": [True, 1, NAN], "text": [True, 1, NAN]}
    for value in wrong.get(kind, [True, "1", NAN]):
        with pytest.raises(ac.Error) as refused:
            ac.fit("Nb-Sn", method, **{option: value})
        message = str(refused.value)
        assert message.startswith(option + ": "), message
        if kind in ("whole", "number") and isinstance(value, float) and math.isnan(value):
            run = subprocess.run([binary, "fit", "--data", "Nb-Sn", "--method", method,
                                  "--quiet", "--out", str(tmp_path / "m.json"),
                                  declared["flag"], "nan"], capture_output=True, text=True)
            line = run.stderr.strip().splitlines()[-1].removeprefix("alloycolor: error: ")
            assert message == line.removesuffix(" (see --help)").replace(declared["flag"], option)


def test_the_settings_ranges_are_the_programs(binary):
    """The bounds walked above are what the program's help says."""
    text = subprocess.run([binary, "match", "--help"], capture_output=True, text=True).stdout
    assert "NUMBER in [0, 100]" in text and "NUMBER in [0, 1000]" in text
    text = subprocess.run([binary, "tolerance", "--help"], capture_output=True, text=True).stdout
    assert "NUMBER in [1e-06, 100]" in text
    text = subprocess.run([binary, "suggest", "--help"], capture_output=True, text=True).stdout
    assert "INT in [1, 20]" in text
    assert ac._core._max_tile_size == 4096
