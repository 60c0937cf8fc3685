"""Shared set-up of the freeplay Python tests: skip cleanly without the module, small fast scenarios."""

import os
import pathlib
import subprocess

import pytest

freeplay = pytest.importorskip("freeplay", reason="the freeplay module is not built (pybind11-dev, python3-dev)")

SOURCE_DIR = pathlib.Path(os.environ.get("FREEPLAY_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD_DIR = pathlib.Path(os.environ.get("FREEPLAY_BUILD_DIR", SOURCE_DIR / "build"))
SCENARIO = SOURCE_DIR / "scenarios" / "child-robot-asocial.yaml"
#: Short sessions: no greeting or debriefing, a 2-minute free-play cap.
SHORT = ["protocol.greeting_s=0", "protocol.tutorial_s=5", "protocol.debriefing_s=0", "protocol.freeplay_cap_s=120"]


@pytest.fixture
def short():
    """Overrides that keep an episode short."""
    return list(SHORT)


@pytest.fixture
def scenario():
    """A child-robot scenario file."""
    return SCENARIO


def cli(*args, cwd):
    """Runs the C++ program's `run`/`suite` front (build/freeplay-run); returns the CompletedProcess."""
    program = BUILD_DIR / "freeplay-run"
    if not program.exists():
        pytest.skip("the C++ freeplay program is not built")
    return subprocess.run([str(program), *map(str, args)], cwd=cwd, capture_output=True, text=True)
