"""Shared fixtures of the Python module's tests (run by ctest through tests/python/CMakeLists.txt,
which sets PYTHONPATH to the build tree's python folder, STOCHNAV_CLI to the built CLI and
STOCHNAV_SHARED_DATA_DIR to the reference data)."""

import os
import pathlib
import subprocess

import pytest

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def shared_data_dir():
    """../shared/data beside the repository, or STOCHNAV_SHARED_DATA_DIR."""
    return pathlib.Path(os.environ.get("STOCHNAV_SHARED_DATA_DIR",
                                       REPOSITORY.parent / "shared" / "data"))


def require_shared_file(relative):
    """The path of a reference file under the shared data folder; skips the test without it."""
    path = shared_data_dir() / relative
    if not path.exists():
        pytest.skip(f"shared reference data missing: {path} (set STOCHNAV_SHARED_DATA_DIR)")
    return path


@pytest.fixture
def cli():
    """Runs the built `stochnav` tool: cli(args...) -> CompletedProcess (text)."""
    binary = os.environ.get("STOCHNAV_CLI")
    if not binary or not os.path.exists(binary):
        pytest.skip("STOCHNAV_CLI does not name the built stochnav tool (ctest sets it)")

    def run(*arguments, cwd=None):
        return subprocess.run([binary, *map(str, arguments)], capture_output=True, text=True,
                              cwd=cwd)
    return run
