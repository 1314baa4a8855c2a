"""Shared setup of the tests of the Python module `tem`.

ctest (python/CMakeLists.txt) sets PYTHONPATH to the module's build directory, TEM_BINARY to
the `tem` program and TEM_SOURCE_DIR to the repository. Run by hand, from the repository root:

    PYTHONPATH=build/release/python /usr/bin/python3 -m pytest -q python/tests

and without PYTHONPATH the release build's module is taken.
"""
import os
import pathlib
import subprocess
import sys

import pytest

SOURCE_DIR = pathlib.Path(
    os.environ.get("TEM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
TEM_BINARY = pathlib.Path(os.environ.get("TEM_BINARY", SOURCE_DIR / "build/release/tem"))

try:
    import tem  # noqa: F401
except ImportError:
    sys.path.insert(0, str(SOURCE_DIR / "build/release/python"))


def scene_path(relative):
    """A scene file of the repository, e.g. scene_path("tests/scenes/small_pile.json")."""
    return SOURCE_DIR / relative


def run_tem(*args):
    """Runs `tem ARGS...` on one thread; returns the CompletedProcess (text)."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    return subprocess.run([str(TEM_BINARY), *map(str, args)], capture_output=True, text=True,
                          env=env, check=False)


@pytest.fixture(scope="session", autouse=True)
def one_thread():
    """One OpenMP thread, as `tem run` uses by default (results do not depend on it)."""
    import tem
    tem.set_threads(1)
