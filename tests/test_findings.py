"""Unit tests of experiments/analysis/findings.py: README's summary and
results/FINDINGS.md backed by the results files.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`); pytest rewrites
the asserts, so they check under `python3 -O` too. Every check compares
against a value computed another way (a closed form, a simulation with a
known answer, the definition computed directly), so each can fail. Random
numbers come from fixed seeds: the outcome is deterministic.
"""

import math
import os
import subprocess
import tempfile

import numpy as np
import pandas as pd

from experiments.analysis import findings
from helpers import table1_frame

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def md(name, d):
    """FINDINGS.md's (title, lines) of finding NAME, from the files D names."""
    writer = {n: w for _, n, w, _ in findings.FINDINGS}[name]
    return writer(findings.RECORDS[name](d))


def readme(name, d):
    """README's summary bullet of finding NAME, from the files D names."""
    return dict(findings.SUMMARY)[name](findings.RECORDS[name](d))


def test_readme_numbers_backed():
    """Every number of README's findings section is a number token of some
    results file (the committed README against the committed results/)."""
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        section = findings.findings_section(f.read())
    assert section.strip(), "README.md has no findings section"
    assert findings.unbacked_numbers(section, findings.results_text(os.path.join(ROOT, "results"))) == []


def test_readme_numbers_negative_control():
    """A made-up number fails the check, a digit run inside a longer number
    does not count as present, and a thousands separator is looked through."""
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "a.md"), "w", encoding="utf-8") as f:
            f.write("ratio 85.6% at n = 10; 1800 shapes; 2.4117\n")
        readme = "# x\n\n## What it found, in short\n\n- 85.6% at n = 10, 1,800 shapes\n\n## Next\n\n- 99.9\n"
        sec = findings.findings_section(readme)
        assert "99.9" not in sec
        hay = findings.results_text(d)
        assert findings.unbacked_numbers(sec, hay) == []
        bad = readme.replace("85.6%", "85.7%")
        assert findings.unbacked_numbers(findings.findings_section(bad), hay) == ["85.7"]
        inner = readme.replace("85.6%", "2.41x")  # 2.41 is only a prefix of 2.4117
        assert findings.unbacked_numbers(findings.findings_section(inner), hay) == ["2.41"]
        # the command line exits 1 on the bad README (markers and an empty
        # block given, so that the number check is what fails)
        path = os.path.join(d, "README.md")
        with open(path, "w", encoding="utf-8") as f:
            f.write(bad.replace("## Next", findings.SUMMARY_BEGIN + "\n" + findings.SUMMARY_END + "\n\n## Next"))
        rc = subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.findings", "--results", d,
                             "--check-readme", path], cwd=ROOT, capture_output=True, check=False).returncode
        assert rc == 1


def test_readme_summary_current(monkeypatch):
    """README's summary block is the one findings.summary writes from the
    committed results/ now (as `make findings` runs it, from the top
    directory): a number left behind by a rerun fails here."""
    monkeypatch.chdir(ROOT)
    with open("README.md", encoding="utf-8") as f:
        text = f.read()
    at = findings.readme_block(text)
    assert at is not None, "README.md has no findings summary block"
    assert text[at[0]:at[1]] == findings.summary(findings.paths("results"))


