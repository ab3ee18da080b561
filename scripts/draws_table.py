#!/usr/bin/env python3
"""Measures `auto` and the error bars on data that no step of the project was tuned on:
fresh scatter draws of the bundled series, made from a seed, and writes docs/draws.md.

Each data set is one of:
  - Au-Ag: Rioux's series at 5 to 11 compositions (the interior ones picked at random), its
    ends Rioux's or, in a third of the sets, Johnson & Christy's or McPeak's pure metals;
  - Cu-Zn: Querry's three brasses between Werner's zinc and one lab's copper (Johnson &
    Christy, McPeak, Werner or Querry).
Every sample's n and k are scaled by 1 + s (a + b u / 2) + e: a and b drawn once per sample
(and apart for n and k) from a standard normal, u running from -1 to 1 over the sample's
wavelengths (a film-to-film tilt, as thickness, roughness and oxide make), e white noise of
standard deviation s / 4 at each wavelength. The scatter s is drawn per set from 0.5, 1,
1.5, 2 and 3 %; in half the sets the end samples keep their published values.

Every method is refitted without the held-out samples and predicts them (`alloycolor
validate --methods all`): leave-one-out, and some of each set's three- and
four-composition subsets (the ends kept, every other sample held out)."""
import argparse, collections, datetime, itertools, json, os, platform, random, statistics
import subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import accuracy_table as acc  # noqa: E402

try:
    import alloycolor as ac
except ImportError as e:
    sys.exit(f"draws: the alloycolor Python package ({e}): build it (scripts/setup.sh) and put "
             "build/python on PYTHONPATH, as scripts/draws.sh does")

DATA = os.path.join(acc.ROOT, "data")
HOW_DRAWN = __doc__.split("\n\n")[1]  # the description's second paragraph
SCATTERS = [0.005, 0.01, 0.015, 0.02, 0.03]


def read_nk(path):
    """The (wavelength um, n, k) rows of a lab file, as the program reads it."""
    spectrum = ac.read_nk(path)
    return list(zip((spectrum.lambda_nm / 1000).tolist(), spectrum.n.tolist(),
                    spectrum.k.tolist()))


def scattered(rows, s, rng):
    """The rows with n and k scaled as the module's description says (s = 0: as they are)."""
    if s == 0:
        return rows
    lo, hi = rows[0][0], rows[-1][0]
    a_n, b_n, a_k, b_k = (rng.gauss(0, 1) for _ in range(4))
    out = []
    for l, n, k in rows:
        u = 2 * (l - lo) / (hi - lo) - 1
        out.append((l, n * (1 + s * (a_n + b_n * u / 2) + rng.gauss(0, s / 4)),
                    k * (1 + s * (a_k + b_k * u / 2) + rng.gauss(0, s / 4))))
    return out


