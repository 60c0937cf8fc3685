"""freeplay.Env and VecEnv: determinism, equality with a run of the same policy, rewards, bad actions."""

import random

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


def expected_row(obs, info, items):
    """What VecEnv's batched row should hold for a typed Observation and an Env info (the fields compared)."""
    pose = numpy.full((len(items), 3), numpy.nan)
    flags = numpy.zeros((len(items), 3), dtype=bool)
    for item in obs.items:
        k = items.index(item.name)
        pose[k] = (item.pose.x, item.pose.y, item.pose.theta)
        flags[k] = (item.touched_by_child, item.held_by_robot, item.visible)
    touches = numpy.full((6, 2), numpy.nan)
    for touch in obs.touches:
        touches[touch.finger - 1] = touch.position
    coded = [[freeplay.env.LABEL_NAMES[axis].index(labels[axis]) if labels[axis] else -1
              for axis in freeplay.env.CODED_LABELS] for seat, labels in sorted(info["coded"].items())]
    current = items.index(obs.self.current_item) if obs.self.current_item else -1
    return {"t": obs.t, "pose": pose, "flags": flags, "touches": touches, "coded": coded, "current": current,
            "reach": obs.self.arm_reach_centre, "interaction_events": tuple(obs.interaction_events),
            "zones": [(z.colour, z.centroid.tolist()) for z in obs.zones]}


def assert_row(observations, infos, k, expected):
    assert observations["t"][k] == expected["t"]
    numpy.testing.assert_array_equal(observations["item_pose"][k], expected["pose"])
    flags = numpy.stack([observations[key][k] for key in
                         ("item_touched_by_child", "item_held_by_robot", "item_visible")], axis=1)
    numpy.testing.assert_array_equal(flags, expected["flags"])
    numpy.testing.assert_array_equal(observations["touch_position"][k], expected["touches"])
    numpy.testing.assert_array_equal(observations["touch_active"][k], ~numpy.isnan(expected["touches"][:, 0]))
    numpy.testing.assert_array_equal(observations["self_arm_reach_centre"][k], expected["reach"])
    assert observations["self_current_item"][k] == expected["current"]
    assert observations["interaction_events"][k] == expected["interaction_events"]
    assert [(z.colour, z.centroid.tolist()) for z in observations["zones"][k]] == expected["zones"]
    if expected["coded"]:
        assert infos["coded"][k].tolist() == expected["coded"]


def without(record, keys):
    """`record` without `keys`."""
    return {key: value for key, value in record.items() if key not in keys}


def single_rollout(scenario, seed, episode, reward, steps_limit=None):
    """Env rollout of one episode with Mover: per step (row expectation, reward, terminated, truncated, events),
    and the final info."""
    env = freeplay.Env(scenario, SHORT, reward=reward)
    obs, info = env.reset(seed=seed, options={"episode": episode})
    policy = Mover()
    policy.reset(info["context"], info["rng"])
    items = list(info["context"].item_names)
    steps = [(expected_row(obs, info, items), None, False, False, info["events"])]
    while True:
        obs, value, terminated, truncated, info = env.step(policy.decide(obs))
        steps.append((expected_row(obs, info, items), value, terminated, truncated, info["events"]))
        if terminated or truncated:
            return steps, info


