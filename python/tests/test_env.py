"""freeplay.Env and VecEnv: determinism, equality with a run of the same policy, rewards, bad actions."""

import numpy
import pytest

import freeplay
from conftest import SHORT
from policies_for_tests import Mover


def rollout(env, policy, seed):
    """Plays one episode of `env` with `policy`'s decisions; returns (rewards, last info, steps)."""
    obs, info = env.reset(seed=seed)
    policy.reset(info["context"], info["rng"])
    rewards, steps = [], 0
    while True:
        obs, reward, terminated, truncated, info = env.step(policy.decide(obs))
        rewards.append(reward)
        steps += 1
        if terminated or truncated:
            return rewards, info, steps


def test_env_rollout_matches_a_run_of_the_same_policy(scenario, tmp_path):
    env = freeplay.Env(scenario, SHORT + ["robot.policy=python:policies_for_tests:Idle"],
                       reward=freeplay.rewards.session_length)
    rewards, info, steps = rollout(env, freeplay.Policy(), seed=5)
    run = freeplay.run(scenario, episodes=1, seed=5, out=tmp_path / "run", events="all",
                       overrides=SHORT + ["robot.policy=idle"])
    (record,) = run.records
    assert env.events() == run.events_text(record["episode_id"])
    assert info["record"]["duration_s"] == record["duration_s"]
    assert sum(rewards) == pytest.approx(steps * 0.1)


def test_env_rollout_of_a_python_policy_matches_its_run(scenario, tmp_path):
    env = freeplay.Env(scenario, SHORT)
    _, info, _ = rollout(env, Mover(), seed=6)
    run = freeplay.run(scenario, episodes=1, seed=6, out=tmp_path / "run", events="all",
                       overrides=SHORT + ["robot.policy=python:policies_for_tests:Mover"])
    (record,) = run.records
    assert env.events() == run.events_text(record["episode_id"])
    assert info["record"]["duration_s"] == record["duration_s"]


def test_env_is_deterministic_and_accepts_actions(scenario):
    env = freeplay.Env(scenario, SHORT)
    first = rollout(env, Mover(), seed=9)
    log = env.events()
    again = rollout(env, Mover(), seed=9)
    assert first[2] == again[2]
    assert env.events() == log
    assert '"move_goal"' in log  # the moves reached the robot


def test_observation_types(scenario):
    env = freeplay.Env(scenario, SHORT, perceives_children=True)
    obs, info = env.reset(seed=1)
    assert isinstance(obs, freeplay.Observation)
    assert obs.items and isinstance(obs.items[0].position, numpy.ndarray) and obs.items[0].position.shape == (2,)
    assert obs.zones == [] or obs.zones[0].polygon.shape[1] == 2
    assert isinstance(obs.self.arm_reach_centre, numpy.ndarray)
    for _ in range(20):
        obs, *_ = env.step([])
    assert obs.children and obs.children[0].seat in ("purple", "yellow")
    assert set(env.observation_layout) >= {"t", "items", "self"}
    assert "MoveItem" in env.action_layout


def test_env_bad_action_raises(scenario):
    env = freeplay.Env(scenario, SHORT)
    env.reset(seed=1)
    with pytest.raises(freeplay.InputError):
        env.step(["dance"])
    with pytest.raises(freeplay.InputError):
        env.step([freeplay.MoveItem("unicorn", (0.1, 0.1))])


def test_coded_labels_reach_the_reward(scenario):
    seen = []

    def reward(step):
        seen.append(step.coded)
        return freeplay.rewards.coded_joint_play(step)

    env = freeplay.Env(scenario, SHORT, reward=reward)
    rollout(env, freeplay.Policy(), seed=3)
    labels = [c for c in seen if c]
    assert labels and set(labels[-1]["purple"]) == {"task_engagement", "social_engagement", "social_attitude"}


def test_vec_env_equals_single_envs(scenario):
    vec = freeplay.VecEnv(2, scenario, SHORT)
    observations, _ = vec.reset(seed=4)
    single = freeplay.Env(scenario, SHORT)
    expected = []
    for k in range(2):
        single.reset(seed=4, options={"episode": k})
        steps = 0
        while True:
            *_, term, trunc, _ = single.step([])
            steps += 1
            if term or trunc:
                break
        expected.append(steps)
    counts, done = [0, 0], [None, None]
    while None in done:
        observations, rewards, terminated, truncated, infos = vec.step([[], []])
        for k in range(2):
            counts[k] += 1
            if done[k] is None and (terminated[k] or truncated[k]):
                done[k] = counts[k]
                assert "final_info" in infos[k]
    assert done == expected


HIDDEN = {"labels", "motivation", "boredom", "answer_expectation", "wants_to_stop"}


def test_hidden_child_state_is_not_offered_by_default(scenario):
    seen = []

    def reward(step):
        seen.append(step)
        return 0.0

    env = freeplay.Env(scenario, SHORT, reward=reward)
    _, info = env.reset(seed=3)
    assert "privileged" not in info
    _, last, _ = rollout(env, freeplay.Policy(), seed=3)
    assert "privileged" not in last
    assert seen and all(step.privileged is None for step in seen)
    for step in seen:  # nor do the events carry the child model's variables
        for event in step.events:
            assert not HIDDEN & set(event.get("data") or {}), event


def test_hidden_child_state_on_explicit_request(scenario):
    seen = []

    def reward(step):
        seen.append(step.privileged)
        return 0.0

    plain = freeplay.Env(scenario, SHORT)
    rollout(plain, freeplay.Policy(), seed=3)
    env = freeplay.Env(scenario, SHORT, reward=reward, privileged=True)
    _, info, _ = rollout(env, freeplay.Policy(), seed=3)
    assert env.events() == plain.events()  # asking for it does not change the episode
    hidden = info["privileged"]["purple"]
    assert set(hidden) == HIDDEN
    assert set(hidden["labels"]) == set(freeplay.env.CODED_LABELS)
    assert 0.0 <= hidden["motivation"] <= 1.0
    motivations = {s["purple"]["motivation"] for s in seen if s}
    assert len(motivations) > 1  # it follows the child through the episode
    assert all(s is not None for s in seen)
    vec = freeplay.VecEnv(1, scenario, SHORT, privileged=True)
    _, infos = vec.reset(seed=3)
    assert "purple" in vec.step([[]])[4][0]["privileged"]