def test_readme_summary_negative_control():
    """--write-readme fills the block from the files, --check-readme then
    passes; a number changed by hand in the block, a results file changed
    under it, and a README without the markers each fail it (exit 1)."""
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "table1"))
        table1_frame([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(
            os.path.join(d, "table1", "table1.csv"), index=False)
        path = os.path.join(d, "README.md")
        base = ("# x\n\n## What it found, in short\n\nIn short:\n\n" + findings.SUMMARY_BEGIN + "\n"
                + findings.SUMMARY_END + "\n\n## Next\n")
        with open(path, "w", encoding="utf-8") as f:
            f.write(base)

        def run(*args):
            return subprocess.run(["/usr/bin/python3", "-m", "experiments.analysis.findings", "--results", d, *args],
                                  cwd=ROOT, capture_output=True, text=True, check=False)
        assert run("--check-readme", path).returncode == 1  # the empty block is stale
        assert run("--write-readme", path).returncode == 0
        with open(path, encoding="utf-8") as f:
            good = f.read()
        assert "falls from 80.0% [75.0, 85.0] at n = 10 to 40.0% [38.0, 42.0] at n = 100" in good
        assert "Not answered here" in good  # the files this directory lacks say so
        r = run("--check-readme", path)
        assert r.returncode == 0, r.stderr
        with open(path, "w", encoding="utf-8") as f:
            f.write(good.replace("40.0% [38.0, 42.0]", "41.0% [38.0, 42.0]"))
        r = run("--check-readme", path)
        assert r.returncode == 1 and "README.md:10: the findings summary is not the one" in r.stderr, r.stderr
        with open(path, "w", encoding="utf-8") as f:
            f.write(good)
        table1_frame([(80, 75, 85), (45, 43, 47), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(
            os.path.join(d, "table1", "table1.csv"), index=False)
        assert run("--check-readme", path).returncode == 1  # the files moved on
        with open(path, "w", encoding="utf-8") as f:
            f.write(good.replace(findings.SUMMARY_END, ""))
        r = run("--check-readme", path)
        assert r.returncode == 1 and "no summary block" in r.stderr


def test_summary_wording_from_tests():
    """The summary's words follow its tests: the ratio 'falls' over n only
    when the two intervals are disjoint, and the shape 'reproduces' only when
    it falls at every photon count."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "table1.csv")
        table1_frame([(80, 75, 85), (40, 38, 42), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(path, index=False)
        line = readme("table", {"table": path})
        assert "P_e = 50k falls from" in line and "falls over n at 1 of 2 photon counts" in line
        table1_frame([(80, 75, 85), (78, 70, 82), (100, 95, 105)], [(0.01, 0.005, 0.02)] * 3).to_csv(path, index=False)
        line = readme("table", {"table": path})
        assert "P_e = 50k goes from" in line and "falls over n at 0 of 2 photon counts" in line


def test_findings_wording_from_tests():
    """Finding 1 ranks only disjoint intervals: n = 100 below n = 10 at 50k
    (disjoint), P_e undetermined at n = 10 (overlapping); the paper's value
    inside our interval is counted."""
    t = table1_frame([(80, 75, 85), (40, 38, 42), (82, 70, 95)], [(0.01, 0.0, 0.02)] * 3)
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "table1.csv")
        t.to_csv(path, index=False)
        _, lines = md("table", {"table": path})
        text = "\n".join(lines)
        assert "at P_e = 50000: the ratio at n = 100 is ranked below the one at n = 10" in text
        assert "Over P_e at n = 10: the ratio at P_e = 500000 against the one at P_e = 50000: undetermined" in text
        assert "1 of 1 cells at P_e = 500000" in text and "0 of 2 cells at P_e = 50000" in text
        # a table without the paired columns: the finding says so, no number
        t.drop(columns=["paired_ratio_percent"]).to_csv(path, index=False)
        try:
            md("table", {"table": path})
            assert False, "the table record answered without its column"
        except findings.Missing as e:
            assert "paired_ratio_percent" in str(e)


def test_findings_resolution_per_size():
    """Finding 7 gives one block per output size, in size order, from each
    equal-error-WxH.csv; a CSV without the curve's columns is named, not
    read (negative control)."""
    rows = lambda s: pd.DataFrame([  # noqa: E731
        {"estimate": "paper", "kind": "tightest", "target": 0.02, "speedup": s, "lo": s - 0.1, "hi": s + 0.1,
         "defined_fraction": 0.5},
        {"estimate": "paper", "kind": "curve", "target": 0.02, "speedup": s, "lo": s - 0.1, "hi": s + 0.1,
         "defined_fraction": 0.5},
        {"estimate": "paper", "kind": "curve", "target": 0.03, "speedup": s + 0.2, "lo": s + 0.1, "hi": s + 0.3,
         "defined_fraction": 1.0}])
    with tempfile.TemporaryDirectory() as d:
        rows(0.75).to_csv(os.path.join(d, "equal-error-1024x768.csv"), index=False)
        rows(1.25).to_csv(os.path.join(d, "equal-error-256x192.csv"), index=False)
        _, lines = md("resolution", {"root": d, "resolution": d})
        text = "\n".join(lines)
        assert text.index("- 256x192:") < text.index("- 1024x768:")
        # the headline: the curve's tightest target where 95% of the resamples are defined
        assert "1.45 [1.35, 1.55]x" in text and "0.95 [0.85, 1.05]x" in text
        assert "1.25 [1.15, 1.35]" not in text and "0.75 [0.65, 0.85]" not in text  # the tightest: 50% defined
        rows(1.0).drop(columns=["kind"]).to_csv(os.path.join(d, "equal-error-512x384.csv"), index=False)
        try:
            md("resolution", {"root": d, "resolution": d})
            assert False, "the resolution record read a CSV without its columns"
        except findings.Missing as e:
            assert "kind" in str(e)


def test_tightest_half_defined_not_quoted():
    """An equal-error CSV whose tightest target is reached by both fronts in
    only 50% of the resamples: FINDINGS.md and README's summary name it as
    where the curve starts and quote no number of its row; they quote the
    tightest curve target with at least 95% defined. Negative control: the
    same CSV with the tightest target fully defined quotes it."""
    def frame(tight_defined):
        return pd.DataFrame([
            {"estimate": "paper", "kind": "tightest", "target": 0.0101, "speedup": 1.83, "lo": 0.917, "hi": 7.77,
             "defined_fraction": tight_defined},
            {"estimate": "paper", "kind": "curve", "target": 0.0101, "speedup": 1.83, "lo": 0.917, "hi": 7.77,
             "defined_fraction": tight_defined},
            {"estimate": "paper", "kind": "curve", "target": 0.0123, "speedup": 1.61, "lo": 1.42, "hi": 1.88,
             "defined_fraction": 0.97},
            {"estimate": "paper", "kind": "curve", "target": 0.0187, "speedup": 2.44, "lo": 2.11, "hi": 2.83,
             "defined_fraction": 1.0}])
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "equal-error.csv")
        frame(0.5).to_csv(path, index=False)
        for text in ("\n".join(md("equal_error", {"equal_error": path})[1]),
                     readme("equal_error", {"equal_error": path})):
            assert "1.83" not in text and "0.917" not in text and "7.77" not in text, text
            assert "the curve starts at relmse 0.0101" in text.lower(), text
            assert "at 0.0123" in text and "1.61 [1.42, 1.88]x" in text, text
        frame(1.0).to_csv(path, index=False)
        text = readme("equal_error", {"equal_error": path})
        assert "at 0.0101" in text and "1.83 [0.917, 7.77]x" in text, text


def test_findings_beyond():
    """Finding B quotes each case's paper rule and best variant with their
    intervals and counts the cases where the goal holds; a case with fewer
    than MIN_SEEDS_QUOTED seeds is named without its intervals (negative
    control), and a table without the seeds column names the target."""
    def row(case, variant, sp, lo, hi, best, above, vs, met, seeds):
        ratio = {"higher": 1.2, "lower": 0.8}.get(vs, 1.0)
        return {"case": case, "variant": variant, "estimate": "paper", "target": 0.02, "speedup": sp, "lo": lo,
                "hi": hi, "defined_fraction": 1.0, "fallback_rate": 0.125, "evaluated_share": 0.5, "seeds": seeds, "best": best,
                "above_one": above, "vs_paper": vs, "goal_met": met, "image_group": variant, "vs_paper_ratio": ratio,
                "vs_paper_ratio_lo": ratio - 0.05, "vs_paper_ratio_hi": ratio + 0.05}
    rows = [row("a-64x48", "paper", 0.9, 0.8, 1.0, False, False, "", False, 5),
            row("a-64x48", "lazy", 1.3, 1.2, 1.4, True, True, "higher", True, 5),
            row("b-64x48", "paper", 1.1, 1.05, 1.2, False, True, "", False, 5),
            row("b-64x48", "gated0.1", 0.97, 0.9, 1.02, True, False, "lower", False, 5),
            row("c-64x48", "paper", 2.0, 1.9, 2.1, False, True, "", False, 3),
            row("c-64x48", "lazy", 2.5, 2.4, 2.6, True, True, "higher", True, 3),
            row("d-64x48", "paper", 1.0, 0.9, 1.1, False, False, "", False, 5),
            row("d-64x48", "lazy", 1.2, 1.004, 1.5, True, True, "undetermined", True, 5)]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "beyond.csv")
        pd.DataFrame(rows).to_csv(path, index=False)
        _, lines = md("beyond", {"beyond": path})
        text = "\n".join(lines)
        assert ("a-64x48 (5 seeds, each at its own tightest target): the paper's rule 0.900 [0.800, 1.000]x at relMSE "
                "0.02; the best variant, lazy, 1.300 [1.200, 1.400]x at relMSE 0.02") in text
        assert "12.5% of its eye samples fell back, 50.0% of the representatives" in text
        assert "against the paper's rule, paired per seed (Holm): faster" in text
        assert "b-64x48" in text and "(Holm): slower" in text and "the goal does not hold" in text
        assert "c-64x48: 3 seeds" in text and "[2.4, 2.6]" not in text
        assert "1.200 [1.004, 1.500]x at relMSE 0.02, its interval above 1.0 only by less than the 2% margin" in text
        assert "holds as worded, by a margin too thin to rely on" in text
        assert "holds in 2 of 3 cases, 1 of them with the interval's lower end within the margin" in text
        assert "a variant is faster than the paper's rule in 2 of 4 scene and size cases (a-64x48: lazy; c-64x48: lazy)" in text
        pd.DataFrame(rows).drop(columns=["seeds"]).to_csv(path, index=False)
        try:
            md("beyond", {"beyond": path})
            assert False, "the beyond record answered without the seeds column"
        except findings.Missing as e:
            assert "make beyond" in str(e)


def test_findings_scale():
    """Finding P quotes the largest map's row of each method and the paired
    two-thread speed-up (geometric mean of t1 / t2 per pair, t interval); without threads.csv it
    names the target instead of a number (negative control)."""
    sc = pd.DataFrame([{"method": "conventional", "photons_emitted": p, "photons_stored": 4 * p, "threads": 2,
                        "trace_s": p / 1e6, "build_s": 0.5, "precompute_s": 0.0, "eye_s": 0.25,
                        "total_s": p / 1e6 + 0.75, "bytes_per_stored": b} for p, b in ((1000, 90.0), (8000, 44.5))])
    th = pd.DataFrame([{"photons_emitted": 8000, "pair": k, "threads": t, "trace_s": 4.0 / t ** e,
                        "build_s": 2.0 / t, "total_s": 6.0 / t} for k, e in ((1, 1.0), (2, 0.5), (3, 0.0))
                       for t in (1, 2)])
    with tempfile.TemporaryDirectory() as d:
        sp, tp = os.path.join(d, "scaling.csv"), os.path.join(d, "threads.csv")
        sc.to_csv(sp, index=False)
        th.to_csv(tp, index=False)
        _, lines = md("scale", {"scaling": sp, "threads": tp})
        text = "\n".join(lines)
        assert "8,000 emitted photons (32,000 stored): 0.758 s in total" in text and "44.5 bytes" in text
        assert "90" not in text.split("8,000 emitted")[0]
        # per pair 2, 1.41, 1: geometric mean 1.41, t interval over 3 pairs [0.598, 3.35]
        assert "photon pass 1.41x [0.598, 3.35]" in text and "kd-tree build 2x [2, 2]" in text
        os.remove(tp)
        try:
            md("scale", {"scaling": sp, "threads": tp})
            assert False, "the scale record answered without threads.csv"
        except findings.Missing as e:
            assert "make bench-threads" in str(e)


# ---- the record functions: a synthetic results directory with known numbers

def write_csv(d, rel, rows):
    """ROWS (a list of dicts) as the CSV D/REL; its path."""
    path = os.path.join(d, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    pd.DataFrame(rows).to_csv(path, index=False)
    return path


def test_record_table():
    """The table record: ranks over n only between disjoint intervals, the
    paper's value inside/outside our interval counted by hand."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "table1.csv")
        table1_frame([(80, 75, 85), (40, 38, 42), (68, 65, 71)], [(0.01, 0.005, 0.02)] * 3).to_csv(path, index=False)
        r = findings.record_table({"table": path})
        assert r["pairs"] == (5, 5) and r["photons"] == [50000, 500000] and r["nns"] == [10, 100]
        assert r["over_n"][50000]["rank"] == "lower" and r["over_n"][50000]["count"] == 2
        assert r["over_n"][500000]["count"] == 1 and r["falls"] == 1
        assert r["grid"][(100, 500000)] is None and r["grid"][(100, 50000)]["ratio"] == 40
        # paper 70: inside only at (500k, 10) (65-71); outside: 75-85 above it, 38-42 below it
        assert r["inside"] == {50000: (0, 2), 500000: (1, 1)}
        assert r["inside_any"] and not r["inside_all"] and r["outside"] == 2 and r["outside_lower"] == 1
        # negative control: the paper's value moved inside every interval
        t = table1_frame([(80, 60, 85), (40, 38, 72), (68, 65, 71)], [(0.01, 0.005, 0.02)] * 3)
        t.to_csv(path, index=False)
        r = findings.record_table({"table": path})
        assert r["inside_all"] and r["outside"] == 0 and r["over_n"][50000]["rank"] == "overlap"


def test_record_cost():
    """The cost record: verdict groups per estimate, the bias share of the
    excess (cells.csv: excess 0.04 of which 0.01 bias = 25%), the largest
    excess, and what ten times the photons remove (1 - 0.02/0.08 = 75%)."""
    with tempfile.TemporaryDirectory() as d:
        rows = []
        for (ph, n), (m, v), (cm, cc) in zip([(50000, 10), (50000, 100), (500000, 10), (500000, 100)],
                                            [(0.05, "higher"), (0.02, "higher"), (0.0, "equivalent"), (0.01, None)],
                                            [(0.08, 0.001), (0.1, 0.05), (0.02, 0.001), (0.09, 0.05)]):
            rows.append({"photons": ph, "nn": n, "method": "precomputed", "pairs": 5, "relmse_diff_mean": m,
                         "relmse_diff_lo": m - 0.01, "relmse_diff_hi": m + 0.01, "relmse_diff_verdict": v,
                         "relmse_conv_mean": cm, "relmse_conv_ci95": cc})
        table = write_csv(d, "table1.csv", rows)
        cells = []
        for (ph, n), (e, b) in zip([(50000, 10), (50000, 100)], [(0.04, 0.01), (0.02, 0.015)]):
            cells.append({"method": "conventional", "estimate": "paper", "photons": ph, "nn": n,
                          "relmse_ref_mean": 0.1, "bias_ref": 0.02})
            cells.append({"method": "precomputed", "estimate": "paper", "photons": ph, "nn": n,
                          "relmse_ref_mean": 0.1 + e, "bias_ref": 0.02 + b})
        r = findings.record_cost({"table": table, "cells": write_csv(d, "cells.csv", cells)})
        g = r["verdicts"]["paper"]["groups"]
        assert [(c["photons"], c["nn"]) for c in g["higher"]] == [(50000, 10), (50000, 100)]
        assert len(g["equivalent"]) == 1 and len(g["undetermined"]) == 1 and "corrected" not in r["verdicts"]
        s = r["bias_share"][0]
        assert s["cells"] == 2 and abs(s["min"] - 0.25) < 1e-9 and abs(s["max"] - 0.75) < 1e-9
        assert (s["largest"]["photons"], s["largest"]["nn"]) == (50000, 10)
        w = r["worst"]
        assert (w["photons"], w["nn"]) == (50000, 10) and abs(w["share"] - 0.25) < 1e-9 and w["mean"] == 0.05
        assert w["overlaps"] == [] and "the largest excess is at (50k, 10)" in findings.readme_cost(r)
        # control: an overlapping "higher" cell leaves the largest unranked, and is named
        w["overlaps"] = [(50000, 100)]
        text = findings.readme_cost(r)
        assert "the largest excess is" not in text and "overlapping those of (50k, 100) (no cell is ranked" in text
        m = r["more_photons"]
        assert m["factor"] == 10 and [x["nn"] for x in m["per_n"]] == [10, 100]
        assert abs(m["per_n"][0]["removed"] - 0.75) < 1e-9 and m["per_n"][0]["disjoint"]
        assert abs(m["per_n"][1]["removed"] - 0.1) < 1e-9 and not m["per_n"][1]["disjoint"]


def test_record_bias():
    """The bias record: the n = 10 row, whether it sits on the law, and the
    corrected intervals that contain 1 (3 of 4 by construction)."""
    rows = [{"n": n, "law_n_over_n_minus_1": n / (n - 1), "conventional_paper_mean": n / (n - 1) + 0.001,
             "conventional_paper_ci95": 0.002, "conventional_paper_seeds": 8,
             "conventional_corrected_mean": 1.0005, "conventional_corrected_ci95": 0.001,
             "precomputed_corrected_mean": c, "precomputed_corrected_ci95": 0.001} for n, c in ((10, 0.9999), (20, 1.01))]
    with tempfile.TemporaryDirectory() as d:
        r = findings.record_bias({"bias": write_csv(d, "b.csv", rows)})
        assert r["at10"]["n"] == 10 and r["at10"]["on_law"] and r["quoted"]["seeds"] == 8
        assert (r["covered"], r["intervals"]) == (3, 4)
        assert r["lowest"][0] == 0.9999 and r["highest"][0] == 1.01
        rows[0].update(n=5, conventional_paper_mean=1.2)  # no n = 10 row: the smallest n, off its law
        r = findings.record_bias({"bias": write_csv(d, "b.csv", rows)})
        assert r["at10"] is None and r["quoted"]["n"] == 5 and not r["quoted"]["on_law"]
        assert "not shown equivalent to it within 1%" in findings.law_text(r)
        # on the law within the 1% margin: a 95% interval of +-0.5% of the law is
        # inside it; control: one of +-1.5% (containing the law) is not
        rows[0].update(n=10, conventional_paper_mean=10 / 9, conventional_paper_ci95=0.005 * 10 / 9)
        rows[1].update(conventional_paper_ci95=0.015 * 20 / 19, conventional_paper_mean=20 / 19)
        r = findings.record_bias({"bias": write_csv(d, "b.csv", rows)})
        assert r["quoted"]["on_law"] and (r["law_equivalent"], r["law_rows"]) == (1, 2)
        assert findings.law_text(r) == (
            ", equivalent to it within 1% (its 95% interval is 0.9950-1.0050 of the law); at the 2 n where the law "
            "lies more than 2% from 1 (so that equivalence to it rules out no bias), 1 are equivalent to it")
        rows.append({**rows[1], "n": 100, "law_n_over_n_minus_1": 100 / 99, "conventional_paper_mean": 100 / 99})
        r = findings.record_bias({"bias": write_csv(d, "b.csv", rows)})
        assert r["law_rows"] == 2  # n = 100: its law lies 1.01% from 1, too close to tell (control)
        # the precomputed method's paper estimate: said beside its own law, n/(n-2), when the file has it
        assert r["quoted"]["precomputed"] is None and "precomputed method 1" not in findings.brief_bias(r)
        rows[0].update(precomputed_paper_mean=1.17, precomputed_paper_ci95=0.004, law_n_over_n_minus_2=1.25)
        r = findings.record_bias({"bias": write_csv(d, "b.csv", rows)})
        assert r["quoted"]["precomputed"] == {"mean": 1.17, "ci95": 0.004, "law": 1.25}
        assert "and the precomputed method 1.170 (its representatives follow n/(n-2), 1.250)" in findings.brief_bias(r)
        assert "1.17 ± 0.004 at n = 10" in findings.readme_bias(r)


def test_record_caustic_scenes_baseline():
    """The caustic record ranks the window against the image only when the
    intervals are disjoint; the scenes record carries the seeds; the
    baseline record counts the cells whose trace interval excludes 100."""
    with tempfile.TemporaryDirectory() as d:
        base = {"estimate": "paper", "photons": 50000, "nn": 10, "method": "precomputed", "img_excess_mean": 0.1,
                "img_excess_ci95": 0.01, "seeds": 5}
        c = write_csv(d, "c.csv", [{**base, "win_excess_mean": 0.3, "win_excess_ci95": 0.05},
                                   {**base, "nn": 50, "win_excess_mean": 0.12, "win_excess_ci95": 0.05},
                                   {**base, "method": "conventional", "win_excess_mean": 0.0, "win_excess_ci95": 0.0}])
        r = findings.record_caustic({"caustic": c})
        assert [x["rank"] for x in r["rows"]] == ["higher", "overlap"]
        s = write_csv(d, "s.csv", [{"scene": "a", "diff_seeds": 3, "ee_paper": "x", "ee_corrected": "y"}])
        assert findings.record_scenes({"scenes": s})["rows"] == [{"scene": "a", "seeds": 3, "paper": "x",
                                                                 "corrected": "y"}]
        t = table1_frame([(80, 75, 85), (99, 97, 101), (103, 101, 105)], [(0.01, 0.005, 0.02)] * 3)
        r = findings.record_baseline({"table": write_csv(d, "t.csv", t.to_dict("records"))})
        assert (r["median"], r["min"], r["max"], r["off"], r["cells"]) == (99, 80, 103, 2, 3)


def test_record_equal_error_and_resolution():
    """The equal-error record: the tightest row, the span where 95% of the
    resamples are defined, its ends' rank, and the headline against 1; an
    estimate without a tightest row has none (its writer says so)."""
    rows = [{"estimate": "paper", "kind": "tightest", "target": 0.01, "speedup": 0.5, "lo": 0.4, "hi": 0.6,
             "defined_fraction": 1.0},
            {"estimate": "paper", "kind": "curve", "target": 0.01, "speedup": 0.5, "lo": 0.4, "hi": 0.6,
             "defined_fraction": 1.0},
            {"estimate": "paper", "kind": "curve", "target": 0.02, "speedup": 2.0, "lo": 1.8, "hi": 2.2,
             "defined_fraction": 1.0},
            {"estimate": "corrected", "kind": "curve", "target": 0.02, "speedup": 1.0, "lo": 0.8, "hi": 1.2,
             "defined_fraction": 0.5}]
    with tempfile.TemporaryDirectory() as d:
        write_csv(d, "equal-error.csv", rows)
        r = findings.record_equal_error({"equal_error": os.path.join(d, "equal-error.csv")})["estimates"]
        p, c = r
        assert p["tightest"]["target"] == 0.01 and p["span"][0]["speedup"] == 0.5 and p["span"][1]["speedup"] == 2.0
        assert p["span_rank"] == "lower" and p["headline"]["target"] == 0.01 and p["headline_vs_one"] == "lower"
        assert p["curve_targets"] == 2 and c["tightest"] is None and c["headline"] is None
        write_csv(d, "res/equal-error-512x384.csv", rows)
        write_csv(d, "res/equal-error-64x48.csv", rows[:2])
        r = findings.record_resolution({"root": d, "resolution": os.path.join(d, "res")})
        assert [s["size"] for s in r["sizes"]] == ["64x48", "512x384"] and r["dir"] == "res"
        assert r["sizes"][0]["file"] == os.path.join("res", "equal-error-64x48.csv")
        assert r["sizes"][0]["estimates"][0]["span"] is not None and r["sizes"][0]["estimates"][0]["span_rank"] == "overlap"


def test_record_scale_stability_repro_rules():
    """The scale record's conventional row and its two-thread speed-ups (the
    pairs' t1/t2: 4/2, 4/4, 4/1 -> geometric mean 2, t interval); the stability record's file;
    the repro summary row; the rules rejected."""
    with tempfile.TemporaryDirectory() as d:
        sc = write_csv(d, "scaling.csv", [{"method": m, "photons_emitted": p, "photons_stored": 2 * p, "threads": 2,
                                           "trace_s": 1, "build_s": 1, "precompute_s": 0, "eye_s": 1, "total_s": t,
                                           "bytes_per_stored": 40} for m, p, t in
                                          (("conventional", 1000, 3.0), ("conventional", 9000, 7.0),
                                           ("precomputed", 9000, 5.0))])
        th = write_csv(d, "threads.csv", [{"photons_emitted": 9000, "pair": k, "threads": t, "trace_s": 4 / (s if t == 2 else 1),
                                           "build_s": 1.0, "total_s": 6 if t == 1 else 3} for k, s in ((1, 2), (2, 1), (3, 4))
                                          for t in (1, 2)])
        r = findings.record_scale({"scaling": sc, "threads": th})
        c = r["conventional"]
        assert c["photons_emitted"] == 9000 and c["total_s"] == 7.0 and c["two_total_median"] == 3
        h = 4.302652729911275 * math.log(2) / math.sqrt(3)  # t(0.975, 2) x sd of log(2, 1, 4) / sqrt(3)
        assert c["two_total_pairs"] == 3 and abs(c["trace"][0] - 2) < 1e-12 and c["trace"][3] == 3
        assert abs(c["trace"][1] - 2 * math.exp(-h)) < 1e-9 and abs(c["trace"][2] - 2 * math.exp(h)) < 1e-9
        assert [m for m, _ in r["largest"]] == ["conventional", "precomputed"]
        os.makedirs(os.path.join(d, "stability"))
        open(os.path.join(d, "stability", "x.md"), "w", encoding="utf-8").close()
        assert findings.record_stability({"root": d, "stability": os.path.join(d, "stability", "x.md")}) == \
            {"file": os.path.join("stability", "x.md")}
        try:
            findings.record_stability({"root": d, "stability": os.path.join(d, "nope.md")})
            assert False, "the stability record answered without its file"
        except findings.Missing as e:
            assert "make stability" in str(e)
        rp = write_csv(d, "repro.csv", [{"summary_ratio_median_abs_delta_pp": 1.5, "summary_ratio_max_abs_delta_pp": 4.0,
                                         "summary_ratio_overlap_cells": 8, "summary_cells": 9, "summary_goal_pp": 2,
                                         "summary_met": True}])
        r = findings.record_repro({"repro": rp})
        assert {k: r[k] for k in ("median_pp", "max_pp", "overlap", "cells", "goal_pp", "met")} == \
            {"median_pp": 1.5, "max_pp": 4.0, "overlap": 8, "cells": 9, "goal_pp": 2, "met": True}
        # the old file (no runs column) is the interleaved design, without the drift clause
        assert r["design"] == "two interleaved runs of the grid" and r["drift_inside_cells"] is None
        # the sequential design: its rows of runs a-b, the drift clause, the busy run's row
        rows = [{"runs": "a-b", "summary_ratio_median_abs_delta_pp": 2.0, "summary_ratio_max_abs_delta_pp": 5.0,
                 "summary_ratio_overlap_cells": 9, "summary_cells": 9, "summary_goal_pp": 1.5, "summary_met": False,
                 "summary_max_pp": 4, "summary_drift_lo": 97, "summary_drift_hi": 103, "summary_drift_inside_cells": 3,
                 "summary_drift_min": 60.0, "summary_drift_max": 104.0},
                {"runs": "a-busy", "summary_ratio_median_abs_delta_pp": 1.0, "summary_ratio_max_abs_delta_pp": 2.0,
                 "summary_ratio_overlap_cells": 9, "summary_cells": 9, "summary_goal_pp": 3, "summary_met": True}]
        r = findings.record_repro({"repro": write_csv(d, "repro2.csv", rows)})
        assert r["design"].startswith("two runs of `make reproduce-table`") and r["drift_inside_cells"] == 3
        assert r["busy"]["median_pp"] == 1.0 and r["busy"]["met"]
        text = "\n".join(findings.md_repro(r)[1])
        assert "in 3 of 9 cells (range 60.0-104.0%)" in text and "(goal 4 pp)" in text and "goal not met (the median shift is above " \
            "1.5 pp, and the largest shift is above 4 pp, and the drift control lies outside [97%, 103%] in 6 of 9 cells)." in text
        ru = write_csv(d, "rules.csv", [{"rule": k, "label": k.upper(), "fitted": False, "chi2": 1.0, "dof": 3,
                                         "p_value": 0.5, "p_holm": 0.9, "verdict": v}
                                        for k, v in (("a", "incompatible"), ("b", "not rejected"), ("c", "incompatible"))])
        r = findings.record_rules({"rep": ru})
        assert r["rejected"] == ["A", "C"] and len(r["rows"]) == 3
        assert r["sensitivity"] == [] and findings.sensitivity_text(r) == ""  # an old file: nothing said
        # the verdicts at half and twice the paper's assumed noise, when the rules file carries them
        ru = write_csv(d, "rules2.csv", [{"rule": k, "label": k.upper(), "fitted": False, "chi2": 1.0, "dof": 3,
                                          "p_value": 0.5, "p_holm": 0.9, "verdict": "not rejected",
                                          "verdict_noise_x0.5": h, "verdict_noise_x2": "not rejected"}
                                         for k, h in (("a", "incompatible"), ("b", "not rejected"),
                                                      ("c", "incompatible"))])
        r = findings.record_rules({"rep": ru})
        assert r["sensitivity"] == [{"factor": 0.5, "rejected": ["A", "C"]}, {"factor": 2.0, "rejected": []}]
        assert findings.sensitivity_text(r) == "; at half that noise they reject 2 (A and C), and at twice that noise none"
        assert "reject none of the 3 rules" in findings.brief_rules(r) and "half that noise they reject 2 (A and C)" in \
            findings.brief_rules(r)


def test_record_metric_and_peers():
    """The metric record: NMSE proportional to relMSE per cell keeps the
    rank correlation at 1 and the ratio fixed; the peers record: ours twice
    as fast as the strongest peer (cKDTree), nanoflann four times slower."""
    runs = []
    for ph, n, base in ((50000, 10, 1.0), (50000, 50, 2.0), (500000, 10, 3.0)):
        for seed in range(5):
            for method, extra in (("conventional", 0.0), ("precomputed", 0.5)):
                v = base + extra + 0.01 * seed
                runs.append({"role": "grid", "status": "ok", "method": method, "estimate": "paper", "photons": ph,
                             "nn": n, "seed": seed, "relmse_ref": v, "nmse_ref": 2 * v})
    runs.append({**runs[0], "role": "reference", "nmse_ref": 100.0})  # not a grid run: ignored
    with tempfile.TemporaryDirectory() as d:
        r = findings.record_metric({"runs": write_csv(d, "runs.csv", runs)})["estimates"]
        assert len(r) == 1 and r[0]["cells"] == 6 and r[0]["compared"] == 3 and r[0]["changed"] == []
        assert abs(r[0]["rho"] - 1) < 1e-12 and abs(r[0]["ratio_min"] - 2) < 1e-12 and abs(r[0]["ratio_max"] - 2) < 1e-12
        peers = [{"who": w, "order": "tiles", "pe": 50000, "stored": 1000, "k": 50, "queries": 10, "rep": rep,
                  "seconds": s} for w, s in (("ours", 1.0), ("flann-knn", 3.0), ("flann-radius", 5.0), ("ckdtree", 2.0),
                                             ("nanoflann", 4.0)) for rep in (0, 1)]
        peers.append({**peers[0], "rep": "build", "seconds": 99.0})
        r = findings.record_peers({"peers": write_csv(d, "peers.csv", peers)})
        assert r["rows"] == [{"k": 50, "pe": 50000, "strongest": "ckdtree", "strongest_ratio": 2.0,
                              "nanoflann_ratio": 4.0, "strongest_range": (2.0, 2.0)}]
        # the per-run range pairs the answers of one run (control: a run where ours is slower widens it)
        peers += [{**peers[0], "who": "ours", "rep": 2, "seconds": 2.0}, {**peers[0], "who": "ckdtree", "rep": 2,
                                                                          "seconds": 2.0}]
        r = findings.record_peers({"peers": write_csv(d, "peers.csv", peers)})
        assert r["rows"][0]["strongest_range"] == (1.0, 2.0)


def test_writers_read_only_the_record():
    """FINDINGS.md and README's summary quote a record's numbers as they are
    (hand-made records, no file read): a number changed in the record moves
    in both texts."""
    rec = {"median_pp": 1.234, "max_pp": 5.678, "overlap": 7, "cells": 9, "goal_pp": 2, "met": False}
    recs = {name: findings.Missing("absent") for name in findings.RECORDS}
    recs["repro"] = rec
    md_text = findings.markdown({"root": "x"}, recs)
    sm_text = findings.summary({"root": "x"}, recs)
    assert "1.23 pp (goal 2 pp), largest 5.68 pp; the two runs' intervals overlap in 7 of 9 cells; goal not met " \
        "(the intervals are disjoint in 2 of 9 cells)." in md_text
    assert "overlap in 7 of 9 cells" in sm_text and "largest shift is 5.68 pp" in sm_text
    assert md_text.count("Not answered here: absent.") == len(findings.FINDINGS) - 1
    recs["repro"] = {**rec, "overlap": 9}
    assert "overlap in 9 of 9 cells" in findings.summary({"root": "x"}, recs)


def test_primary_estimate_and_changed_verdicts():
    """One primary estimate, the other beside it only where the verdict
    words differ: a cell with the same verdict in both is not listed."""
    assert findings.PRIMARY_ESTIMATE in ("paper", "corrected")
    assert findings.OTHER_ESTIMATE != findings.PRIMARY_ESTIMATE
    a = {(50000, 10): "higher", (50000, 100): "equivalent", (500000, 10): "lower"}
    b = {(50000, 10): "higher", (50000, 100): "undetermined", (500000, 10): "lower"}
    assert findings.changed_verdicts(a, b) == [((50000, 100), "equivalent", "undetermined")]
    assert findings.changed_verdicts(a, dict(a)) == []
    assert findings.verdict_changes_text([]) == ""
    assert "(50k, 100) (undetermined)" in findings.verdict_changes_text(findings.changed_verdicts(a, b))


def table_with_paper(ratio_500k_10, paper_500k_10):
    """A table1.csv frame whose (500k, 10) cell has our paired ratio
    RATIO_500K_10 = (r, lo, hi) and the paper's PAPER_500K_10."""
    t = table1_frame([(80, 75, 85), (40, 38, 42), ratio_500k_10], [(0.01, 0.005, 0.02)] * 3)
    t.loc[(t["photons"] == 500000) & (t["nn"] == 10) & (t["method"] == "precomputed"),
          "paper_ratio_percent"] = paper_500k_10
    return t


def test_table_reversal():
    """Where the paper's method is slower (its ratio above 100%) and our
    interval lies wholly below 100%, the summary says so; negative control:
    our interval reaching 100% is no reversal."""
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "table1.csv")
        table_with_paper((85, 76, 94), 119.0).to_csv(path, index=False)
        r = findings.record_table({"table": path})
        assert [(x["photons"], x["nn"]) for x in r["reversed"]] == [(500000, 10)]
        assert r["ours_faster"] == 3 and r["cells"] == 3
        text = findings.readme_table(r)
        assert "One feature does not reproduce: at P_e = 500k with n = 10 the paper's method is slower (119.0%)" in text
        assert ("and at P_e = 500k with n = 10, where the paper's method was slower than its baseline, ours is "
                "faster.**") in text
        assert "undetermined" not in text
        table_with_paper((95, 88, 101), 119.0).to_csv(path, index=False)
        r = findings.record_table({"table": path})
        text = findings.readme_table(r)
        assert r["reversed"] == [] and "One feature does not reproduce" not in text and "ours is faster.**" not in text
        # the paper's method slower, our interval containing 100%: said, as undetermined
        assert ". At P_e = 500k with n = 10 the paper's method is slower (119.0%) and ours is undetermined " \
               "(95.0% [88.0, 101.0]: the interval contains 100%)" in text


def test_record_precompute():
    """The stated model at a cell of known answer: paper 100 s, its
    conventional 80 s; ours 10 s with a 2 s precompute against a 16 s
    conventional: the rest is 8/16 = 0.5 of the conventional time, so the
    paper's precompute is 100 - 80 x 0.5 = 60 s (60%), ours 20%, and per
    representative (1000) 60 ms against runs.csv's 2 ms; negative control:
    a paper time below its conventional rest gives a negative precompute,
    listed as where the model says nothing."""
    def table(paper_s):
        rows = []
        for ph, n in ((50000, 10), (500000, 10)):
            rows.append({"photons": ph, "nn": n, "method": "precomputed", "paper_s": paper_s, "paper_conv_s": 80.0,
                         "total_median_s": 10.0, "precompute_median_s": 2.0, "conv_total_median_s": 16.0,
                         "representatives": 1000})
            rows.append({"photons": ph, "nn": n, "method": "conventional", "paper_s": 80.0, "paper_conv_s": 80.0,
                         "total_median_s": 16.0, "precompute_median_s": 0.0, "conv_total_median_s": 16.0,
                         "representatives": 0})
        return rows
    runs = [{"role": "grid", "status": "ok", "method": m, "estimate": findings.PRIMARY_ESTIMATE, "photons": ph,
             "precompute_s": pre, "representatives": reps}
            for ph in (50000, 500000) for m, pre, reps in (("precomputed", 2.0, 1000), ("precomputed", 4.0, 1000),
                                                          ("conventional", 0.0, 0))]
    with tempfile.TemporaryDirectory() as d:
        rp = write_csv(d, "runs.csv", runs)
        r = findings.record_precompute({"table": write_csv(d, "table1.csv", table(100.0)), "runs": rp})
        c = r["cells"][-1]
        assert r["top"] == 500000 and abs(c["rest"] - 0.5) < 1e-12 and abs(c["paper_pre"] - 60) < 1e-9
        assert abs(c["paper_share"] - 0.6) < 1e-12 and abs(c["ours_share"] - 0.2) < 1e-12
        assert abs(r["paper_per_rep"] - 0.06) < 1e-12 and abs(r["ours_per_rep"] - 0.003) < 1e-12
        assert abs(r["machine"] - 5.0) < 1e-12 and abs(r["paper_per_rep_here"] - 0.012) < 1e-12
        assert r["negative"] == []
        assert "60.0-60.0% of its time" in findings.readme_precompute(r)
        # the model's spread: 60 ms per representative in both cells
        assert "over the P_e = 500k cells and from 6e+04 to 6e+04 µs over the others" \
            in "\n".join(findings.md_precompute(r)[1])
        r = findings.record_precompute({"table": write_csv(d, "table1.csv", table(30.0)), "runs": rp})
        assert r["negative"] == [(50000, 10), (500000, 10)]
        assert "says nothing" in "\n".join(findings.md_precompute(r)[1])


def curve_rows(spec, est="paper"):
    """Equal-error curve rows of estimate EST from SPEC = [(target, lo, hi, defined)]."""
    return [{"estimate": est, "kind": "curve", "target": t, "speedup": (lo + hi) / 2, "lo": lo, "hi": hi,
             "defined_fraction": f} for t, lo, hi, f in spec]


def test_curve_regions():
    """Where the curve pays: intervals wholly below 1 at the tight targets,
    containing 1 in between, wholly above at the loose ones; a target that
    fewer than 95% of the resamples reach is left out; the crossing lies
    between the last target below and the first above. Negative control: a
    curve wholly above 1 has no crossing and a different head."""
    spec = [(0.001, 0.5, 0.8, 0.99), (0.002, 0.6, 0.9, 0.99), (0.003, 0.9, 1.2, 0.99),
            (0.004, 1.1, 1.5, 0.99), (0.005, 0.2, 0.3, 0.5), (0.006, 1.2, 1.9, 1.0)]
    runs = findings.curve_regions(pd.DataFrame(curve_rows(spec)))
    assert [(x["class"], x["first"], x["last"], x["count"]) for x in runs] == [
        ("below", 0.001, 0.002, 2), ("contains", 0.003, 0.003, 1), ("above", 0.004, 0.006, 2)]
    assert findings.crossing_of(runs) == ("up", 0.002, 0.004)
    text = findings.regions_text(runs)
    assert "crosses 1 between 0.002 and 0.004, slower at the tighter targets" in text
    assert findings.regions_head(runs) == \
        "Small images: the precomputation pays at the looser targets, not at the tightest"
    up = findings.curve_regions(pd.DataFrame(curve_rows([(0.001, 1.1, 1.3, 1.0), (0.002, 1.2, 1.4, 1.0)])))
    assert findings.crossing_of(up) is None and "crosses" not in findings.regions_text(up)
    assert findings.regions_head(up).startswith("Small images: the precomputation still pays")
    # undetermined only at the tight end: said as such; control: in the middle it is "the rest"
    tight = findings.curve_regions(pd.DataFrame(curve_rows([(0.001, 0.9, 1.2, 1.0), (0.002, 1.2, 1.4, 1.0),
                                                            (0.003, 1.3, 1.5, 1.0)])))
    assert findings.regions_head(tight).endswith("pays at the looser targets enough resamples reach and is "
                                                 "undetermined at the tightest")
    mid = findings.curve_regions(pd.DataFrame(curve_rows([(0.001, 1.1, 1.2, 1.0), (0.002, 0.9, 1.4, 1.0),
                                                          (0.003, 1.3, 1.5, 1.0)])))
    assert findings.regions_head(mid).endswith("is undetermined at the rest")


def test_one_wording_of_the_curve():
    """README's summary and FINDINGS.md word the curve's trend with the same
    sentence (trend_text), and which sentence follows the test of its two
    ends: disjoint intervals say it depends on the target, overlapping ones
    that no trend is claimed (negative control: the other sentence absent)."""
    rows = [{"estimate": "paper", "kind": "tightest", "target": 0.01, "speedup": 1.5, "lo": 1.2, "hi": 1.8,
             "defined_fraction": 0.99}]
    for hi_end, claim in (((2.5, 2.1, 2.9), "depends on the target"), ((1.9, 1.5, 2.3), "no trend with the target")):
        spec = [(0.01, 1.2, 1.8, 0.99), (0.02, hi_end[1], hi_end[2], 0.99)]
        with tempfile.TemporaryDirectory() as d:
            path = write_csv(d, "equal-error.csv", rows + curve_rows(spec))
            rec = findings.record_equal_error({"equal_error": path})
        r = findings.estimate_of(rec["estimates"], "paper")
        sentence = findings.trend_text(r)
        assert claim in sentence
        other = "no trend with the target" if claim == "depends on the target" else "depends on the target"
        assert other not in sentence
        if findings.PRIMARY_ESTIMATE == "paper":
            assert sentence in findings.readme_equal_error(rec)
        assert any(sentence in x for x in findings.equal_error_lines(rec["estimates"]))


def test_bias_equivalence_and_share_interval():
    """The corrected intervals are equivalent to 1 only when wholly inside
    1 +- BIAS_MARGIN (negative control: an interval containing 1 but reaching
    beyond the margin is not); a bias share's interval holds the bias fixed
    over the excess's interval, and is not defined where the share is
    negative or the excess's interval reaches 0."""
    m = findings.BIAS_MARGIN
    b = pd.DataFrame([{"n": 10, "conventional_corrected_mean": 1.0, "conventional_corrected_ci95": m / 2,
                       "precomputed_corrected_mean": 1.0, "precomputed_corrected_ci95": 3 * m}])
    eq = findings.equivalence_to_one(b, m)
    assert [(e["method"], e["equivalent"]) for e in eq] == [("conventional", True), ("precomputed", False)]
    assert all(e["equivalent"] for e in findings.equivalence_to_one(b, 4 * m))
    share, lo, hi, ok = findings.share_interval(0.5, 1.0, 0.5, 2.0)
    assert ok and (share, lo, hi) == (0.5, 0.25, 1.0)
    assert findings.share_interval(-0.1, 1.0, 0.5, 2.0)[3] is False
    assert findings.share_interval(0.5, 1.0, -0.1, 2.0)[3] is False


def test_reference_error_and_figure3():
    """The margin widened to the reference's own error: an interval inside
    it becomes equivalent, one wholly beyond it stays ranked, one across its
    edge is undetermined; Figure 3's statements agree or not with the
    paired verdicts (negative control: a ranked cell is 'differ', never
    'alike')."""
    assert findings.verdict_at_margin(-0.0003, -0.0002, 0.0006) == "equivalent"
    assert findings.verdict_at_margin(0.001, 0.002, 0.0006) == "higher"
    assert findings.verdict_at_margin(-0.002, -0.001, 0.0006) == "lower"
    assert findings.verdict_at_margin(0.0004, 0.0008, 0.0006) == "undetermined"
    assert findings.verdict_at_margin(float("nan"), 0.1, 0.0006) == "undetermined"
    def table(last):
        rows = []
        for (ph, n, _), (m, lo, hi, v) in zip(findings.FIGURE3, ((0.03, 0.02, 0.04, "higher"),
                                                                 (-1e-5, -5e-5, 3e-5, "equivalent"), last)):
            rows.append({"photons": ph, "nn": n, "method": "precomputed", "relmse_diff_mean": m,
                         "relmse_diff_lo": lo, "relmse_diff_hi": hi, "relmse_diff_delta": 2e-4,
                         "relmse_diff_verdict": v, "relmse_ref_floor": 6e-4})
            rows.append({"photons": ph, "nn": n, "method": "conventional", "relmse_ref_floor": 6e-4})
        return rows
    # the fixture's columns are the paper estimate's: a change of the primary
    # estimate must rewrite it, not skip it
    assert findings.PRIMARY_ESTIMATE == "paper"
    with tempfile.TemporaryDirectory() as d:
        # the last cell ranked, but its interval inside +-delta: alike, said as
        # a difference smaller than the margin
        r = findings.record_figure3({"table": write_csv(d, "inside.csv", table((-1.5e-4, -1.8e-4, -1.2e-4, "lower")))})
        assert [x["paper"]["word"] for x in r["rows"]] == ["differ", "alike", "alike"]
        assert [x["paper"]["ranked_within"] for x in r["rows"]] == [False, False, True]
        text = "\n".join(findings.md_figure3(r)[1])
        assert "so the data disagree" not in text and "(ranked, by less than delta)" in text
        assert "by less than 2%" in findings.readme_figure3(r)
        # control: ranked beyond the margin is 'differ', never 'alike'
        path = write_csv(d, "table1.csv", table((-3e-4, -4e-4, -2.5e-4, "lower")))
        r = findings.record_figure3({"table": path})
        assert [x["paper"]["word"] for x in r["rows"]] == ["differ", "alike", "differ"]
        assert [x["paper"]["wide"] for x in r["rows"]] == ["differ", "alike", "alike"]
        text = "\n".join(findings.md_figure3(r)[1])
        assert "the paper says alike" in text and "so the data disagree" in text and "so the data agree" in text
        e = findings.record_reference_error({"table": path, "equal_error": os.path.join(d, "none.csv")})
        assert e["floor"] == 6e-4 and e["tightest"] is None
        p = e["estimates"]["paper"]
        assert [(c["photons"], c["verdict"], c["widened"]) for c in p["changed"]] == \
            [(500000, "lower", "equivalent")]
        assert p["judged"] == 2 and abs(p["times"][0] - 3) < 1e-9


def test_record_judges():
    """Which reference judges which study, from the cells files' ref column,
    and a converged reference's noise and bias as a study's Markdown quotes
    it; negative control: without that Markdown (and no JSON) they are None
    and the section says they are missing."""
    conv = "results/runs/cornell-convref-p1000-n200-s2-seeds9/64x48.exr"
    with tempfile.TemporaryDirectory() as d:
        root = os.path.join(d, "results")
        write_csv(root, "table1/cells.csv", [{"ref": "reference/cornell/cornell-reference-64x48.exr"}])
        write_csv(root, "resolution/cells-64x48.csv", [{"ref": conv}])
        write_csv(root, "beyond/studies/cells-cornell-64x48-paper.csv", [{"ref": conv}])
        write_csv(root, "beyond/studies/equal-error-cornell-64x48-paper.csv",
                  [{"kind": "tightest", "target": 0.004}, {"kind": "curve", "target": 0.005}])
        md = os.path.join(root, "resolution", "resolution.md")
        with open(md, "w", encoding="utf-8") as f:
            f.write(f"- 64x48: Reference `{conv}`: conventional method. Its own error in relmse: noise 0.0002 "
                    "(from the seeds), kernel bias 1e-05 (from halving P_e).\n")
        r = findings.record_judges({"root": root})
        kinds = {x["study"]: x["kinds"] for x in r["studies"]}
        assert kinds["Table 1"] == ["POV-Ray"] and kinds["resolution"] == ["converged photonmap"]
        assert kinds["beyond"] == ["converged photonmap"] and kinds["scenes"] == []
        (b,) = r["beyond"]
        assert b["cases"] == ["cornell-64x48"] and (b["noise"], b["bias"], b["tightest"]) == (0.0002, 1e-05, 0.004)
        assert "noise 5.0%" in "\n".join(findings.md_judges(r)[1])
        os.remove(md)
        (b,) = findings.record_judges({"root": root})["beyond"]
        assert b["noise"] is None and b["bias"] is None
        assert "is missing here" in "\n".join(findings.md_judges(findings.record_judges({"root": root}))[1])
        # the committed runs file carries the reference's error (collect.py's
        # ref_noise, ref_bias); control: empty columns do not count
        runs = write_csv(root, "beyond/studies/runs-cornell-64x48-paper.csv",
                         [{"ref_noise": "", "ref_bias": ""}, {"ref_noise": 0.0003, "ref_bias": 2e-05}])
        (b,) = findings.record_judges({"root": root})["beyond"]
        assert (b["noise"], b["bias"]) == (0.0003, 2e-05) and b["source"] == os.path.relpath(runs, root)
        write_csv(root, "beyond/studies/runs-cornell-64x48-paper.csv", [{"ref_noise": "", "ref_bias": ""}])
        assert findings.record_judges({"root": root})["beyond"][0]["noise"] is None


def test_scale_both_methods():
    """The scaling bullet gives both methods at the largest map and names
    the phase that makes the difference (the precompute, 3 s of the 2 s
    more; the eye pass's -1 s named beside the photon pass's 0 s, identical
    code in both); negative control: without a
    precomputed row the bullet names no difference."""
    rows = [{"method": m, "photons_emitted": 9000, "photons_stored": 18000, "threads": 2, "trace_s": 1, "build_s": 1,
             "precompute_s": pre, "eye_s": eye, "total_s": 2 + pre + eye, "bytes_per_stored": 40}
            for m, pre, eye in (("conventional", 0.0, 2.0), ("precomputed", 3.0, 1.0))]
    th = [{"photons_emitted": 9000, "pair": 1, "threads": t, "trace_s": 1.0, "build_s": 1.0, "total_s": 4.0 / t}
          for t in (1, 2)]
    with tempfile.TemporaryDirectory() as d:
        tp = write_csv(d, "threads.csv", th)
        r = findings.record_scale({"scaling": write_csv(d, "scaling.csv", rows), "threads": tp})
        assert r["both"]["largest_phase"] == "precompute" and r["both"]["phases"]["eye"] == -1.0
        text = findings.readme_scale(r)
        assert "the precomputed method took 6 s against the conventional 4 s" in text
        assert "(one render each)" in text  # no repeats column: timed once
        assert findings.timed_text(3) == "one process each, the minimum of its 3 repeats"
        assert findings.timed_text(3, each=False) == "one process, the minimum of its 3 repeats"
        for row in rows:
            row["repeats"] = 3
        r = findings.record_scale({"scaling": write_csv(d, "scaling.csv", rows), "threads": tp})
        assert "(one process each, the minimum of its 3 repeats)" in findings.readme_scale(r)
        assert "of the difference, 2 s, its precompute is 3 s; the photon pass, the same code in both, differs " \
            "by 0 s, and the eye pass by -1 s, more than that" in text
        r = findings.record_scale({"scaling": write_csv(d, "scaling.csv", rows[:1]), "threads": tp})
        assert r["both"] is None and "precomputed method took" not in findings.readme_scale(r)


def test_opener_anchors_figures():
    """FINDINGS.md opens with the summary, each bullet linked to its
    section's anchor, and shows a section's figures; a missing record's
    bullet is left out of the opener (negative control) and a figure that
    is not there is not linked."""
    rec = {"median_pp": 1.234, "max_pp": 5.678, "overlap": 7, "cells": 9, "goal_pp": 2, "met": False}
    recs = {name: findings.Missing("absent") for name in findings.RECORDS}
    recs["repro"] = rec
    recs["figures"] = {"repro": ["figures/x.png"]}
    text = findings.markdown({"root": "x"}, recs)
    assert text.index("## In short") < text.index('<a id="finding-R"></a>')
    assert "[Finding R](#finding-R)." in text and "![x.png](figures/x.png)" in text
    assert "[Finding 1](#finding-1)" not in text
    assert findings.PRIMARY_ESTIMATE_REASON in text
    with tempfile.TemporaryDirectory() as d:
        assert findings.figures_of({"root": d}) == {}
        os.makedirs(os.path.join(d, "figures"))
        open(os.path.join(d, "figures", "beyond.png"), "wb").close()
        assert findings.figures_of({"root": d}) == {"beyond": ["figures/beyond.png"]}


def test_peers_stateless_and_coverage_quoted():
    """The kNN bullet names the asymmetry and quotes the stateless ratio
    when the file has a stateless run (negative control: without it, says
    so); a few-seed line quotes the simulated coverage it is given."""
    peers = [{"who": w, "order": "tiles", "pe": 50000, "stored": 1000, "k": 10, "queries": 10, "rep": rep,
              "seconds": s} for w, s in (("ours", 1.0), ("flann-knn", 3.0), ("flann-radius", 5.0), ("ckdtree", 2.0),
                                         ("nanoflann", 4.0), ("ours-stateless", 1.6)) for rep in (0, 1)]
    with tempfile.TemporaryDirectory() as d:
        r = findings.record_peers({"peers": write_csv(d, "peers.csv", peers)})
        assert r["rows"][0]["stateless_ratio"] == 1.25
        text = findings.readme_peers(r)
        assert "carries its state" in text and "AVX2" in text and "without the carried state ours answers 1.25x" in text
        r = findings.record_peers({"peers": write_csv(d, "peers.csv", [p for p in peers
                                                                      if p["who"] != "ours-stateless"])})
        assert "has no stateless run" in findings.readme_peers(r)
    assert "covers the truth 74.5% of the time" in findings.few_seeds("x", 3, "make scenes", 0.745)
    assert "covers" not in findings.few_seeds("x", 3, "make scenes")


def test_record_repro_runs_a_b_busy():
    """A reproducibility.csv that names its runs: the a-b rows give the
    summary, the a-busy rows the busy run's, said in FINDINGS.md; negative
    control: without a-b rows the finding is missing, not a busy number."""
    def row(runs, med, met):
        return {"runs": runs, "summary_ratio_median_abs_delta_pp": med, "summary_ratio_max_abs_delta_pp": 2 * med,
                "summary_ratio_overlap_cells": 12, "summary_cells": 12, "summary_goal_pp": 3, "summary_met": met}
    with tempfile.TemporaryDirectory() as d:
        r = findings.record_repro({"repro": write_csv(d, "r.csv", [row("a-b", 1.5, True), row("a-b", 1.5, True),
                                                                    row("a-busy", 4.5, False)])})
        assert r["median_pp"] == 1.5 and r["met"] and r["busy"]["median_pp"] == 4.5 and not r["busy"]["met"]
        assert "busy loop: median |difference| 4.50 pp" in "\n".join(findings.md_repro(r)[1])
        try:
            findings.record_repro({"repro": write_csv(d, "r.csv", [row("a-busy", 4.5, False)])})
            assert False, "a file without runs a-b answered"
        except findings.Missing as e:
            assert "a-b" in str(e)
        # where the noise arises: said from the process columns, absent without them
        assert not any("Where the noise" in x for x in findings.md_repro(r)[1])
        assert "between two processes" not in findings.readme_repro(r)
        noisy = {**row("a-b", 1.5, True), "summary_process_change_median": 0.076, "summary_process_change_p90": 0.3,
                 "summary_drift_inside_cells_a": 8, "summary_drift_inside_cells_b": 7,
                 "summary_drift_inside_cells_min2": 10, "summary_drift_inside_cells_min3": 11}
        r = findings.record_repro({"repro": write_csv(d, "r.csv", [noisy])})
        text = "\n".join(findings.md_repro(r)[1])
        assert "moves by a median 7.6% between two processes" in text and "(90th percentile 30.0%)" in text
        assert "in 8 (run a) and 7 (run b) of 12 cells" in text
        assert "would lie inside in 10 timed over runs a's and b's processes and in 11 adding the run beside a busy loop" in text
        assert "moves by a median 7.6% between two processes" in findings.readme_repro(r)


AGREEMENT_HEADER = "scene,size,region,material_kind,pixels,pm_ratio,pm_ci,pm_bias,pov_ratio,holds"


def agreement_csv(d, rows):
    """An agreement.csv under D with a settings line and ROWS (CSV lines after the header); its path."""
    path = os.path.join(d, "agreement.csv")
    with open(path, "w", encoding="utf-8") as f:
        f.write("# 2000000 photons\n" + AGREEMENT_HEADER + "\n" + "\n".join(rows) + "\n")
    return path


def test_references_side_by_side():
    """Finding A counts each verdict per scene, spans the ratios of the
    diffuse regions where pbrt and photonmap agree (never the image row, a
    specular region or an undetermined one), and says where POV-Ray is off;
    a scene whose POV-Ray is off gets no 'POV-Ray where few bounces' claim."""
    rows = ["a,8x6,image (every pixel),,48,1.03,0.001,0.0,1.02,mixed: see the regions",
            "a,8x6,shape 1 (rect; white),lambert,20,0.998,0.002,0.001,0.990,all three agree",
            "a,8x6,shape 2 (rect; white),lambert,10,1.004,0.003,0.001,0.985,all three agree",
            "a,8x6,shape 3 (rect; mirror),mirror,10,1.14,0.003,-0.003,1.12,"
            "photonmap (BDPT cannot sample a caustic seen via a specular surface)",
            "a,8x6,shape 4 (rect; white),lambert,8,0.95,0.01,0.0,0.9,"
            "pbrt and photonmap disagree beyond their noise: undetermined",
            "b,8x6,shape 1 (rect; white),lambert,30,1.001,0.01,0.0,0.80,"
            "pbrt and photonmap agree; POV-Ray off by more than 2% plus pbrt's noise"]
    with tempfile.TemporaryDirectory() as d:
        rec = findings.record_references({"agreement": agreement_csv(d, rows)})
        a, b = rec["scenes"]
        assert (a["regions"], a["agree_n"], a["diffuse_n"]) == (4, 2, 3)
        assert {k: v["n"] for k, v in a["by"].items()} == {"all": 2, "pm_specular": 1, "undetermined": 1}
        assert a["agree_pm"] == (0.998, 1.004) and a["agree_pov"] == (0.985, 0.990)
        assert b["by"] == {"pov_off": {"n": 1, "pm": (1.001, 1.001), "pov": (0.8, 0.8),
                                       "names": ["shape 1 (rect; white)"]}}
        title, lines = findings.md_references(rec)
        text = "\n".join(lines)
        assert "in 3 of 4 diffuse regions" in text
        assert "POV-Ray where few bounces carry the light** (a)" in text
        assert "Not POV-Ray in b" in text and "0.800 of pbrt" in text
        assert "a shape 4 (rect; white), 8 pixels: photonmap 0.9500" in text
        assert "| a | image" not in text  # the image row is no region
        # control: POV-Ray off in scene a too removes a from the claim
        off = [r.replace("1.004,0.003,0.001,0.985,all three agree",
                         "1.004,0.003,0.001,0.9,pbrt and photonmap agree; POV-Ray off by more than 2%")
               for r in rows]
        text = "\n".join(findings.md_references(findings.record_references({"agreement": agreement_csv(d, off)}))[1])
        assert "POV-Ray where few bounces" not in text and "Not POV-Ray in a" in text
        assert "Why is not measured here" in text  # no cause is known for these made-up scenes


def test_references_missing():
    """Without agreement.csv finding A is Missing and names the script that writes it."""
    try:
        findings.record_references({"agreement": "/nonexistent/agreement.csv"})
    except findings.Missing as e:
        assert "measure-pbrt.sh" in str(e)
    else:
        raise AssertionError("no Missing")


def test_gather_finding():
    """Finding G counts, per grid, only the targets that enough resamples
    reach, and says a grid pays at every target only when each interval lies
    wholly above 1: a grid with one interval touching 1 does not count."""
    rows = ["scene,size,kind,target,conventional_s,precomputed_s,speedup,lo,hi,defined",
            "scenes/a.scene,8x6,equal_error,0.01,2,1,2.0,1.5,2.5,0.99",
            "scenes/a.scene,8x6,equal_error,0.02,2,1,1.8,1.2,2.2,0.97",
            "scenes/a.scene,8x6,equal_error,0.005,2,1,9.0,0.5,20,0.40",  # too few resamples: not counted
            "scenes/a.scene,8x6,gather_phase,,,,3.0,2.8,3.2,",
            "scenes/a.scene,8x6,precompute_share,,,,0.02,0.01,0.03,",
            "scenes/a.scene,8x6,memory_increase,,,,0.25,,,",
            "scenes/a.scene,8x6,work_bound,,,,2.5,,,",
            "scenes/b.scene,8x6,equal_error,0.01,2,1,1.3,0.9,1.6,0.99",
            "scenes/b.scene,8x6,equal_error,0.02,2,1,0.7,0.6,0.8,0.99",
            "scenes/b.scene,8x6,gather_phase,,,,1.5,1.4,1.6,"]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "gather.csv")
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(rows) + "\n")
        rec = findings.record_gather({"gather": path})
        a, b = rec["grids"]
        assert (a["scene"], a["targets"], a["above"], a["below"]) == ("a", 2, 2, 0)
        assert a["speedup"] == (1.8, 2.0) and a["gather"] == (3.0, 2.8, 3.2)
        assert (b["targets"], b["above"], b["below"]) == (2, 0, 1)
        text = "\n".join(findings.md_gather(rec)[1])
        assert "pays (its interval wholly above 1) at every one of its 2 targets" in text
        assert "pays at 0 of 2 targets, does not (wholly below 1) at 1, undetermined at 1" in text
        assert "in 1 of 2 grids (a at 8x6)" in text
        bullet = findings.readme_gather(rec)
        assert "0.70-2.00x" in bullet and "in 1 of 2 grids" in bullet and "1.50-3.00x" in bullet
        # the gather phase's intervals: both above 1, both wholly below 5x
        assert "its 95% interval lies above 1 in 2 of 2 grids, lies below 5x, Christensen's low end, in 2 of 2 " \
            "and lies below 12.7x, pbrt-v2's low end, in 2 of 2" in bullet
        b["gather"] = (1.5, 0.9, 6.0)  # control: containing 1 or 5x is undetermined against it, not ranked
        assert findings.gather_phase_intervals(rec["grids"]) == (
            "its 95% interval lies above 1 in 1 of 2 grids (the others contain 1: undetermined), lies below 5x, "
            "Christensen's low end, in 1 of 2 and contains it in 1 (undetermined against it) and lies below "
            "12.7x, pbrt-v2's low end, in 2 of 2")
        a["gather"] = (6.0, 5.5, 7.0)  # control: an interval wholly above 5x is ranked above it
        assert "contains 5x, Christensen's low end, in 1 of 2 (undetermined against it) and lies above it in 1" \
            in findings.gather_phase_intervals(rec["grids"])


def test_within_margin_text():
    """Ranked cells whose interval lies inside +-delta are said to differ by
    less than the margin: all of a group, some of it (named), or none
    (control: nothing is added)."""
    a = {"photons": 500000, "nn": 50, "inside": True}
    b = {"photons": 500000, "nn": 100, "inside": True}
    c = {"photons": 50000, "nn": 10, "inside": False}
    assert findings.within_margin_text([a, b]) == " (each by less than the 2% margin)"
    assert findings.within_margin_text([a]) == " (by less than the 2% margin)"
    assert findings.within_margin_text([a, c]) == " (by less than the 2% margin at (500k, 50))"
    assert findings.within_margin_text([c]) == ""
    assert findings.inside_margin(-1.8e-4, -1.2e-4, 2e-4) and not findings.inside_margin(-3e-4, -1e-4, 2e-4)
    assert not findings.inside_margin(float("nan"), 0.0, 1.0)


def test_brief_writers():
    """FINDINGS.md's two-minute opening: one sentence per finding from the
    same records, the counts computed here by hand; a zero count is left
    out; a record without the needed rows raises Missing (control)."""
    groups = {"higher": [{"photons": 50000, "nn": 10, "inside": False}],
              "lower": [{"photons": 500000, "nn": 100, "inside": True}],
              "equivalent": [{"photons": 100000, "nn": 50}, {"photons": 50000, "nn": 50}]}
    text = findings.brief_cost({"verdicts": {findings.PRIMARY_ESTIMATE: {"groups": groups}}, "cells": 4})
    assert "Of the 4 cells, the precomputed method's error is higher in 1, equivalent within 2% in 2 and lower " \
        "in 1 (each by less than 2%)." in text
    assert "undetermined" not in text
    res = {"dir": "resolution", "sizes": [
        {"size": "64x48", "estimates": [{"estimate": findings.PRIMARY_ESTIMATE, "tightest": {}, "regions": [
            {"class": "contains", "count": 3}, {"class": "above", "count": 10}]}]}, {"size": "128x96"}]}
    assert "of the 13 error targets enough resamples reach, the precomputation pays at 10 and is " \
        "undetermined at 3." in findings.brief_resolution(res)
    try:
        findings.brief_resolution({"dir": "resolution", "sizes": res["sizes"][:1]})
        assert False, "one size answered"
    except findings.Missing:
        pass
    rec = {"median_pp": 2.3376, "goal_pp": 1.5, "met": False, "process_change_median": 0.076}
    assert findings.brief_repro(rec) == ("- **A rerun.** A second run of Table 1 moves the time ratios by a median "
                                         "2.34 pp (goal 1.5 pp); goal not met (the median shift is above 1.5 pp); "
                                         "the same render's time moves by a median 7.6% between two processes.")
    # a miss is named by the clause that misses: here the drift control alone, not the median within its goal
    drift = {"median_pp": 1.37, "goal_pp": 1.5, "max_pp": 3.34, "goal_max_pp": 4, "overlap": 24, "cells": 24,
             "met": False, "drift_lo": 97, "drift_hi": 103, "drift_inside_cells": 22}
    text = findings.brief_repro(drift)
    assert "1.37 pp (goal 1.5 pp) and by at most 3.34 pp (goal 4 pp); goal not met (the drift control lies " \
        "outside [97%, 103%] in 2 of 24 cells)." in text and "median shift is above" not in text
    assert "but misses the goal" in findings.readme_repro(drift) and "in 2 of 24 cells" in findings.readme_repro(drift)
    assert findings.repro_verdict(drift | {"met": True}) == "goal met"
    assert findings.repro_verdict(drift | {"drift_inside_cells": None}) == "goal not met"
    # the opening: brief sentences first, the detailed bullets after, a
    # missing record left out of both
    out = findings.opener({name: findings.Missing("x") for name, _ in findings.SUMMARY} | {"repro": rec | {
        "max_pp": 9.2, "overlap": 24, "cells": 24}})
    i = out.index("## The summary in numbers")
    assert any(x.startswith("- **A rerun.**") and "(#finding-R)" in x for x in out[:i])
    assert any("median shift of the paired ratios of 2.34 pp" in x for x in out[i:])
    assert len([x for x in out if x.startswith("- ")]) == 2


def test_max_bias_term():
    """A reference at q times the truth adds at most (1/q - 1)^2 to an
    unbiased render's relMSE: checked against the per-pixel term computed
    directly over a range of brightness (its supremum, as t grows), from
    either side of 1; control: an exact reference adds nothing."""
    t = np.logspace(-3, 4, 200)
    for q in (0.986, 1.03):
        term = ((1 - q) * t) ** 2 / ((q * t) ** 2 + 0.01)
        assert term.max() <= findings.max_bias_term((q, q)) + 1e-15
        assert term.max() > 0.999 * findings.max_bias_term((q, q))
    assert findings.max_bias_term((0.986, 1.03)) == max(findings.max_bias_term((0.986, 0.986)),
                                                        findings.max_bias_term((1.03, 1.03)))
    assert findings.max_bias_term((1.0, 1.0)) == 0.0


def test_noise_bound_text():
    """The scaling bullet's phase differences are read against the photon
    pass's, identical code in both methods: within it they are not told from
    noise; control: a phase beyond it is named, with its difference."""
    ph = {"trace": -0.6, "build": 0.3, "precompute": 11.5, "eye": -0.33}
    assert findings.noise_bound_text(ph) == "so the other phases' differences of at most 0.33 s are not told from noise"
    ph["eye"] = -2.0
    assert findings.noise_bound_text(ph) == "and the eye pass by -2 s, more than that"


def test_beyond_unquoted_cases_said_once():
    """Cases whose speed-ups sit at a target too few resamples reach are
    named in one bullet, not one bullet each; control: a single such case
    is said in the singular."""
    rec = {"cases": [{"case": "a-8x6", "status": "undefined"}, {"case": "b-8x6", "status": "undefined"}],
           "quoted": 0, "met": 0, "thin": 0, "decided": 0, "no_best": 0}
    lines = findings.md_beyond(rec)[1]
    assert len(lines) == 1 and lines[0].startswith("- a-8x6 and b-8x6: their speed-ups are taken at a target")
    rec["cases"] = rec["cases"][:1]
    assert findings.md_beyond(rec)[1][0].startswith("- a-8x6: its speed-ups")


def test_beyond_without_a_best_variant():
    """Cases without a best variant count in finding B's denominators (the
    goal holds in 1 of 3, not 1 of 1), each says what its variants do
    against the paper's rule, with the paper rule's time over theirs; a
    variant with another's images is said once; control: with every case's
    variants slower, README's headline says that no variant beats the rule."""
    def row(case, variant, vs, ratio, best=False, group=None, lo=0.9):
        return {"case": case, "variant": variant, "estimate": "paper", "target": 0.02, "speedup": 1.1, "lo": lo,
                "hi": 1.3, "defined_fraction": 1.0, "fallback_rate": 0.0, "evaluated_share": 0.5, "seeds": 5,
                "best": best, "above_one": lo > 1.0, "vs_paper": vs, "goal_met": best and lo > 1.0,
                "image_group": group or variant, "vs_paper_ratio": ratio, "vs_paper_ratio_lo": ratio - 0.05,
                "vs_paper_ratio_hi": ratio + 0.05}
    rows = [row("a-64x48", "paper", "", float("nan")), row("a-64x48", "lazy", "higher", 1.14, True, lo=1.05),
            row("b-64x48", "paper", "", float("nan")), row("b-64x48", "gated0.1", "lower", 0.8),
            row("b-64x48", "gated0.2", "lower", 0.8, group="gated0.1"),
            row("c-64x48", "paper", "", float("nan")), row("c-64x48", "lazy", "undetermined", 0.97),
            row("c-64x48", "gated0.1", "lower", 0.7)]
    with tempfile.TemporaryDirectory() as d:
        path = os.path.join(d, "beyond.csv")
        pd.DataFrame(rows).to_csv(path, index=False)
        text = "\n".join(md("beyond", {"beyond": path})[1])
        assert "holds in 1 of 3 cases (2 without a best variant)" in text, text
        assert "- b-64x48: no best variant" in text and "slower: gated0.1 (and 1 with the same images) 0.800" in text
        assert "gated0.2" not in text
        assert "not ranked: lazy 0.970 [0.920, 1.020]" in text
        bullet = readme("beyond", {"beyond": path})
        assert "a variant beats the paper's rule in 1 of 3 cases" in bullet
        assert "in 1 every variant is slower (the paper rule's time over theirs 0.800 to 0.800; each group" in bullet
        # overlapping equal-error intervals are not ranked: the paired ratio ranks the two (control: disjoint ones)
        assert "overlaps it: the paired time ratio above, not these, ranks the two" in bullet
        rows[0].update(lo=0.5, hi=0.9)
        pd.DataFrame(rows).to_csv(path, index=False)
        assert "is disjoint from it" in readme("beyond", {"beyond": path})
        pd.DataFrame(rows).to_csv(path, index=False)
        assert "in 1 (c-64x48) none is faster and some are not ranked" in bullet
        pd.DataFrame([r for r in rows if r["case"] == "b-64x48"]).to_csv(path, index=False)
        assert "no variant beats the paper's rule" in readme("beyond", {"beyond": path})


def test_bias_rest_text():
    """The corrected intervals not shown equivalent are told apart: reaching
    past the margin (undetermined) or wholly outside it; control: all
    equivalent says nothing."""
    e = lambda mean, half, eq: {"mean": mean, "half": half, "equivalent": eq}  # noqa: E731
    rec = {"margin": 0.01, "equivalence": [e(1.0, 0.005, True), e(1.002, 0.03, False), e(0.995, 0.02, False)]}
    assert findings.bias_rest_text(rec) == "; the other 2 are undetermined (their intervals reach past the margin)"
    rec["equivalence"].append(e(1.05, 0.01, False))
    assert findings.bias_rest_text(rec) == ("; of the other 3, 2 are undetermined (their intervals reach past the "
                                            "margin) and 1 lies wholly outside it")
    rec["equivalence"] = [e(1.0, 0.005, True)]
    assert findings.bias_rest_text(rec) == ""


def test_trend_text_names_the_loosest_target():
    """The curve's largest speed-up is not called its end: where the loosest
    counted target is neither extreme, its value is given beside them;
    control: when the largest is at the loosest target, nothing is added."""
    a = {"speedup": 0.9, "lo": 0.7, "hi": 1.1, "target": 0.008}
    b = {"speedup": 1.6, "lo": 1.3, "hi": 1.9, "target": 0.012}
    z = {"speedup": 1.5, "lo": 1.4, "hi": 1.8, "target": 0.017}
    r = {"span": (a, b), "span_rank": "lower", "loosest": z}
    text = findings.trend_text(r)
    assert "from its smallest, 0.9 [0.7, 1.1]x at 0.008, to its largest, 1.6 [1.3, 1.9]x at 0.012" in text, text
    assert "(at the loosest such target, 0.017, 1.5 [1.4, 1.8]x)" in text
    r["loosest"] = b
    assert "loosest" not in findings.trend_text(r)


def test_rerun_text():
    """Table 1's counts in its rerun are given where they differ from the
    first run's, and said to be unstable; control: equal counts say so in
    a few words, and no rerun says nothing."""
    rec = {"rerun": {"cells": 12, "ours_faster": 11, "inside": 4, "inside_other": 2}, "ours_faster": 12,
           "inside": {50000: (3, 4), 100000: (0, 4)}, "inside_other": (0, 12)}
    text = findings.rerun_text(rec)
    assert "11 of 12 intervals lie below 100% and 4 hold the paper's value" in text, text
    assert "not stable between runs" in text
    rec["rerun"] = {"cells": 12, "ours_faster": 12, "inside": 3, "inside_other": 0}
    assert findings.rerun_text(rec) == "; its rerun (`make reproducibility`, run b) gives the same counts"
    rec["rerun"] = None
    assert findings.rerun_text(rec) == ""


def test_brief_table_equal_error_and_gather_wording():
    """The opening's sentences say only what their tests say: Table 1's fall
    over n is claimed when the two ends' intervals are ranked (control: they
    overlap, no change is claimed; the paper's own course is said apart);
    the equal-error sentence gives the smallest and largest speed-up over
    the targets enough resamples reach, not "faster at the tightest"; final
    gathering's span is of point estimates, with the grids whose intervals
    lie above 1 counted."""
    def table(rank, paper_last):
        first = {"photons": 50000, "nn": 10, "ratio": 68.0, "paper": 70.4}
        last = {"photons": 50000, "nn": 100, "ratio": 28.5, "paper": paper_last}
        return {"photons": [50000], "over_n": {50000: {"first": first, "last": last, "rank": rank}}, "reversed": []}
    text = findings.brief_table(table("lower", 29.3))
    assert "time falls from 68.0% to 28.5% of the conventional one's, as in the paper (70.4% and 29.3%)." in text
    text = findings.brief_table(table("overlap", 29.3))
    assert "time goes from 68.0% to 28.5%" in text and "no change is claimed" in text and "as in the paper" not in text
    text = findings.brief_table(table("lower", 80.0))
    assert "where the paper's does not fall (70.4% and 80.0%)" in text
    span = ({"speedup": 2.24, "target": 0.0102}, {"speedup": 3.28, "target": 0.0124})
    rec = {"estimates": [{"estimate": findings.PRIMARY_ESTIMATE, "span": span, "span_rank": "lower", "tightest": {}}]}
    text = findings.brief_equal_error(rec)
    assert "speed-up at equal error runs from 2.24x" in text and "to 3.28x (0.0124): it depends on the target" in text
    assert "tightest" not in text and "faster" not in text
    g = {"grids": [{}, {}, {}], "every": [{}], "speedup": (0.8, 3.2)}
    text = findings.brief_gather(g)
    assert "(point estimates); its interval lies above 1 at every counted target in 1 of 3 grids." in text
    assert "faster" not in text


def test_renderers_sentence_names_each_studys_renderer():
    """The sentence FINDINGS.md and README's summary open with: one renderer
    when every study's last attempt ended ok on it; two named with their
    studies when a regeneration on a newer one is under way (a study's files
    are its last ok attempt's: a later killed one changes nothing), and a
    target with no finished attempt named as such; none without a log."""
    from experiments import regenerate
    with tempfile.TemporaryDirectory() as d:
        assert findings.renderers(d, "log.md") == ""
        row = {"started": "t0", "ended": "t1", "commit": "c", "status": "ok", "renders": "1", "seconds": "1", "why": ""}
        rows = [dict(row, target=t, renderer="aaaaaaa11111") for t in ("reproduce-table", "figures", "gather")]
        regenerate.write_log(d, rows)
        assert findings.renderers(d, "log.md") == "Every study's files come from renderer `aaaaaaa` ([regeneration-log.md](log.md))."
        rows += [dict(row, target="reproduce-table", renderer="bbbbbbb22222"),
                 dict(row, target="gather", renderer="bbbbbbb22222", status="running", ended=""),
                 dict(row, target="caustic", renderer="bbbbbbb22222", status="exit 1")]
        regenerate.write_log(d, rows)
        line = findings.renderers(d, "log.md")
        assert "from 2 renderers" in line and "`bbbbbbb` made `reproduce-table`" in line
        assert "`aaaaaaa` made `figures`, `gather`;" in line and line.count("`gather`") == 1
        assert "no attempt of `caustic` has ended ok" in line