def test_vec_env_rows_equal_single_envs_with_the_same_seeds(scenario):
    """Environment k of a VecEnv reset with seed s plays what Env plays for episode k of seed s: the same
    observations (batched row by row), rewards, ends, events and record; then it restarts with episode n + …"""
    reward = freeplay.rewards.coded_joint_play
    expected = [single_rollout(scenario, 4, k, reward) for k in range(2)]
    vec = freeplay.VecEnv(2, scenario, SHORT, reward=reward)
    assert vec.native_reward == "coded_joint_play"
    items = list(vec.item_names)
    observations, infos = vec.reset(seed=4)
    policies = []
    for k in range(2):
        policy = Mover()
        policy.reset(infos["context"][k], infos["rng"][k])
        policies.append(policy)
        assert_row(observations, infos, k, expected[k][0][0][0])
        assert infos["episode"][k] == k and infos["seed"][k] == freeplay.episode_seed(4, k)
    done = [False, False]
    step = 0
    while not all(done):
        step += 1
        actions = [policies[k].decide(vec.observation(k)) if not done[k] else [] for k in range(2)]
        observations, rewards, terminated, truncated, infos = vec.step(actions)
        assert rewards.dtype == numpy.float64 and terminated.dtype == bool
        for k in range(2):
            if done[k]:
                continue
            row, value, term, trunc, events = expected[k][0][step]
            assert (rewards[k], terminated[k], truncated[k]) == (value, term, trunc)
            if term or trunc:  # the row holds the next episode's start; final_* the end
                done[k] = True
                assert infos["_final_info"][k] and infos["_final_observation"][k]
                wall = {"wall_s"}  # the record's wall-clock time differs from run to run
                assert (without(infos["final_info"][k]["record"], wall) == without(expected[k][1]["record"], wall))
                assert infos["final_info"][k]["events"] == events
                final = infos["final_observation"][k]
                assert final["t"] == row["t"]
                numpy.testing.assert_array_equal(final["item_pose"], row["pose"])
                assert infos["episode"][k] == 2 + sum(done) - 1  # restarted with the next episode index
                assert infos["_context"][k] and infos["rng"][k] is not None
                assert_row(observations, infos, k, expected_row(vec.observation(k), {"coded": {}}, items))
            else:
                assert_row(observations, infos, k, row)
                assert (infos["events"][k] or []) == events and infos["_events"][k] == bool(events)


def test_batched_layout(scenario):
    vec = freeplay.VecEnv(3, scenario, SHORT, perceives_children=True)
    observations, infos = vec.reset(seed=2)
    for _ in range(20):
        observations, rewards, terminated, truncated, infos = vec.step([[], [], []])
    layout = vec.single_observation_layout
    assert set(observations) == set(layout)
    for key, (shape, dtype, _) in layout.items():
        if shape is None:
            assert isinstance(observations[key], tuple) and len(observations[key]) == 3
        else:
            assert observations[key].shape == (3, *shape) and observations[key].dtype == numpy.dtype(dtype), key
    assert vec.item_names == tuple(freeplay.Env(scenario, SHORT).reset(seed=2)[1]["context"].item_names)
    assert vec.child_seats == ("purple",) and observations["child_perceived"].any()
    assert infos["coded"].shape == (3, 1, 3) and infos["coded"].dtype == numpy.int8
    assert rewards.shape == terminated.shape == truncated.shape == (3,)
    assert infos["t"] is observations["t"] and numpy.all(observations["t"] > 0)
    for k in range(3):  # the perceived child as the typed observation has it
        (child,) = vec.observation(k).children
        assert observations["child_seconds_since_touch"][k, 0] == child.seconds_since_touch
        assert observations["child_gaze"][k, 0] == int(child.gaze)


def test_vec_env_calls_a_python_reward_per_environment(scenario):
    """A Python callable is called once per environment and step with that environment's Step, and gives what the
    built-in reward computed in C++ gives."""
    calls = []

    def joint(step):
        calls.append(step.observation.t)
        social = [labels.get("social_engagement") for labels in step.coded.values()]
        return step.dt if any(label in freeplay.rewards.JOINT_PLAY for label in social) else 0.0

    python = freeplay.VecEnv(2, scenario, SHORT, reward=joint)
    native = freeplay.VecEnv(2, scenario, SHORT, reward=freeplay.rewards.coded_joint_play)
    assert python.native_reward is None
    python.reset(seed=8)
    native.reset(seed=8)
    total, steps = 0.0, 0
    while steps < 100 or (total == 0.0 and steps < 2400):
        a = python.step([[], []])
        b = native.step([[], []])
        numpy.testing.assert_array_equal(a[1], b[1])
        total += b[1].sum()
        steps += 1
    assert len(calls) == 2 * steps
    assert total > 0.0  # the children were coded as playing together at times: the formula was exercised


def test_builtin_rewards_over_a_step():
    step = freeplay.env.Step(observation=None, coded={"purple": {"social_engagement": "cooperative"}})
    assert freeplay.rewards.coded_joint_play(step) == pytest.approx(0.1)
    assert freeplay.rewards.session_length(step) == pytest.approx(0.1)
    assert freeplay.rewards.zero(step) == 0.0
    step.coded = {"purple": {"social_engagement": "parallel"}}
    assert freeplay.rewards.coded_joint_play(step) == 0.0
    assert freeplay.rewards.JOINT_PLAY == ("associative", "cooperative")


