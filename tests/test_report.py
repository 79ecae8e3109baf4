"""Unit tests of experiments/analysis/report.py's reading of a results CSV:
the exit status says whose fault it is (a file a step before did not make:
1; a file that is there but malformed, or lacks a column: 2), and the
message names the file.

Run by pytest from the repository root (tests/pytest.test.sh, part of
`make test` and `make check`: `python3 -m pytest tests/`).
"""

import pytest

from experiments.analysis import report


def exit_of(capsys, *args, **kw):
    """(exit status, stderr) of report.read_csv(*ARGS, **KW)."""
    with pytest.raises(SystemExit) as e:
        report.read_csv(*args, **kw)
    return e.value.code, capsys.readouterr().err


def test_read_csv_exit_statuses(tmp_path, capsys):
    good = tmp_path / "good.csv"
    good.write_text("a,b\n1,2\n")
    frame = report.read_csv(str(good), ["a", "b"], "t")  # control: a good file reads
    assert list(frame.columns) == ["a", "b"] and int(frame["b"].iloc[0]) == 2
    code, err = exit_of(capsys, str(tmp_path / "none.csv"), ["a"], "t", hint="make x")
    assert code == report.EXIT_FAILURE == 1 and "none.csv: missing (make x)" in err
    code, err = exit_of(capsys, str(good), ["a", "c"], "t")
    assert code == report.EXIT_BAD_INPUT == 2 and "good.csv: no column(s) c" in err
    bad = tmp_path / "bad.csv"
    bad.write_text('a,b\n"1,2\n')
    code, err = exit_of(capsys, str(bad), ["a"], "t")
    assert code == 2 and "bad.csv: not a CSV" in err
    empty = tmp_path / "empty.csv"
    empty.write_text("")
    code, err = exit_of(capsys, str(empty), ["a"], "t")
    assert code == 2 and "empty.csv: not a CSV" in err
