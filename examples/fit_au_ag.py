#!/usr/bin/env python3
"""Fit Au-Ag from three samples (Ag, Au50Ag50, Au) and show the colour against composition.

    PYTHONPATH=build/python python3 examples/fit_au_ag.py [--out chart.png]

Plots sRGB swatches and L*, a*, b* against x with matplotlib when it is installed, else
prints a table; either way it compares the prediction with the bundled measured (Rioux)
samples the fit did not see (CIEDE2000 is not needed for that: the table shows both Labs).
"""
import argparse

import numpy as np

import alloycolor as ac


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--method", default="smooth", help="a method of alloycolor.methods()")
    parser.add_argument("--out", default="au-ag-colour.png", help="the plot (with matplotlib)")
    args = parser.parse_args()

    full = ac.Dataset("Au-Ag")
    three = full.select([0.0, 0.5, 1.0])
    model = ac.fit(three, args.method, progress=lambda m: print("fit:", m))
    print(model)

    x = np.linspace(0.0, 1.0, 101)
    c = model.color(x)  # normal incidence, D65, 2-degree observer
    unseen = [s for s in full.samples if s["x_atomic"] not in (0.0, 0.5, 1.0)]
    measured = {s["x_atomic"]: ac.color(s["spectrum"])["lab"] for s in unseen}

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        plt = None
    if plt is None:
        print("matplotlib not found: printing instead")
        print("%6s %8s %8s %8s  %-7s %s" % ("x_Au", "L*", "a*", "b*", "sRGB", "measured L*a*b*"))
        for i in range(0, 101, 10):
            xi = x[i]
            m = measured.get(round(xi, 6))
            r, g, b = c["srgb8"][i]
            print("%6.2f %8.3f %8.3f %8.3f  #%02x%02x%02x %s" % (
                xi, *c["lab"][i], r, g, b,
                "" if m is None else "%.3f %.3f %.3f" % tuple(m)))
        return
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 5), sharex=True,
                                      gridspec_kw={"height_ratios": [1, 3]})
    top.imshow(c["srgb8"][np.newaxis], aspect="auto", extent=(0, 1, 0, 1))
    top.set_yticks([])
    top.set_title("Au-Ag, %s model from three samples (D65, normal incidence)" % model.method)
    for i, name in enumerate(("L*", "a*", "b*")):
        line, = bottom.plot(x, c["lab"][:, i] - (90 if i == 0 else 0), label=name +
                            (" - 90" if i == 0 else ""))
        xs = sorted(measured)
        bottom.plot(xs, [measured[v][i] - (90 if i == 0 else 0) for v in xs], "o",
                    color=line.get_color())
    bottom.set_xlabel("x (Au atomic fraction); dots: measured samples not used in the fit")
    bottom.legend()
    fig.savefig(args.out, dpi=120)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
