"""Result files are replaced in one step: an interrupted write leaves the old file whole."""
import pytest

from model import csvfile
from model.files import write_atomic, write_text_atomic
from model.runs.sweeps import SweepResult, read_csv


def test_a_failed_write_leaves_the_old_file_and_no_temporary(tmp_path):
    path = tmp_path / "table.csv"
    path.write_text("old\n")

    def half_then_fail(tmp):
        tmp.write_text("new, half")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_atomic(path, half_then_fail)
    assert path.read_text() == "old\n"
    assert [p.name for p in tmp_path.iterdir()] == ["table.csv"]


def test_text_is_replaced_whole(tmp_path):
    path = tmp_path / "report.md"
    write_text_atomic(path, "first")
    write_text_atomic(path, "second ü")
    assert path.read_text(encoding="utf-8") == "second ü"


def test_a_sweep_table_interrupted_mid_write_keeps_the_previous_table(tmp_path, monkeypatch):
    path = tmp_path / "sweep.csv"
    old = SweepResult("orientation", {"theta0": [0.0, 1.0], "FTx_over_mu0FN": [0.5, 0.6]}, {}, 0.1)
    old.to_csv(path)
    before = path.read_bytes()
    real_write = csvfile.write

    def interrupted(out, columns, header):
        real_write(out, columns, header)
        raise KeyboardInterrupt  # Ctrl-C after the rows reached the temporary file

    monkeypatch.setattr(csvfile, "write", interrupted)
    new = SweepResult("orientation", {"theta0": [0.0], "FTx_over_mu0FN": [0.9]}, {}, 0.1)
    with pytest.raises(KeyboardInterrupt):
        new.to_csv(path)
    assert path.read_bytes() == before
    assert list(read_csv(path).columns["FTx_over_mu0FN"]) == [0.5, 0.6]
    assert [p.name for p in tmp_path.iterdir()] == ["sweep.csv"]