def test_vec_env_bad_actions_raise(scenario):
    vec = freeplay.VecEnv(2, scenario, SHORT)
    with pytest.raises(RuntimeError):
        vec.step([[], []])
    vec.reset(seed=1)
    with pytest.raises(freeplay.InputError):
        vec.step([[]])
    with pytest.raises(freeplay.InputError):
        vec.step([[], ["dance"]])
    vec.step([[], []])  # still usable


def test_vec_env_reset_without_seed_plays_the_next_episodes(scenario):
    vec = freeplay.VecEnv(2, scenario, SHORT)
    vec.reset(seed=4)
    _, infos = vec.reset()
    assert infos["episode"].tolist() == [2, 3]
    assert infos["seed"].tolist() == [freeplay.episode_seed(4, 2), freeplay.episode_seed(4, 3)]
    vec.close()


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
    hidden = vec.step([[]])[4]["privileged"]
    assert set(hidden) == HIDDEN and hidden["motivation"].shape == (1, 1)
    assert 0.0 <= hidden["motivation"][0, 0] <= 1.0 and hidden["labels"].shape == (1, 1, 3)
    assert "privileged" not in freeplay.VecEnv(1, scenario, SHORT).reset(seed=3)[1]


def play_async(vec, seed, episodes_per_env, pick):
    """Plays `vec` asynchronously with one Mover per environment until each environment has finished
    `episodes_per_env` episodes; `pick(held, in_flight)` picks which of the received environments are sent back
    now (the others wait for later rounds; at least one when none is in flight). Returns per environment the list
    of its episodes, each {"episode": index, "info": final info (None while running), "steps": per step (row
    fields, reward, terminated, truncated, events)}."""
    items = list(vec.item_names)
    vec.async_reset(seed=seed)
    policies = [None] * vec.num_envs
    played = [[] for _ in range(vec.num_envs)]
    held = []  # environments received and not yet sent: (env id, its actions)
    while True:
        observations, rewards, terminated, truncated, infos = vec.recv()
        assert len(infos["env_id"]) == vec.batch_size == rewards.shape[0] == observations["t"].shape[0]
        for row, k in enumerate(infos["env_id"]):
            k = int(k)
            if infos.get("_final_info") is not None and infos["_final_info"][row]:
                final = infos["final_info"][row]
                played[k][-1]["steps"].append((expected_row_of(infos["final_observation"][row], items), rewards[row],
                                               terminated[row], truncated[row], final["events"]))
                played[k][-1]["info"] = final
            elif played[k]:
                played[k][-1]["steps"].append((expected_row_of(observations, items, row), rewards[row],
                                               terminated[row], truncated[row], infos["events"][row] or []))
            if infos.get("_context") is not None and infos["_context"][row]:  # a new episode starts in this row
                assert rewards[row] == 0.0 or played[k]
                policy = Mover()
                policy.reset(infos["context"][row], infos["rng"][row])
                policies[k] = policy
                played[k].append({"episode": int(infos["episode"][row]), "info": None,
                                  "steps": [(expected_row_of(observations, items, row), None, False, False,
                                             infos["events"][row] or [])]})
            held.append((k, policies[k].decide(vec.observation(k))))
        if all(len(p) > episodes_per_env for p in played):
            return played
        sending = pick(held, vec.num_envs - len(held))
        held = [entry for entry in held if entry not in sending]
        vec.send([actions for _, actions in sending], [k for k, _ in sending])


def expected_row_of(observations, items, row=None):
    """The fields of a batched row that `expected_row` gives for a typed observation (to compare the two)."""
    get = (lambda key: observations[key]) if row is None else (lambda key: observations[key][row])
    flags = numpy.stack([get(key) for key in ("item_touched_by_child", "item_held_by_robot", "item_visible")], axis=1)
    return {"t": float(get("t")), "pose": numpy.array(get("item_pose")), "flags": flags,
            "touches": numpy.array(get("touch_position")), "current": int(get("self_current_item")),
            "reach": numpy.array(get("self_arm_reach_centre")), "interaction_events": tuple(get("interaction_events")),
            "zones": [(z.colour, z.centroid.tolist()) for z in get("zones")]}


