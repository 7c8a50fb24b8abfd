"""The one CSV reader (issue 21, analysis.csvtable) and the trials files read with it (issue 22):
every fault names the file, the 1-based line and the column, for measurements and trials alike."""

from __future__ import annotations

import os

import numpy as np
import pytest

from analysis.csvtable import CsvError, read_header, read_table
from analysis.errors import ValidationError
from analysis.identify import MeasurementError, load_measurement
from analysis.profiles import ControllerSection, bundled_profiles, load_profile
from analysis.sampled import TrialsError, load_trials
from analysis.study import TrialsRequest, profile_trials, resolve_trials, trials_path
from trials_files import BAD_TRIALS, GOOD, BadFile


@pytest.mark.parametrize("case", BAD_TRIALS, ids=[c.name for c in BAD_TRIALS])
def test_each_bad_trials_file_names_file_line_and_column(tmp_path, case: BadFile):
    path = tmp_path / f"{case.name}.csv"
    case.write(path)
    with pytest.raises(TrialsError) as exc:
        load_trials(path)
    err = exc.value
    assert isinstance(err, ValidationError) and isinstance(err, CsvError)  # every caller of either shows it
    assert err.file == str(path) and str(path) in str(err)
    assert (err.line, err.column) == (case.line, case.column)
    assert case.words in err.reason
    if case.line is not None:
        assert f"line {case.line}" in str(err)
    if case.column is not None:
        assert f"column {case.column!r}" in str(err)


def test_good_trials_any_order_other_and_unnamed_columns_comments_and_bom(tmp_path):
    path = tmp_path / "t.csv"
    text = "# bench, 2026\n\n,note,Stable , K,b\n0,first,1,5000,1\n\n1,\"a, b\",0,8e3,10\n# end\n"
    path.write_bytes(b"\xef\xbb\xbf" + text.encode())  # a UTF-8 BOM, as a spreadsheet writes it
    t = load_trials(path)
    assert list(t.lines) == [4, 6]
    np.testing.assert_array_equal(t.b, [1.0, 10.0])
    np.testing.assert_array_equal(t.k, [5000.0, 8000.0])
    np.testing.assert_array_equal(t.stable, [True, False])


def test_measurements_get_the_same_file_faults_as_trials(tmp_path):
    """The faults of the file itself are the reader's: one wording for both kinds of file."""
    for case in BAD_TRIALS:
        if case.column is not None or case.name.startswith(("header-only", "ragged")):
            continue  # column faults depend on the kind of file; checked below and in test_identify_measurement
        path = tmp_path / f"m-{case.name}.csv"
        case.write(path)
        with pytest.raises(TrialsError) as trial:
            load_trials(path)
        with pytest.raises(MeasurementError) as meas:
            load_measurement(path)
        assert (meas.value.file, meas.value.line) == (trial.value.file, trial.value.line), case.name
        assert trial.value.reason.startswith(meas.value.reason), case.name  # trials add the columns they need


def test_measurement_cells_and_ragged_rows(tmp_path):
    rows = "\n".join(f"{f},{0.1 * f},-0.01" for f in range(1, 10))
    path = tmp_path / "frf.csv"
    path.write_text("# FRF\nfrequency_hz,real,imag\n" + rows.replace("3,0.30000000000000004", "3,1e400") + "\n")
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    assert (exc.value.line, exc.value.column) == (5, "real") and "not finite" in exc.value.reason
    path.write_text("frequency_hz,real,imag\n" + rows.replace("2,0.2,-0.01", "2,0.2") + "\n")
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    assert (exc.value.line, exc.value.column) == (3, None) and "2 values" in exc.value.reason
    path.write_text("frequency_hz,real\n" + "\n".join(f"{f},1" for f in range(1, 10)) + "\n")
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    assert exc.value.column == "imag" and exc.value.line == 1


def test_the_header_line_is_the_header_not_the_line_before_the_data(tmp_path):
    """A comment between the header and the data: the header's own line is reported."""
    path = tmp_path / "frf.csv"
    path.write_text("frequency_hz,real\n# comment\n" + "\n".join(f"{f},1" for f in range(1, 10)) + "\n")
    with pytest.raises(MeasurementError) as exc:
        load_measurement(path)
    assert (exc.value.line, exc.value.column) == (1, "imag")


def test_reader_options(tmp_path):
    path = tmp_path / "x.csv"
    path.write_text("a,B,c\n1,2,x\n")
    with pytest.raises(CsvError) as exc:
        read_table(path, ("a", "b"))
    assert (exc.value.line, exc.value.column) == (1, "c") and "unknown column" in exc.value.reason
    t = read_table(path, ("a", "b"), other_columns=True)
    assert list(t.columns) == ["a", "b"] and t.header_line == 1 and len(t) == 1
    np.testing.assert_array_equal(t.columns["b"], [2.0])
    with pytest.raises(CsvError) as exc:
        read_table(path, ("a", "b", "c"))
    assert (exc.value.line, exc.value.column) == (2, "c") and exc.value.reason == "'x' is not a number"
    t = read_table(path, ("a", "c"), other_columns=True, choices={"c": {"x": 7.0}})
    np.testing.assert_array_equal(t.columns["c"], [7.0])
    path.write_text("a\n1_000\n")
    with pytest.raises(CsvError, match="not a number"):
        read_table(path, ("a",))
    path.write_text('\n# c\n"a\nb",c\n1,2\n')  # a quoted header cell over two lines: the row starts on line 3
    assert read_header(path) == (3, ["a\nb", "c"])


def test_relative_trials_path_resolves_against_the_profile_folder(tmp_path, monkeypatch):
    folder = tmp_path / "bench"
    folder.mkdir()
    (folder / "trials.csv").write_text(GOOD)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    p = load_profile(bundled_profiles()["hbfd"])
    p = p.replace(controller=ControllerSection(trials="trials.csv"))
    with pytest.raises(TrialsError, match="no such file"):
        profile_trials(p)  # without the folder: the working directory, where there is no trials.csv
    assert len(profile_trials(p, base=folder)) == 2
    assert TrialsRequest.of(p, folder).path == os.path.join(str(folder), "trials.csv")
    assert TrialsRequest.of(p, folder).mtime_ns == os.stat(folder / "trials.csv").st_mtime_ns
    r = resolve_trials(p, folder)
    assert r.controller.trials == str(folder / "trials.csv") and len(profile_trials(r)) == 2
    absolute = p.replace(controller=ControllerSection(trials=str(folder / "trials.csv")))
    assert resolve_trials(absolute, elsewhere) is absolute and trials_path(None, folder) is None
