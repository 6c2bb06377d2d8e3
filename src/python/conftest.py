"""Fixtures of the Python module's tests: the weir binary to compare with, small scenes."""

import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def weir_binary():
    """The weir command built beside the module: WEIR_BINARY, else <build>/weir of the module."""
    given = os.environ.get("WEIR_BINARY")
    if given:
        return pathlib.Path(given)
    import weir

    # <build>/python/weir/_weir*.so -> <build>/weir
    module = pathlib.Path(weir._weir.__file__).resolve()
    return module.parents[2] / "weir"


@pytest.fixture(scope="session")
def cli():
    """Runs the weir binary; returns the CompletedProcess (text, stdout and stderr)."""
    binary = weir_binary()
    if not binary.exists():
        pytest.fail(f"the weir binary is not at {binary}; set WEIR_BINARY")

    def run(*args, cwd=None, check=True):
        done = subprocess.run([str(binary), *map(str, args)], cwd=cwd, capture_output=True,
                              text=True, timeout=600)
        if check and done.returncode != 0:
            raise AssertionError(f"weir {' '.join(map(str, args))} exited {done.returncode}:\n"
                                 f"{done.stderr}")
        return done

    return run


@pytest.fixture
def repo():
    return REPO


@pytest.fixture
def dam_break_small():
    """The built-in dam break at about 2000 particles: a few hundred steps a second on 2 cores."""
    import weir

    return weir.Simulation("dam_break", backend="cpu", particles=2000)

