# docs/accuracy.md and docs/performance.md are written by their scripts: the accuracy
# tables hold exactly the splits, sets and methods scripts/accuracy_table.py runs (not
# their numbers, which a rerun reproduces), and both name the command that made them.
import importlib.util
import re

from conftest import REPO


def accuracy_script():
    spec = importlib.util.spec_from_file_location("accuracy_table",
                                                  REPO / "scripts" / "accuracy_table.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


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
    script = accuracy_script()
    text = (REPO / "docs" / "accuracy.md").read_text()
    assert "scripts/accuracy.sh" in text.splitlines()[2]
    splits, own, bars = tables(text)
    assert splits[0] == ["split"] + script.METHODS
    assert [row[0] for row in splits[2:]] == [label for label, _, _ in script.SPLITS]
    assert all(len(row) == len(script.METHODS) + 1 for row in splits[2:])
    sets = [name for name, _ in script.COVERAGE_SETS] + ["Nb-Sn"]
    assert {(row[0], row[1]) for row in own[2:]} == {
        (s, m) for s in sets for m in script.METHODS[:-1]}
    assert {row[0] for row in bars[2:]} == {name for name, _ in script.COVERAGE_SETS} | {"pooled"}
    assert {row[2] for row in bars[2:]} == set(script.COVERAGE_METHODS)


def test_performance_names_its_command():
    text = (REPO / "docs" / "performance.md").read_text()
    assert re.search(r"Written by `scripts/bench\.sh[^`]*`", text)
    assert "naive" in text


def test_draws_tables_are_the_scripts():
    spec = importlib.util.spec_from_file_location("draws_table",
                                                  REPO / "scripts" / "draws_table.py")
    script = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(script)
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