def draw_set(directory, name, rng):
    """One data set in directory/name (manifest and files); returns its description."""
    kind = rng.choice(["Au-Ag", "Au-Ag", "Au-Ag", "Cu-Zn"])
    s = rng.choice(SCATTERS)
    ends_scattered = rng.random() < 0.5
    if kind == "Au-Ag":
        rioux = {i / 10: f"{DATA}/Au-Ag/Rioux-Au{10 * i}Ag{100 - 10 * i}.yml" for i in range(11)}
        count = rng.choice([5, 6, 7, 8, 9, 11])
        interior = sorted(rng.sample(range(1, 10), count - 2))
        lo, hi, ends = rioux[0.0], rioux[1.0], "Rioux's ends"
        if rng.random() < 1 / 3:
            ag, au = rng.choice(["Johnson", "McPeak"]), rng.choice(["Johnson", "McPeak"])
            lo, hi = f"{DATA}/pure/Ag-{ag}.yml", f"{DATA}/pure/Au-{au}.yml"
            ends = f"{ag}'s Ag, {au}'s Au"
        samples = [(0.0, lo)] + [(i / 10, rioux[i / 10]) for i in interior] + [(1.0, hi)]
        system, composition = {"a": "Au", "b": "Ag"}, "atomic_fraction_a"
        what = f"Au-Ag, {count} compositions, {ends}"
    else:
        cu = rng.choice(["Johnson", "McPeak", "Werner", "Querry"])
        copper = f"{DATA}/Cu-Zn/Querry-Cu100.yml" if cu == "Querry" else f"{DATA}/pure/Cu-{cu}.yml"
        samples = [(0.0, f"{DATA}/Cu-Zn/Werner-Zn100.yml"),
                   (0.70, f"{DATA}/Cu-Zn/Querry-Cu70Zn30.yml"),
                   (0.85, f"{DATA}/Cu-Zn/Querry-Cu85Zn15.yml"),
                   (0.90, f"{DATA}/Cu-Zn/Querry-Cu90Zn10.yml"), (1.0, copper)]
        system, composition = {"a": "Cu", "b": "Zn"}, "weight_fraction_a"
        what = f"Cu-Zn, Werner's Zn, {cu}'s Cu"
    os.makedirs(os.path.join(directory, name))
    entries = []
    for x, source in samples:
        end = x in (0.0, 1.0)
        rows = scattered(read_nk(source), s if ends_scattered or not end else 0, rng)
        file = f"{name}-{round(1000 * x):04d}.yml"
        with open(os.path.join(directory, name, file), "w") as f:
            f.write(f"REFERENCES: |\n    {os.path.basename(source)} with scatter s = {s}\n"
                    "DATA:\n  - type: tabulated nk\n    data: |\n")
            f.writelines(f"        {l:.4f} {n:.4f} {k:.4f}\n" for l, n, k in rows)
        entries.append({"x": x, "file": file})
    with open(os.path.join(directory, name, "dataset.json"), "w") as f:
        json.dump({"name": name, "system": system, "composition": composition,
                   "samples": entries}, f, indent=1)
    return f"{what}, s = {100 * s:g} %" + (", ends too" if ends_scattered else "")


def against_best(means):
    """auto's mean error (means["auto"]) against the methods' (the rest): the best single
    mean, whether auto is within 10 % or 0.05 of it, whether auto is above eps-linear."""
    best = min(v for m, v in means.items() if m != "auto")
    auto = means["auto"]
    return best, auto <= max(1.1 * best, best + 0.05), auto > means.get("eps-linear", auto)


