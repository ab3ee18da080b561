#!/usr/bin/env python3
"""Runs `alloycolor validate` on every split docs/accuracy.md reports and writes its tables:
held-out error per split and method (every method, the baselines among them), auto's
choices, the methods' in-sample error at their own samples, and how often the held-out
errors fell inside one and two of the model's own sigma (leave-one-out and every three- and
four-composition subset of the bundled sets, the ends kept)."""
import argparse, datetime, itertools, json, os, platform, statistics, subprocess, sys, tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import suggest_table  # noqa: E402

try:
    import alloycolor as ac
except ImportError as e:
    sys.exit(f"accuracy: the alloycolor Python package ({e}): build it (scripts/setup.sh) and "
             "put build/python on PYTHONPATH, as scripts/accuracy.sh does")

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Every method of the registry, in its order, then auto.
METHODS = [m["name"] for m in ac.methods()] + ["auto"]
AUAG = "data/Au-Ag"
# (label, data set, compositions held out; None: leave-one-out)
SPLITS = [
    ("Au-Ag, paper's split (train 0, .2, .5, .6, .8, 1)", AUAG, [0.1, 0.3, 0.4, 0.7, 0.9]),
    ("Au-Ag, 3 samples (train 0, .5, 1)", AUAG, [0.1, 0.2, 0.3, 0.4, 0.6, 0.7, 0.8, 0.9]),
    ("Au-Ag, 4 samples (train 0, .3, .7, 1)", AUAG, [0.1, 0.2, 0.4, 0.5, 0.6, 0.8, 0.9]),
    ("Au-Ag, leave-one-out", AUAG, None),
    ("Cu-Zn with Werner's Zn, leave-one-out", "data/Cu-Zn/dataset-werner-zn.json", None),
    ("Cu-Zn (Querry), leave-one-out", "data/Cu-Zn", None),
    ("Nb-Sn, leave-one-out (infrared: reflectance RMS)", "data/Nb-Sn", None),
]
COVERAGE_SETS = [("Au-Ag", AUAG), ("Cu-Zn (Querry)", "data/Cu-Zn"),
                 ("Cu-Zn (Werner's Zn)", "data/Cu-Zn/dataset-werner-zn.json")]
COVERAGE_METHODS = METHODS


def manifest(path):
    p = os.path.join(ROOT, path)
    return os.path.join(p, "dataset.json") if os.path.isdir(p) else p


def validate(program, data, holdout, methods, threads):
    with tempfile.TemporaryDirectory() as out:
        cmd = [program, "validate", "--data", manifest(data), "--methods", ",".join(methods),
               "--angles", "0", "--out", out, "--quiet", "--threads", str(threads)]
        if holdout:
            cmd += ["--holdout", ",".join(repr(x) for x in holdout)]
        run = subprocess.run(cmd, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"accuracy: {' '.join(cmd)} failed: {run.stderr.strip()}")
        with open(os.path.join(out, "report.json")) as f:
            return json.load(f)


def first(v):
    return list(v.values())[0] if isinstance(v, dict) else v


def rows(report):
    """(method, error, sigma) per held-out sample; the error is CIEDE2000 at normal
    incidence, or the reflectance RMS where the data have no colour."""
    out = []
    for h in report["holdouts"]:
        for m, r in h["results"].items():
            if "reflectance_rms" not in r:
                continue
            e = first(r.get("delta_e00"))
            s = first(r.get("delta_e00_sigma"))
            out.append((m, r["reflectance_rms"] if e is None else e, None if e is None else s))
    return out


def coverage(ratios):
    """Table cells for errors over their sigmas: how many, the shares within one and two
    sigma, the median ratio."""
    if not ratios:
        return "— | — | — | —"
    n = len(ratios)
    return (f"{n} | {100 * sum(r <= 1 for r in ratios) / n:.0f} % | "
            f"{100 * sum(r <= 2 for r in ratios) / n:.0f} % | {statistics.median(ratios):.2f}")


def write_markdown(path, lines, who):
    """The lines to `path`, whole or not at all."""
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(path + ".tmp", path)
    print(f"{who}: wrote {path}", file=sys.stderr)


