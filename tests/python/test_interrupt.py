# Ctrl-C during a long call (issue 49): the work runs without the GIL while the caller's
# thread runs Python's signal handlers, and the library stops at its next step (its cancel
# check, core/progress.h), so a SIGINT ends each long call with KeyboardInterrupt within
# moments, where it used to be acted on only when the call returned; nothing is written,
# no temporary is left. Each call runs in a child interpreter sent SIGINT a moment after
# it starts; uninterrupted, each takes many seconds more (measured when this was written:
# validate "all" 285 s, fit "auto" 7 s, explore 4 s, render 18 s, the colours 50 s).
import json
import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import alloycolor as ac

# The longest a call may take to stop after SIGINT: generous for a loaded machine; the
# calls stop in a fraction of a second (the slowest steps: a solver iteration, a split's
# setup, a block of rows).
STOP_SECONDS = 4.0

CHILD = r"""
import os, sys, numpy as np, alloycolor as ac
what, spread, model_path, out = sys.argv[1:5]
model = ac.load_model(model_path)
calls = {
    "validate": lambda: ac.validate(spread, "all", html=os.path.join(out, "report.html"),
                                    json=os.path.join(out, "report.json")),
    "fit": lambda: ac.fit(spread, "auto").save(os.path.join(out, "m.json")),
    "explore": lambda: model.explore(os.path.join(out, "e.html"), size=1024, tolerance=1e-4),
    "render": lambda: np.save(os.path.join(out, "r.npy"),
                              model.render(0.5, size=4096, direct=True)),
    "colour": lambda: np.save(os.path.join(out, "c.npy"),
                              model.color(np.linspace(0, 1, 200000), sigma=True)["lab"]),
    "export": lambda: model.export(0.5, os.path.join(out, "t"), format="blender-table"),
}
print("ready", flush=True)
try:
    calls[what]()
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    sys.exit(0)
print("returned", flush=True)
"""


@pytest.fixture(scope="module")
def spread(tmp_path_factory):
    """A composition spread of 40 Au-Ag films (n, k of the smooth model of Au-Ag with 1 %
    scatter, 360-830 nm) and a smooth model fitted to it: work that takes a while."""
    folder = tmp_path_factory.mktemp("spread")
    model = ac.fit(ac.Dataset("Au-Ag"), "smooth")
    lam = np.arange(360.0, 831.0, 10.0)
    rng = np.random.default_rng(49)
    samples = []
    for i, x in enumerate(np.linspace(0, 1, 40)):
        nk = model.nk(x, lam) * (1 + 0.01 * rng.standard_normal(lam.size))
        name = "film%02d.csv" % i
        rows = ["wavelength_nm,n,k"] + ["%g,%.6f,%.6f" % (l, v.real, abs(v.imag))
                                        for l, v in zip(lam, nk)]
        (folder / name).write_text("\n".join(rows) + "\n")
        samples.append({"x": round(float(x), 6), "file": name})
    (folder / "dataset.json").write_text(json.dumps({
        "name": "spread", "system": {"a": "Au", "b": "Ag"},
        "composition": "atomic_fraction_a", "samples": samples}))
    ac.fit(ac.Dataset(str(folder)), "smooth").save(folder.parent / "spread-smooth.json")
    return folder


@pytest.mark.parametrize("what", ["validate", "fit", "explore", "render", "colour"])
def test_ctrl_c_stops_a_long_call(spread, tmp_path, what):
    out = tmp_path / "out"
    out.mkdir()
    child = subprocess.Popen(
        [sys.executable, "-c", CHILD, what, str(spread), str(spread.parent / "spread-smooth.json"),
         str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "ready"
        time.sleep(1.0)  # the call is under way
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        stdout, stderr = child.communicate(timeout=60)
        stopped = time.monotonic() - sent
    finally:
        if child.poll() is None:
            child.kill()
    assert stdout.strip() == "KeyboardInterrupt", (stdout, stderr)
    assert stopped < STOP_SECONDS, stopped
    assert os.listdir(out) == []  # nothing written, no temporary left


def test_an_interrupt_handled_by_the_program_lets_the_call_go_on(spread, tmp_path):
    """A SIGINT whose handler does not raise does not stop the work."""
    code = ("import signal, alloycolor as ac\n"
            "signal.signal(signal.SIGINT, lambda *a: print('seen', flush=True))\n"
            "m = ac.load_model(%r)\n"
            "print('ready', flush=True)\n"
            "m.export(0.5, %r, format='blender-table')\n"
            "print('returned', flush=True)\n"
            % (str(spread.parent / "spread-smooth.json"), str(tmp_path / "t")))
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "ready"
    time.sleep(0.1)
    child.send_signal(signal.SIGINT)
    stdout, _ = child.communicate(timeout=60)
    assert stdout.split()[-1] == "returned"
    assert (tmp_path / "t.alloy-table.png").exists()