def same_row(batched, typed):
    """True when a batched row's fields equal those `expected_row` gave for Env's typed observation."""
    return (batched["t"] == typed["t"] and numpy.array_equal(batched["pose"], typed["pose"], equal_nan=True)
            and numpy.array_equal(batched["flags"], typed["flags"])
            and numpy.array_equal(batched["touches"], typed["touches"], equal_nan=True)
            and batched["current"] == typed["current"] and numpy.array_equal(batched["reach"], typed["reach"])
            and batched["interaction_events"] == typed["interaction_events"] and batched["zones"] == typed["zones"])


@pytest.mark.parametrize("shuffle", [None, 1, 2])
def test_async_env_k_plays_env_episodes_whatever_order_they_come_back(scenario, shuffle):
    """With send/recv (batch_size 1) environment k plays Env's episodes k, k + n, … of the seed: the same
    observations row by row, rewards, ends, events and records, whichever order the environments are received and
    sent back in (all at once, or a random part of those received each round while the others wait)."""
    reward = freeplay.rewards.coded_joint_play
    n = 2 if shuffle is None else 3
    vec = freeplay.VecEnv(n, scenario, SHORT, reward=reward, batch_size=1)
    rng = random.Random(shuffle)

    def pick(held, in_flight):
        return held if shuffle is None else rng.sample(held, rng.randint(0 if in_flight else 1, len(held)))

    played = play_async(vec, 6, 1, pick)
    for k in range(n):
        for m, episode in enumerate(played[k][:2]):
            assert episode["episode"] == k + m * n
            if m == 1:
                continue  # the second episode is still running: its start is compared below
            expected, final = single_rollout(scenario, 6, k + m * n, reward)
            assert len(episode["steps"]) == len(expected)
            for step, ((got, value, term, trunc, events), (row, want, want_term, want_trunc, want_events)) in \
                    enumerate(zip(episode["steps"], expected)):
                assert same_row(got, row), (k, step)
                assert (term, trunc, events) == (want_term, want_trunc, want_events), (k, step)
                if want is not None:
                    assert value == want, (k, step)
            wall = {"wall_s"}
            assert without(episode["info"]["record"], wall) == without(final["record"], wall)
        obs, info = freeplay.Env(scenario, SHORT).reset(seed=6, options={"episode": k + n})
        assert same_row(played[k][1]["steps"][0][0], expected_row(obs, info, list(vec.item_names)))
    vec.close()


def test_async_batches_and_python_rewards(scenario):
    """recv returns batch_size rows with their env ids; a Python reward is called for stepped rows only and equals
    the built-in one; the first recv after async_reset holds every environment's first decision."""
    def joint(step):
        social = [labels.get("social_engagement") for labels in step.coded.values()]
        return step.dt if any(label in freeplay.rewards.JOINT_PLAY for label in social) else 0.0

    python = freeplay.VecEnv(3, scenario, SHORT, reward=joint, batch_size=3)
    native = freeplay.VecEnv(3, scenario, SHORT, reward=freeplay.rewards.coded_joint_play, batch_size=3)
    python.async_reset(seed=8)
    native.async_reset(seed=8)
    a, b = python.recv(), native.recv()
    assert sorted(a[4]["env_id"].tolist()) == [0, 1, 2] and a[4]["_context"].all()
    assert a[1].tolist() == [0.0, 0.0, 0.0]
    for _ in range(300):
        for vec, got in ((python, a), (native, b)):
            vec.send([[] for _ in got[4]["env_id"]], got[4]["env_id"])
        a, b = python.recv(), native.recv()
        order_a, order_b = numpy.argsort(a[4]["env_id"]), numpy.argsort(b[4]["env_id"])
        numpy.testing.assert_array_equal(a[1][order_a], b[1][order_b])
        numpy.testing.assert_array_equal(a[0]["t"][order_a], b[0]["t"][order_b])
    small = freeplay.VecEnv(3, scenario, SHORT, batch_size=2)
    small.async_reset(seed=1)
    observations, rewards, terminated, truncated, infos = small.recv()
    assert infos["env_id"].shape == rewards.shape == terminated.shape == (2,)
    assert observations["item_pose"].shape[0] == 2 and len(observations["zones"]) == 2
    assert infos["episode"].tolist() == infos["env_id"].tolist()


