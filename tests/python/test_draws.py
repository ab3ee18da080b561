# scripts/draws_table.py draws the data sets docs/draws.md measures auto and the error bars
# on: its scatter has the spread its description states, and the program reads the sets it
# writes as drawn.
import random
import statistics

import pytest

from conftest import DATA, load_script


@pytest.fixture(scope="module")
def draws():
    return load_script("draws_table")


def test_scatter_has_the_stated_spread(draws):
    # n and k times 1 + s (a + b u / 2) + e, a, b standard normal, e of standard deviation
    # s / 4: relative standard deviation s sqrt(1 + u^2 / 4 + 1 / 16) at u (-1, 0, 1 here),
    # mean 0. 4000 draws: the mean within 4 standard errors, the spread within 5 % (its
    # standard error about 1.1 %).
    rows = [(0.4, 1.5, 3.0), (0.5, 1.5, 3.0), (0.6, 1.5, 3.0)]
    s, count = 0.02, 4000
    rng = random.Random(3)
    drawn = [draws.scattered(rows, s, rng) for _ in range(count)]
    for i, u in enumerate((-1, 0, 1)):
        expected = s * (1 + u * u / 4 + 1 / 16) ** 0.5
        for j in (1, 2):
            relative = [d[i][j] / rows[i][j] - 1 for d in drawn]
            assert abs(statistics.mean(relative)) < 4 * expected / count**0.5
            assert statistics.stdev(relative) == pytest.approx(expected, rel=0.05)
        assert all(d[i][0] == rows[i][0] for d in drawn)
    # n's and k's factors are drawn apart.
    n = [d[1][1] for d in drawn]
    k = [d[1][2] for d in drawn]
    assert abs(statistics.correlation(n, k)) < 4 / count**0.5
    assert draws.scattered(rows, 0, rng) == rows


def test_the_program_reads_the_drawn_sets(draws, tmp_path):
    import alloycolor as ac
    rng = random.Random(11)
    for i in range(8):
        name = f"set{i}"
        what = draws.draw_set(tmp_path, name, rng)
        data = ac.Dataset(tmp_path / name / "dataset.json")
        assert data.system == ("Au-Ag" if what.startswith("Au-Ag") else "Cu-Zn")
        for sample in data.samples:
            # The wavelengths of the file it was drawn from (named in its REFERENCES), in
            # the written digits: none added or lost.
            with open(sample["path"]) as f:
                source = f.read().splitlines()[1].split()[0]
            published = ac.read_nk(next(DATA.glob(f"*/{source}")))
            assert list(sample["spectrum"].lambda_nm) == pytest.approx(
                list(published.lambda_nm), abs=0.05)
        given = sorted(s["x_given"] for s in data.samples)
        assert given[0] == 0 and given[-1] == 1
        if what.startswith("Au-Ag"):
            assert len(given) == int(what.split(", ")[1].split()[0])
        else:
            assert given == [0, 0.7, 0.85, 0.9, 1]
        if "ends too" not in what:
            # The ends keep their published values (to the written digits).
            zinc = draws.read_nk(DATA / "Cu-Zn" / "Werner-Zn100.yml")
            silver = draws.read_nk(DATA / "Au-Ag" / "Rioux-Au0Ag100.yml")
            end = min(data.samples, key=lambda s: s["x_given"])["spectrum"]
            published = zinc if what.startswith("Cu-Zn") else silver
            if what.startswith("Cu-Zn") or "Rioux's ends" in what:
                assert list(end.n) == pytest.approx([r[1] for r in published], abs=6e-5)


def test_auto_against_the_best_by_hand(draws):
    # Within 10 % or 0.05 of the best single method; above eps-linear or not.
    assert draws.against_best({"eps-linear": 1.0, "smooth": 0.5, "auto": 0.55}) == (
        0.5, True, False)
    assert draws.against_best({"eps-linear": 1.0, "smooth": 0.5, "auto": 0.56})[1] is False
    assert draws.against_best({"eps-linear": 0.1, "smooth": 0.02, "auto": 0.07})[1:] == (
        True, False)
    assert draws.against_best({"eps-linear": 0.1, "smooth": 0.02, "auto": 0.071})[1] is False
    assert draws.against_best({"eps-linear": 1.0, "physical": 0.3, "auto": 1.2})[1:] == (
        False, True)
    assert draws.against_best({"smooth": 0.4, "auto": 0.4})[1:] == (True, False)
