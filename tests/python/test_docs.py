# docs/accuracy.md, docs/draws.md, docs/suspects.md and docs/performance.md are written by
# their scripts: the accuracy, suggest and draws tables hold exactly the splits, sets, series,
# rules and methods their scripts run (not their numbers, which a rerun reproduces), and each
# names the command that made it.
import re

from conftest import REPO, load_script


def tables(text):
    """Each markdown table as a list of rows, each a list of cells."""
    found, current = [], []
    for line in text.splitlines():
        if line.startswith("|"):
            current.append([c.strip() for c in line.strip().strip("|").split("|")])
        elif current:
            found.append(current)
            current = []
    if current:
        found.append(current)
    return found


def test_accuracy_tables_are_the_scripts():
    script = load_script("accuracy_table")
    text = (REPO / "docs" / "accuracy.md").read_text()
    assert "scripts/accuracy.sh" in text.splitlines()[2]
    splits, own, bars, suggest, sums = tables(text)
    assert splits[0] == ["split"] + script.METHODS
    assert [row[0] for row in splits[2:]] == [label for label, _, _ in script.SPLITS]
    assert all(len(row) == len(script.METHODS) + 1 for row in splits[2:])
    sets = [name for name, _ in script.COVERAGE_SETS] + ["Nb-Sn"]
    assert {(row[0], row[1]) for row in own[2:]} == {
        (s, m) for s in sets for m in script.METHODS[:-1]}
    assert {row[0] for row in bars[2:]} == {name for name, _ in script.COVERAGE_SETS} | {"pooled"}
    assert {row[2] for row in bars[2:]} == set(script.COVERAGE_METHODS)
    # Where to measure next (scripts/suggest_table.py): every series under every rule.
    series = [label for label, _ in script.suggest_table.SERIES]
    rules = ["suggest", "widest gap", "random"]
    assert [(row[0], row[1]) for row in suggest[2:]] == [(s, r) for s in series for r in rules]
    assert sums[0] == ["rule"] + series
    assert [row[0] for row in sums[2:]] == rules
    assert all(cell == "1.000" for cell in sums[3][1:])  # the widest gap against itself


def test_suspects_table_names_its_command_and_counts():
    text = (REPO / "docs" / "suspects.md").read_text()
    seeds, sets = re.search(
        r"written by scripts/suspects_table\.py --seeds ([\d,]+) --sets (\d+)", text).groups()
    samples, flagged = re.search(
        r"(\d+) series each, (\d+) samples: \*\*(\d+) flagged", text).group(2, 3)
    flagged_rows, per_set = tables(text)
    assert len(flagged_rows) - 2 == int(flagged)
    assert sum(int(row[1]) for row in per_set[2:]) == len(seeds.split(",")) * int(sets)
    assert sum(int(row[2]) for row in per_set[2:]) == int(samples)
    assert sum(int(row[3]) for row in per_set[2:]) == int(flagged)


def test_performance_names_its_command():
    text = (REPO / "docs" / "performance.md").read_text()
    assert re.search(r"Written by `scripts/bench\.sh[^`]*`", text)
    assert "naive" in text


def test_draws_tables_are_the_scripts():
    script = load_script("draws_table")
    text = (REPO / "docs" / "draws.md").read_text()
    assert "scripts/draws.sh" in text.splitlines()[2]
    seed, sets = re.search(r"seed (\d+), (\d+) data sets", text).groups()
    loo, bars, per_set = tables(text)
    methods = script.acc.METHODS
    assert loo[0] == ["set", "drawn as"] + methods + ["auto / best"]
    assert [row[0] for row in loo[2:]] == [f"draw{seed}-{i + 1}" for i in range(int(sets))]
    assert {row[1] for row in bars[2:]} == set(methods)
    assert {row[0] for row in bars[2:]} <= {
        "leave-one-out", "3 compositions", "4 compositions", "all"}
    assert [row[0] for row in per_set[2:]] == [row[0] for row in loo[2:]]
