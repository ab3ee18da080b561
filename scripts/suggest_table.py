#!/usr/bin/env python3
"""Judges `alloycolor suggest` on the real series: where to measure next, as a lab would use
it, against the obvious alternative and against chance.

Each series starts from its two ends and the sample nearest the middle of its composition
range; the rest of its samples are the pool of films one could still measure. At each step
the model (auto) is fitted to the samples measured so far, a rule names the next
composition, the pool sample nearest to it is "measured" (added), and the model refitted on
the new set is scored on every sample still in the pool (`alloycolor validate --holdout`:
mean CIEDE2000 at normal incidence, or reflectance RMS for data without colour). The rules:
  - suggest: `alloycolor suggest --count 1` (the composition of largest one-sigma);
  - widest gap: the middle of the widest gap between the measured compositions;
  - random: the pool in a random order (the mean over ten orders, seeded).
A rule is better where its curve of held-out error lies lower: the table gives the error
before any addition (the same for every rule), the curve after each addition but the last
(which leaves no sample to score), and the curve's sum."""
import argparse, json, os, random, subprocess, sys, tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SERIES = [("Au-Ag (Rioux)", "data/Au-Ag"),
          ("Cu-Zn (Querry)", "data/Cu-Zn"),
          ("Cu-Zn (Werner's Zn)", "data/Cu-Zn/dataset-werner-zn.json"),
          ("Nb-Sn (infrared)", "data/Nb-Sn")]
RANDOM_ORDERS = 10


def manifest_path(path):
    p = os.path.join(ROOT, path)
    return os.path.join(p, "dataset.json") if os.path.isdir(p) else p


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"suggest_table: {' '.join(cmd)} failed: {r.stderr.strip()}")
    return r.stdout


class Series:
    """A bundled series: its manifest, its samples (entries with their atomic fraction)."""

    def __init__(self, program, path):
        self.program = program
        self.manifest = manifest_path(path)
        with open(self.manifest) as f:
            self.doc = json.load(f)
        folder = os.path.dirname(self.manifest)
        # Atomic fractions as the program reads them: one fit of the whole set tells them.
        with tempfile.TemporaryDirectory() as tmp:
            model = os.path.join(tmp, "m.json")
            run([program, "fit", "--data", self.manifest, "--method", "eps-linear", "--out",
                 model, "--quiet"])
            with open(model) as f:
                by_file = {s["file"]: s["x"] for s in json.load(f)["training_samples"]}
        self.samples = []
        for entry in self.doc["samples"]:
            e = dict(entry)
            e["file"] = os.path.join(folder, entry["file"])
            self.samples.append((by_file[entry["file"]], e))
        self.samples.sort(key=lambda s: s[0])

    def write(self, folder, chosen):
        doc = dict(self.doc)
        doc["samples"] = [e for _, e in chosen]
        path = os.path.join(folder, "dataset.json")
        with open(path, "w") as f:
            json.dump(doc, f)
        return path


def held_out_error(series, folder, measured, pool, threads):
    """Mean error of auto fitted to `measured` on the `pool` samples."""
    data = series.write(folder, measured + pool)
    out = os.path.join(folder, "report")
    run([series.program, "validate", "--data", data, "--methods", "auto", "--angles", "0",
         "--holdout", ",".join(e["file"] for _, e in pool), "--out", out, "--quiet",
         "--threads", str(threads)])
    with open(os.path.join(out, "report.json")) as f:
        report = json.load(f)
    errors = []
    for h in report["holdouts"]:
        r = h["results"]["auto"]
        value = r["delta_e00"]["0"] if report["delta_e00_available"] else r["reflectance_rms"]
        errors.append(value)
    return sum(errors) / len(errors)


def nearest(pool, x):
    return min(range(len(pool)), key=lambda i: (abs(pool[i][0] - x), pool[i][0]))


def suggest_rule(series, folder, measured, pool, threads):
    data = series.write(folder, measured)
    model = os.path.join(folder, "m.json")
    run([series.program, "fit", "--data", data, "--out", model, "--quiet", "--threads",
         str(threads)])
    out = json.loads(run([series.program, "suggest", "--model", model, "--count", "1", "--json",
                          "--quiet"]))
    return nearest(pool, out[0]["x"])


def widest_gap_rule(series, folder, measured, pool, threads):
    xs = sorted(x for x, _ in measured)
    gaps = [(b - a, (a + b) / 2) for a, b in zip(xs, xs[1:])]
    return nearest(pool, max(gaps)[1])


def curve(series, rule, threads, rng=None):
    """The held-out error after each addition (the first value: before any)."""
    samples = series.samples
    middle = (samples[0][0] + samples[-1][0]) / 2
    inner = samples[1:-1]
    mid = inner[nearest(inner, middle)]
    measured = [samples[0], mid, samples[-1]]
    pool = [s for s in inner if s is not mid]
    if rng is not None:
        rng.shuffle(pool)
    values = []
    with tempfile.TemporaryDirectory() as folder:
        while pool:
            values.append(held_out_error(series, folder, measured, pool, threads))
            i = 0 if rng is not None else rule(series, folder, measured, pool, threads)
            measured = sorted(measured + [pool.pop(i)], key=lambda s: s[0])
    return values


def section(program, threads, progress=print):
    """The markdown lines of the table (docs/accuracy.md)."""
    lines = ["## Where to measure next (`alloycolor suggest`)", "",
             __doc__.split("\n\n")[1], "",
             "| series | rule | before | held-out error after each addition | sum |",
             "|---|---|---|---|---|"]
    totals = {"suggest": [], "widest gap": [], "random": []}
    for label, path in SERIES:
        series = Series(program, path)
        progress(f"suggest_table: {label}")
        curves = {"suggest": curve(series, suggest_rule, threads),
                  "widest gap": curve(series, widest_gap_rule, threads)}
        rng = random.Random(20261206)
        orders = [curve(series, None, threads, rng) for _ in range(RANDOM_ORDERS)]
        curves["random"] = [sum(c[i] for c in orders) / len(orders) for i in range(len(orders[0]))]
        for rule, values in curves.items():
            after = values[1:]
            totals[rule].append(sum(after))
            lines.append(f"| {label} | {rule} | {values[0]:.3g} | " +
                         ", ".join(f"{v:.3g}" for v in after) + f" | {sum(after):.3g} |")
    lines += ["", "Sum over the additions, each series' sum over the widest gap's:", "",
              "| rule | " + " | ".join(label for label, _ in SERIES) + " |",
              "|---|" + "---|" * len(SERIES)]
    for rule, sums in totals.items():
        ratios = [s / w if w > 0 else float("nan") for s, w in zip(sums, totals["widest gap"])]
        lines.append(f"| {rule} | " + " | ".join(f"{r:.3f}" for r in ratios) + " |")
    return lines


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--program", default=os.path.join(ROOT, "build/app/alloycolor"))
    p.add_argument("--threads", type=int, default=0)
    a = p.parse_args()
    print("\n".join(section(a.program, a.threads, lambda m: print(m, file=sys.stderr))))


if __name__ == "__main__":
    main()
