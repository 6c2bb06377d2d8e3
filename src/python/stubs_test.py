"""The type stubs (weir/_weir.pyi) are the module's: regenerated, they come out the same."""

import pathlib
import subprocess
import sys

import pytest

import weir

STUB = pathlib.Path(__file__).resolve().parent / "weir" / "_weir.pyi"
# The nanobind that wrote the stub (scripts/setup.sh installs it); another may word it otherwise.
STUBGEN_VERSION = "3.1.0"


def test_the_stubs_match_the_module(tmp_path):
    nanobind = pytest.importorskip("nanobind")
    if nanobind.__version__ != STUBGEN_VERSION:
        pytest.skip(f"stubs written by nanobind {STUBGEN_VERSION}, this is {nanobind.__version__}")
    fresh = tmp_path / "_weir.pyi"
    subprocess.run([sys.executable, "-m", "nanobind.stubgen", "-q", "-m", "weir._weir", "-o",
                    str(fresh)], check=True)
    assert fresh.read_text() == STUB.read_text(), (
        "src/python/weir/_weir.pyi is stale: regenerate it with "
        "PYTHONPATH=build/python build/python-env/bin/python -m nanobind.stubgen -m weir._weir "
        "-o src/python/weir/_weir.pyi")


def test_every_public_name_has_a_docstring():
    for name in weir.__all__:
        if name.startswith("__"):
            continue
        item = getattr(weir, name)
        assert item.__doc__ and len(item.__doc__.strip()) > 10, name
        for member, value in vars(item).items() if isinstance(item, type) else []:
            if not member.startswith("_") and callable(value):
                assert value.__doc__, f"{name}.{member}"
