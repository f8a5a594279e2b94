# Shared helpers of the Python module's tests: the real `hapscene` binary (HAPSCENE_BINARY,
# set by ctest; default build/hapscene), run from the source tree, and the CSV and number
# formats the command line writes, so outputs compare byte for byte.
import csv
import io
import math
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
BINARY = os.environ.get("HAPSCENE_BINARY", str(ROOT / "build" / "hapscene"))


def run_cli(*args, check_code=None):
    """Runs `hapscene ARGS` in the source tree; returns the CompletedProcess."""
    result = subprocess.run([BINARY, *map(str, args)], cwd=ROOT, capture_output=True, text=True, timeout=600)
    if check_code is not None:
        assert result.returncode == check_code, (result.returncode, result.stdout, result.stderr)
    return result


def to_chars(value):
    """A double as std::to_chars writes it (the shortest text that reads back exactly,
    fixed or scientific, whichever is shorter; fixed on a tie), as the CLI's CSVs do."""
    value = float(value)
    if math.isnan(value):
        return "nan"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    fixed = np.format_float_positional(value, unique=True, trim="-")
    scientific = np.format_float_scientific(value, unique=True, trim="-", exp_digits=2)
    return fixed if len(fixed) <= len(scientific) else scientific


def csv_text(columns, names):
    """The CSV the CLI would write for these columns (header, then one line per row)."""
    lines = [",".join(names)]
    arrays = [np.ravel(columns[name]) for name in names]
    for row in zip(*arrays):
        lines.append(",".join(str(int(v)) if isinstance(v, np.integer) else to_chars(v) for v in row))
    return "\n".join(lines) + "\n"


def read_csv(text):
    """header, {column: float64 array} of a CLI CSV (an empty field, where a script faulted: NaN)."""
    rows = list(csv.reader(io.StringIO(text)))
    header = rows[0]
    data = np.array([[float(v) if v else math.nan for v in row] for row in rows[1:]],
                    dtype=np.float64).reshape(-1, len(header))
    return header, {name: data[:, i] for i, name in enumerate(header)}


def assert_bits_equal(actual, expected, what):
    """Equal to the bit (NaN payloads and the sign of zero included)."""
    actual = np.ascontiguousarray(np.ravel(actual), dtype=np.float64)
    expected = np.ascontiguousarray(np.ravel(expected), dtype=np.float64)
    assert actual.shape == expected.shape, (what, actual.shape, expected.shape)
    differ = np.nonzero(actual.view(np.uint64) != expected.view(np.uint64))[0]
    assert differ.size == 0, f"{what}: {differ.size} values differ, first at row {differ[0]}: " \
                             f"{actual[differ[0]]!r} != {expected[differ[0]]!r}"


@pytest.fixture(autouse=True)
def _in_source_tree(monkeypatch):
    # Paths in the tests are relative to the source tree, as the CLI's are.
    monkeypatch.chdir(ROOT)