def test_async_bad_input_raises(scenario):
    vec = freeplay.VecEnv(2, scenario, SHORT, batch_size=1)
    with pytest.raises(ValueError, match="batch_size"):
        freeplay.VecEnv(2, scenario, SHORT, batch_size=3)
    with pytest.raises(RuntimeError, match="async_reset"):
        vec.recv()
    with pytest.raises(RuntimeError, match="async_reset"):
        vec.send([[]], [0])
    vec.async_reset(seed=1)
    with pytest.raises(ValueError, match="not been received"):
        vec.send([[]], [0])  # reset, not yet received
    with pytest.raises(ValueError, match="recv"):
        vec.step([[], []])  # the synchronous step needs every environment received
    k = int(vec.recv()[4]["env_id"][0])
    with pytest.raises(IndexError, match="no environment 5"):
        vec.send([[]], [5])
    with pytest.raises(IndexError, match="no environment -1"):
        vec.send([[]], [-1])
    with pytest.raises(freeplay.InputError):
        vec.send([[], []], [k])  # two action lists for one id
    with pytest.raises(ValueError, match="twice"):
        vec.send([[], []], [k, k])
    with pytest.raises(freeplay.InputError):
        vec.send([["dance"]], [k])
    vec.send([[]], [k])
    with pytest.raises(ValueError, match="not been received since its last send"):
        vec.send([[]], [k])
    vec.recv()
    vec.recv()
    with pytest.raises(ValueError, match="send"):
        vec.recv()  # nothing sent
    vec.reset(seed=1)  # back to synchronous stepping
    vec.step([[], []])
    vec.close()


def test_arrays_handed_out_are_never_overwritten(scenario):
    """VecEnv reuses the arrays of batches that Python dropped; anything still held (a dict, one array, a view of
    a row, the rewards) keeps its values while later steps and recvs run."""
    vec = freeplay.VecEnv(2, scenario, SHORT, batch_size=1)
    vec.reset(seed=3)
    kept = []
    for step in range(40):
        observations, rewards, terminated, truncated, infos = vec.step([[], []])
        if step % 7 == 0:
            kept.append(({key: value.copy() for key, value in observations.items() if isinstance(value, numpy.ndarray)},
                         observations, rewards.copy(), rewards, observations["item_pose"][1],
                         observations["item_pose"][1].copy()))
        elif step % 7 == 3:
            single = (observations["t"], observations["t"].copy())
    vec.async_reset(seed=3)
    ids = vec.recv()[4]["env_id"]
    for step in range(40):
        vec.send([[]], ids)
        observations, rewards, _, _, infos = vec.recv()
        ids = infos["env_id"]
        if step % 9 == 0:
            kept.append(({key: value.copy() for key, value in observations.items() if isinstance(value, numpy.ndarray)},
                         observations, rewards.copy(), rewards, observations["item_pose"][0],
                         observations["item_pose"][0].copy()))
    for copies, held, reward_copy, reward, view, view_copy in kept:
        for key, value in copies.items():
            numpy.testing.assert_array_equal(held[key], value)
        numpy.testing.assert_array_equal(reward, reward_copy)
        numpy.testing.assert_array_equal(view, view_copy)
    numpy.testing.assert_array_equal(single[0], single[1])
    vec.close()
    hidden = freeplay.VecEnv(2, scenario, SHORT, privileged=True)
    hidden.reset(seed=3)
    kept = []
    for step in range(60):
        infos = hidden.step([[], []])[4]
        if step % 10 == 0:  # only the privileged dict is kept, not the infos around it
            kept.append((infos["privileged"], {key: value.copy() for key, value in infos["privileged"].items()}))
    assert any(numpy.isfinite(copies["motivation"]).any() for _, copies in kept)
    for held, copies in kept:
        for key, value in copies.items():
            numpy.testing.assert_array_equal(held[key], value)
