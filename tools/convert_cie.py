#!/usr/bin/env python3
"""Converts colord-data's CGATS/IT8 CIE tables (../shared/data/cie) to data/cie/*.csv.

One-time conversion; the CSV files are committed. Each output starts with a '#' line
naming its source, then a header: 'lambda_nm,value' for illuminants and
'lambda_nm,x_bar,y_bar,z_bar' for colour matching functions.
"""
import pathlib
import sys

SOURCE = "CIE standard table, from Debian colord-data (/usr/share/colord/, CGATS/IT8 file {name})"


def parse(path):
    lines = path.read_text().splitlines()
    head = {}
    for line in lines:
        parts = line.split(None, 1)
        if len(parts) == 2 and parts[0].startswith("SPECTRAL_"):
            head[parts[0]] = float(parts[1])
    start = lines.index("BEGIN_DATA") + 1
    end = lines.index("END_DATA")
    rows = [[float(v) for v in l.split()] for l in lines[start:end]]
    first, last = head["SPECTRAL_START_NM"], head["SPECTRAL_END_NM"]
    bands = int(head["SPECTRAL_BANDS"])
    step = (last - first) / (bands - 1)
    for r in rows:
        assert len(r) == bands, path
    lam = [first + i * step for i in range(bands)]
    return lam, rows


def main(src, dst):
    src, dst = pathlib.Path(src), pathlib.Path(dst)
    for p in sorted(src.iterdir()):
        lam, rows = parse(p)
        name = p.stem.replace("CIE-", "illuminant-").replace("-XYZ", "")
        if p.suffix == ".cmf":
            header = "lambda_nm,x_bar,y_bar,z_bar"
            name = "cmf-" + {"CIE1931-2deg": "1931-2", "CIE1964-10deg": "1964-10"}[name]
        else:
            header = "lambda_nm,value"
        with open(dst / (name + ".csv"), "w") as f:
            f.write("# " + SOURCE.format(name=p.name) + "\n")
            f.write(header + "\n")
            for i, l in enumerate(lam):
                f.write("%g,%s\n" % (l, ",".join(repr(r[i]) for r in rows)))


if __name__ == "__main__":
    main(*sys.argv[1:3])
