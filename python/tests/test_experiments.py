"""Experiments from Python: loading, validation errors, runs equal to the command line's, DataFrames."""

import json

import pytest

import freeplay
from conftest import BUILD_DIR, SCENARIO, SHORT, cli


def test_load_returns_the_validated_variants(scenario):
    loaded = freeplay.load(scenario, SHORT + ["episodes=3"])
    assert loaded["name"] == "child-robot-asocial"
    assert not loaded["is_suite"]
    (variant,) = loaded["variants"]
    assert variant["episodes"] == 3
    assert variant["policy"] == "asocial"
    assert variant["scenario"]["protocol"]["freeplay_cap_s"] == 120


def test_unknown_key_raises_input_error_with_key_and_allowed(scenario):
    with pytest.raises(freeplay.InputError) as caught:
        freeplay.load(scenario, ["robot.polcy=idle"])
    error = caught.value
    assert isinstance(error, ValueError)
    assert "polcy" in str(error)
    assert "robot" in error.key


def test_bad_value_in_a_file_names_file_line_and_allowed(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: bad\ncondition: child-robot\nrobot:\n  policy: telepathic\n")
    with pytest.raises(freeplay.InputError) as caught:
        freeplay.validate(bad)
    error = caught.value
    assert error.file == str(bad)
    assert error.line == 4
    assert error.key == "robot.policy"
    assert "asocial" in error.allowed and "python:*" in error.allowed


def test_run_equals_the_command_line(scenario, tmp_path):
    args = dict(episodes=2, seed=11, jobs=2, overrides=SHORT, events="all")
    py_run = freeplay.run(scenario, out=tmp_path / "py", **args)
    sets = [a for o in SHORT for a in ("--set", o)]
    done = cli("run", scenario, "--episodes", 2, "--seed", 11, "-j", 2, "--events", "all", "-q", "--out",
               tmp_path / "cli", *sets, cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    cli_run = freeplay.Run(tmp_path / "cli")
    strip = ("program_version", "libraries", "wall_s")  # the build's version and the wall clock

    def comparable(records):
        return [{k: v for k, v in r.items() if k not in strip and not k.startswith("wall")} for r in records]

    assert len(py_run.records) == 2
    assert comparable(py_run.records) == comparable(cli_run.records)
    for r in py_run.records:
        assert py_run.events_text(r["episode_id"]) == cli_run.events_text(r["episode_id"])
    assert [row["mean"] for row in py_run.summary] == [row["mean"] for row in cli_run.summary]


def test_records_and_summary_as_dataframes(scenario, tmp_path):
    pandas = pytest.importorskip("pandas")
    result = freeplay.run(scenario, episodes=2, seed=3, overrides=SHORT, out=tmp_path / "run")
    frame = result.records_frame()
    assert isinstance(frame, pandas.DataFrame)
    assert len(frame) == 2 and "duration_s" in frame.columns
    summary = result.summary_frame()
    assert {"variant", "metric", "mean"} <= set(summary.columns)


def test_python_idle_gives_idle_event_logs(scenario, tmp_path):
    common = dict(episodes=2, seed=5, jobs=2, events="all")
    cpp = freeplay.run(scenario, out=tmp_path / "cpp", overrides=SHORT + ["robot.policy=idle"], **common)
    py = freeplay.run(scenario, out=tmp_path / "py",
                      overrides=SHORT + ["robot.policy=python:policies_for_tests:Idle"], **common)
    for a, b in zip(cpp.records, py.records):
        assert cpp.events_text(a["episode_id"]) == py.events_text(b["episode_id"])
        assert a["duration_s"] == b["duration_s"]


def test_python_policy_runs_are_deterministic_and_independent_of_jobs(scenario, tmp_path):
    overrides = SHORT + ["robot.policy=python:policies_for_tests:Mover"]
    one = freeplay.run(scenario, episodes=3, seed=8, jobs=1, overrides=overrides, out=tmp_path / "a", events="all")
    two = freeplay.run(scenario, episodes=3, seed=8, jobs=3, overrides=overrides, out=tmp_path / "b", events="all")
    for a, b in zip(one.records, two.records):
        assert one.events_text(a["episode_id"]) == two.events_text(b["episode_id"])
    moves = [e for e in one.events(one.records[0]["episode_id"]) if e["type"] == "move_goal"]
    assert moves, "the Mover policy moved nothing"


def test_bad_action_raises_a_clear_error(scenario, tmp_path):
    with pytest.raises(freeplay.InputError) as caught:
        freeplay.run(scenario, episodes=1, overrides=SHORT + ["robot.policy=python:policies_for_tests:BadAction"],
                     out=tmp_path / "run")
    assert "'dance'" in str(caught.value) and "not an action" in str(caught.value)
    assert "MoveItem" in caught.value.allowed


def test_exception_in_decide_keeps_finished_episodes(scenario, tmp_path):
    out = tmp_path / "run"
    with pytest.raises(ZeroDivisionError) as caught:
        freeplay.run(scenario, episodes=6, seed=2, jobs=1, out=out,
                     overrides=SHORT + ["robot.policy=python:policies_for_tests:Raises"])
    assert any("policies_for_tests:Raises" in note for note in getattr(caught.value, "__notes__", []))
    kept = freeplay.Run(out).records
    assert 1 <= len(kept) < 6  # the episodes before the failing one are kept (seed 2: not the first)


def test_unknown_python_module_is_an_input_error(scenario, tmp_path):
    with pytest.raises(freeplay.InputError) as caught:
        freeplay.run(scenario, episodes=1, overrides=SHORT + ["robot.policy=python:no_such_module:Policy"],
                     out=tmp_path / "run")
    assert "no_such_module" in str(caught.value)


def test_the_cpp_program_refuses_python_policies_clearly(scenario, tmp_path):
    done = cli("run", scenario, "--episodes", 1, "-q", "--out", tmp_path / "run", "--set",
               "robot.policy=python:policies_for_tests:Idle", cwd=tmp_path)
    assert done.returncode == 2
    assert "python3 -m freeplay" in done.stderr


def test_python_dash_m_freeplay_runs_python_policies(scenario, tmp_path):
    import os
    import subprocess
    import sys
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([os.path.dirname(__file__), env.get("PYTHONPATH", "")])
    sets = [a for o in SHORT + ["robot.policy=python:policies_for_tests:Idle"] for a in ("--set", o)]
    done = subprocess.run([sys.executable, "-m", "freeplay", "run", str(scenario), "--episodes", "1", "--seed", "5",
                           "-q", "--out", str(tmp_path / "run"), *sets], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    (record,) = freeplay.Run(tmp_path / "run").records
    assert record["policy"] == "python:policies_for_tests:Idle"
    assert json.loads((tmp_path / "run" / "run.json").read_text())["complete"]


def test_compare_uses_the_command_line_comparison(scenario, tmp_path):
    program = BUILD_DIR / "freeplay"
    if not (program.exists() and (BUILD_DIR / "freeplay-full").exists()):
        pytest.skip("the C++ freeplay program (freeplay-full) is not built")
    a = freeplay.run(scenario, episodes=3, seed=4, overrides=SHORT + ["robot.policy=idle"], out=tmp_path / "a")
    b = freeplay.run(scenario, episodes=3, seed=4, overrides=SHORT, out=tmp_path / "b")
    result = freeplay.compare(a.dir, b.dir, program=program)
    assert result == freeplay.compare(a.dir, b.dir, program=program)  # deterministic (fixed bootstrap seed)
    assert "duration_s" in json.dumps(result)


def test_python_dash_m_freeplay_runs_suites_in_shards(tmp_path):
    import subprocess
    import sys
    suite = SCENARIO.parent / "baselines.yaml"
    sets = [a for o in SHORT for a in ("--set", o)]
    done = subprocess.run([sys.executable, "-m", "freeplay", "suite", str(suite), "--episodes", "2", "--shard", "1/2",
                           "-j", "2", "-q", "--out", str(tmp_path / "run"), *sets], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    records = freeplay.Run(tmp_path / "run").records
    assert 0 < len(records) < 6 and {r["variant"] for r in records} <= {"child-child", "child-robot-asocial",
                                                                         "child-robot-social"}
    bad = subprocess.run([sys.executable, "-m", "freeplay", "suite", str(SCENARIO)], capture_output=True, text=True)
    assert bad.returncode == 2 and "not a suite" in bad.stderr


def test_a_python_policy_sees_children_only_when_it_perceives_them(scenario, tmp_path):
    from policies_for_tests import PerceivingRecorder, Recorder
    Recorder.seen.clear()
    PerceivingRecorder.seen.clear()
    for name in ("Recorder", "PerceivingRecorder"):
        freeplay.run(scenario, episodes=1, seed=3, out=tmp_path / name,
                     overrides=SHORT + [f"robot.policy=python:policies_for_tests:{name}"])
    assert Recorder.seen and all(not o.children for o in Recorder.seen)
    assert any(o.children for o in PerceivingRecorder.seen)
    first = Recorder.seen[0]
    assert isinstance(first, freeplay.Observation) and first.items
    assert first.item(first.items[0].name).name == first.items[0].name and first.item("unicorn") is None


def test_a_python_port_of_asocial_gives_asocials_event_logs(scenario, tmp_path):
    common = dict(episodes=3, seed=12, jobs=2, events="all")
    cpp = freeplay.run(scenario, out=tmp_path / "cpp", overrides=SHORT + ["robot.policy=asocial"], **common)
    py = freeplay.run(scenario, out=tmp_path / "py",
                      overrides=SHORT + ["robot.policy=python:policies_for_tests:Asocial"], **common)
    moves = 0
    for a, b in zip(cpp.records, py.records):
        log = cpp.events_text(a["episode_id"])
        assert log == py.events_text(b["episode_id"])
        moves += log.count('"move_goal"')
    assert moves > 0