def whole(least):
    """An argparse type: a whole number, `least` or more."""
    def number(text):
        value = int(text)
        if value < least:
            raise argparse.ArgumentTypeError(f"must be {least} or more")
        return value
    return number


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--program", required=True, help="the alloycolor program")
    ap.add_argument("--seed", type=int, default=1, help="the draws' seed (default 1)")
    ap.add_argument("--sets", type=whole(1), default=10,
                    help="data sets to draw (default 10)")
    ap.add_argument("--subsets", type=whole(0), default=3,
                    help="three- and four-composition subsets per set, each (default 3)")
    ap.add_argument("--threads", default="0", help="the program's threads (0: every core)")
    ap.add_argument("--keep", help="a new directory to keep the drawn data sets in")
    ap.add_argument("--out", required=True, help="the markdown file to write")
    a = ap.parse_args()
    if not (os.path.isfile(a.program) and os.access(a.program, os.X_OK)):
        sys.exit(f"draws: --program {a.program}: no such program")
    if not os.path.isdir(os.path.dirname(os.path.abspath(a.out))):
        sys.exit(f"draws: --out {a.out}: its directory does not exist")
    if a.keep and os.path.exists(a.keep):
        sys.exit(f"draws: --keep {a.keep}: exists already")
    commit = subprocess.run(["git", "-C", acc.ROOT, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    rng = random.Random(a.seed)
    with tempfile.TemporaryDirectory() as tmp:
        directory = a.keep or tmp
        os.makedirs(directory, exist_ok=True)
        described, loo, ratios, choices = [], {}, {}, []
        for i in range(a.sets):
            name = f"draw{a.seed}-{i + 1}"
            described.append((name, draw_set(directory, name, rng)))
            data = os.path.join(directory, name, "dataset.json")
            xs = sorted({s["x"] for s in json.load(open(data))["samples"]})
            interior = xs[1:-1]
            configs = [("leave-one-out", None)]
            for k, label in ((1, "3 compositions"), (2, "4 compositions")):
                if len(interior) > k + 1:
                    kept = list(itertools.combinations(interior, k))
                    rng.shuffle(kept)
                    configs += [(label, [x for x in interior if x not in keep])
                                for keep in kept[:a.subsets]]
            for label, holdout in configs:
                print(f"draws: {name} ({described[-1][1]}), {label}", file=sys.stderr, flush=True)
                report = acc.validate(a.program, data, holdout, acc.METHODS, a.threads)
                for m, e, s in acc.rows(report):
                    if label == "leave-one-out":
                        loo.setdefault(name, {}).setdefault(m, []).append(e)
                    if s:
                        ratios.setdefault((name, label, m), []).append(e / s)
                if label == "leave-one-out":
                    picked = collections.Counter(
                        str(c).split(":")[0] for split in report["splits"]
                        for c in split.get("choices", {}).values())
                    choices.append(f"- {name}: " + ", ".join(
                        f"{m} {n}" for m, n in picked.most_common()) +
                        f" (of {sum(picked.values())} splits)")

    lines = ["# auto and the error bars on fresh scatter draws", "",
             f"Written by `scripts/draws.sh` on {datetime.date.today()}, commit {commit}, "
             f"{platform.machine()} {os.cpu_count()} cores: seed {a.seed}, {a.sets} data sets, "
             f"{a.subsets} three- and four-composition subsets of each. `scripts/draws.sh "
             "--seed N` draws others. How the sets are drawn:", ""]
    lines += ["    " + line for line in HOW_DRAWN.splitlines()]
    lines += ["", "## Leave-one-out, mean CIEDE2000", "",
              "`auto` against the best single method: within 10 % (or 0.05) of it, and never "
              "above the simplest baseline, eps-linear. Rioux's alloys are the output of a "
              "model (data/README.md) whose terms physical can take: its wins on the Au-Ag "
              "draws say little about real alloys.", "",
              "| set | drawn as | " + " | ".join(acc.METHODS) + " | auto / best |",
              "|---|---|" + "---|" * (len(acc.METHODS) + 1)]
    within = above = 0
    for name, what in described:
        means = {m: statistics.mean(v) for m, v in loo.get(name, {}).items()}
        single = {m: v for m, v in means.items() if m != "auto"}
        if "auto" not in means or not single:
            lines.append(f"| {name} | {what} |" + " — |" * (len(acc.METHODS) + 1))
            continue
        best, ok, over = against_best(means)
        within += ok
        above += over
        cells = [("—" if m not in means else f"**{acc.fmt(means[m])}**"
                  if means[m] == best else acc.fmt(means[m])) for m in acc.METHODS]
        lines.append(f"| {name} | {what} | " + " | ".join(cells) +
                     f" | {means['auto'] / best:.2f}{'' if ok else ' (above 10 %)'} |")
    lines += ["", f"`auto` within 10 % (or 0.05) of the best single method on {within} of "
              f"{len(described)} sets; above eps-linear on {above}.", "",
              "What `auto` chose in the leave-one-out splits (the reasons: `alloycolor validate`'s "
              "report):", ""] + choices
    lines += ["", "## Error bars", "",
              "Held-out CIEDE2000 over the model's own one-sigma: the share within one and two "
              "sigma and the median ratio (aim: 55-80 %, at least 90 %, 0.5-1.5).", "",
              "| splits | method | held-out errors | within 1 sigma | within 2 sigma | "
              "median error / sigma |", "|---|---|---|---|---|---|"]
    labels = ["leave-one-out", "3 compositions", "4 compositions"]
    for m in acc.METHODS:
        for label in labels + ["all"]:
            r = [v for (n, lab, mm), vs in ratios.items() for v in vs
                 if mm == m and (label == "all" or lab == label)]
            if r:
                lines.append(f"| {label} | {m} | {acc.coverage(r)} |")
    lines += ["", "`auto` per set, every split pooled:", "",
              "| set | held-out errors | within 1 sigma | within 2 sigma | median error / sigma |",
              "|---|---|---|---|---|"]
    for name, _ in described:
        r = [v for (n, lab, mm), vs in ratios.items() for v in vs if n == name and mm == "auto"]
        lines.append(f"| {name} | {acc.coverage(r)} |")
    acc.write_markdown(a.out, lines, "draws")


if __name__ == "__main__":
    main()
