import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def cli():
    """Run the roadbrdf program (path from $ROADBRDF_CLI, set by ctest) and return stdout."""
    exe = os.environ.get("ROADBRDF_CLI", str(ROOT / "build" / "roadbrdf"))

    def run(*args, check=True):
        result = subprocess.run([exe, *map(str, args)], capture_output=True, text=True)
        if check and result.returncode != 0:
            raise AssertionError(f"roadbrdf {' '.join(map(str, args))} failed: {result.stderr}")
        return result

    return run


@pytest.fixture
def root():
    return ROOT


@pytest.fixture(scope="module")
def instruments(tmp_path_factory):
    """The synthetic instrument files: the build's (ctest sets ROADBRDF_INSTRUMENT_FILES), or written
    here by the same script."""
    if os.environ.get("ROADBRDF_INSTRUMENT_FILES"):
        return pathlib.Path(os.environ["ROADBRDF_INSTRUMENT_FILES"])
    out = tmp_path_factory.mktemp("instruments")
    script = pathlib.Path(__file__).resolve().parents[1] / "data" / "instruments" / "make_synthetic.py"
    subprocess.run([sys.executable, str(script), str(out)], check=True)
    return out


@pytest.fixture
def real_data():
    """../shared/real-data next to the source tree (real third-party measurements, never copied into
    the repository); the test is skipped with a message when the folder is absent (a user's clone)."""
    folder = ROOT.parent / "shared" / "real-data"
    if not folder.is_dir():
        pytest.skip(f"real third-party data not available ({folder} is absent)")
    return folder


def assert_same_error(cli_result, python_error, cli_field: str, py_field: str) -> None:
    """One library error seen from both front ends: the program exits with status 2 and prints
    ``roadbrdf: error: FLAG: MESSAGE``; Python raises ``FIELD: MESSAGE``, with the same MESSAGE."""
    prefix = f"roadbrdf: error: {cli_field}: "
    assert cli_result.returncode == 2 and cli_result.stderr.startswith(prefix), cli_result.stderr
    assert str(python_error).startswith(py_field + ": "), str(python_error)
    assert cli_result.stderr.strip()[len(prefix):] == str(python_error)[len(py_field) + 2:]
