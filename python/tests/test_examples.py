"""The worked examples of examples/python run at a small size."""

import os
import subprocess
import sys

from conftest import SHORT, SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples" / "python"


def run_example(name, *args, cwd):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(EXAMPLES), env.get("PYTHONPATH", "")])
    sets = [a for o in SHORT for a in ("--set", o)]
    return subprocess.run([sys.executable, str(EXAMPLES / name), *args, *sets], cwd=cwd, env=env,
                          capture_output=True, text=True)


def test_follow_the_child_example(tmp_path):
    done = run_example("follow_the_child.py", "--episodes", "2", "--jobs", "2", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "| FollowTheChild | 2 |" in done.stdout


def test_learning_example(tmp_path):
    done = run_example("learn_cem.py", "--iterations", "1", "--population", "2", "--episodes", "1", "--jobs", "2",
                       "--check-sessions", "2", "--out", "checked", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "iteration 0:" in done.stdout
    assert "| yoked-learned | 2 |" in done.stdout and "learned − yoked, paired by child" in done.stdout
    for run in ("learned", "yoked-learned", "asocial"):
        assert (tmp_path / "checked" / run / "episodes.jsonl").exists()
    assert (tmp_path / "checked" / "check.json").exists()