def fmt(v):
    return "—" if v is None else (f"{v:.2g}" if v < 0.01 else f"{v:.3f}" if v < 0.1 else f"{v:.2f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--program", required=True)
    ap.add_argument("--threads", default="0")
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip() or "unknown"
    lines = ["# Accuracy on held-out compositions", "",
             f"Written by `scripts/accuracy.sh` on {datetime.date.today()}, commit {commit}, "
             f"{platform.machine()} {os.cpu_count()} cores. Every method is refitted without "
             "the held-out samples and predicts them (`alloycolor validate --methods all`); "
             "`auto` runs its own leave-one-out inside every split, on the training samples "
             "only. Mean / worst CIEDE2000 at normal incidence (D65, 2°); Nb-Sn is infrared: "
             "reflectance RMS. Lowest mean in bold.", "",
             "| split | " + " | ".join(METHODS) + " |", "|---|" + "---|" * len(METHODS)]
    choices = []
    for label, data, holdout in SPLITS:
        print(f"accuracy: {label}", file=sys.stderr, flush=True)
        report = validate(a.program, data, holdout, METHODS, a.threads)
        by = {}
        for m, e, _ in rows(report):
            by.setdefault(m, []).append(e)
        means = {m: statistics.mean(v) for m, v in by.items()}
        best = min((v for m, v in means.items() if m != "auto"), default=None)
        cells = []
        for m in METHODS:
            if m not in by:
                cells.append("refused")
                continue
            text = f"{fmt(means[m])} / {fmt(max(by[m]))}"
            cells.append(f"**{text}**" if means[m] == best else text)
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
        picked = [c for split in report["splits"] for c in split.get("choices", {}).values()]
        if picked:
            choices.append(f"- {label}: " + ", ".join(str(p) for p in picked))
    lines += ["", "What `auto` chose in each split:", ""] + choices

    lines += ["", "## Each method at its own samples", "",
              "Fitted to all samples of each set; the largest CIEDE2000 between the model and "
              "one of its own training samples (reflectance RMS for Nb-Sn), and the model's "
              "one-sigma there. A miss above ΔE00 1 is also a warning at fit time.", "",
              "| set | method | worst miss | at | its one-sigma there |", "|---|---|---|---|---|"]
    for name, data in COVERAGE_SETS + [("Nb-Sn", "data/Nb-Sn")]:
        for m in METHODS[:-1]:
            with tempfile.TemporaryDirectory() as out:
                model = os.path.join(out, "m.json")
                run = subprocess.run([a.program, "fit", "--data", manifest(data), "--method", m,
                                      "--out", model, "--quiet"], capture_output=True, text=True)
                if run.returncode != 0:
                    lines.append(f"| {name} | {m} | refused | | |")
                    continue
                doc = json.load(open(model))
                worst = max(doc.get("in_sample", []), key=lambda r: r["delta_e00"]
                            if r["delta_e00"] is not None else r["reflectance_rms"])
                miss = worst["delta_e00"] if worst["delta_e00"] is not None else worst["reflectance_rms"]
                sigma = "—"
                if worst["delta_e00"] is not None:
                    c = subprocess.run([a.program, "color", "--model", model, "--x",
                                        repr(worst["x"]), "--json", "--quiet"],
                                       capture_output=True, text=True)
                    if c.returncode == 0:
                        got = json.loads(c.stdout)
                        got = got[0] if isinstance(got, list) else got
                        s = got.get("delta_e00_sigma", got.get("sigma"))
                        sigma = fmt(first(s)) if s is not None else "—"
                lines.append(f"| {name} | {m} | {fmt(miss)} | {worst['file']} | {sigma} |")

    lines += ["", "## Error bars", "",
              "Held-out CIEDE2000 over the model's own one-sigma: the share within one and two "
              "sigma and the median ratio (aim: 55-80 %, at least 90 %, 0.5-1.5), on "
              "leave-one-out and on every three- and four-composition subset (the ends kept, "
              "every other sample held out).", "",
              "| set | splits | method | held-out errors | within 1 sigma | within 2 sigma | median error / sigma |",
              "|---|---|---|---|---|---|---|"]
    pooled = {}
    for name, data in COVERAGE_SETS:
        xs = sorted(s["x"] for s in json.load(open(manifest(data)))["samples"])
        interior = xs[1:-1]
        configs = [("leave-one-out", [None])]
        for k, label in ((1, "3 compositions"), (2, "4 compositions")):
            subsets = [[x for x in interior if x not in keep]
                       for keep in itertools.combinations(interior, k)]
            if len(interior) > k + 1:
                configs.append((label, subsets))
        for label, holdouts in configs:
            print(f"accuracy: error bars, {name}, {label}", file=sys.stderr, flush=True)
            ratios = {}
            for h in holdouts:
                for m, e, s in rows(validate(a.program, data, h, COVERAGE_METHODS, a.threads)):
                    if s:
                        ratios.setdefault(m, []).append(e / s)
            for m in COVERAGE_METHODS:
                r = ratios.get(m, [])
                if not r:
                    continue
                pooled.setdefault(m, []).extend(r)
                lines.append(f"| {name} | {label} | {m} | {coverage(r)} |")
    for m in COVERAGE_METHODS:
        r = pooled.get(m, [])
        if r:
            lines.append(f"| pooled | all | {m} | {coverage(r)} |")
    # Where to measure next: suggest's rule against the widest gap and chance.
    lines += [""] + suggest_table.section(a.program, a.threads,
                                          lambda m: print(m, file=sys.stderr))
    write_markdown(a.out, lines, "accuracy")


if __name__ == "__main__":
    main()
