#!/usr/bin/env python3
"""Colour of 100,000 compositions from Python: alloycolor.color against a pure-numpy chain.

    PYTHONPATH=build/python python3 examples/bench_colour.py [--count 100000] [--method smooth]

The numpy chain takes n + ik on the 5 nm CIE grid from model.nk (the model itself), then
does Fresnel (eq. 2-4), XYZ (eq. 5) and CIELAB in numpy, vectorised over all compositions.
alloycolor.color runs the whole chain in C++: by default through the XYZ table (error below
1e-7, checked while it is built), and with exact=True evaluating every composition.
Prints wall-clock times (best of three) and the largest XYZ difference between the chains.
"""
import argparse
import pathlib
import time

import numpy as np

import alloycolor as ac


def read_cie(name):
    path = pathlib.Path(ac.data_root()) / "cie" / name
    rows = [l for l in path.read_text().splitlines() if l and not l.startswith("#")]
    t = np.array([[float(v) for v in r.split(",")] for r in rows[1:]])
    return t[:, 0], t[:, 1:]


def numpy_colour(N, p, cmf):
    """N: (count, wavelengths) at normal incidence -> XYZ and Lab (D65 white)."""
    R = np.abs((N - 1) / (N + 1)) ** 2
    norm = p @ cmf[:, 1]
    xyz = (R * p) @ cmf / norm
    white = p @ cmf / norm
    t = xyz / white
    f = np.where(t > (6 / 29) ** 3, np.cbrt(t), t / (3 * (6 / 29) ** 2) + 4 / 29)
    lab = np.stack([116 * f[:, 1] - 16, 500 * (f[:, 0] - f[:, 1]), 200 * (f[:, 1] - f[:, 2])], 1)
    return xyz, lab


def best_of(n, fn):
    times = []
    for _ in range(n):
        t0 = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - t0)
    return min(times), result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=100000)
    parser.add_argument("--method", default="smooth")
    args = parser.parse_args()
    model = ac.fit(ac.Dataset("Au-Ag"), args.method)
    xs = np.random.default_rng(1).uniform(0.0, 1.0, args.count)
    lam_cmf, cmf = read_cie("cmf-1931-2.csv")
    lam_p, p = read_cie("illuminant-D65.csv")
    grid = np.arange(360.0, 831.0, 5.0)
    cmf = cmf[np.searchsorted(lam_cmf, grid)]
    p = p[np.searchsorted(lam_p, grid), 0]

    t_table, c_table = best_of(3, lambda: ac.color(model, xs))
    t_exact, c_exact = best_of(3, lambda: ac.color(model, xs, exact=True))
    t_nk, N = best_of(3, lambda: model.nk(xs, grid))
    t_np, (xyz_np, lab_np) = best_of(3, lambda: numpy_colour(N, p, cmf))
    print("%d compositions, %s model, D65, 2-degree, normal incidence" % (args.count,
                                                                         model.method))
    print("alloycolor.color (table):       %8.1f ms" % (1e3 * t_table))
    print("alloycolor.color (exact=True):  %8.1f ms" % (1e3 * t_exact))
    print("numpy chain: model.nk %8.1f ms + numpy Fresnel/XYZ/Lab %8.1f ms = %8.1f ms" % (
        1e3 * t_nk, 1e3 * t_np, 1e3 * (t_nk + t_np)))
    print("speed-up against numpy: table %.1fx, exact %.1fx" % (
        (t_nk + t_np) / t_table, (t_nk + t_np) / t_exact))
    print("max |XYZ table - numpy| %.2e, max |XYZ exact - numpy| %.2e" % (
        np.abs(c_table["xyz"] - xyz_np).max(), np.abs(c_exact["xyz"] - xyz_np).max()))


if __name__ == "__main__":
    main()
