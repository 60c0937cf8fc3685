"""A Gymnasium-style environment over the real episode loop: one step per 10 Hz decision of the robot's policy.

The episode runs on a C++ worker thread; its policy hands each decision to :meth:`Env.step` and waits for the
actions, so a rollout is exactly a run of the same policy (same seed → same event log). Gymnasium is optional:
the spaces are described in plain Python; when ``gymnasium`` imports they are ``gymnasium.spaces`` objects and the
environment is registered as ``freeplay/Sandtray-v0``.
"""

import os
from dataclasses import dataclass, field

import numpy

from . import _freeplay, rewards
from .experiments import load, overrides_list

#: Decisions per simulated second.
DECISION_HZ = 10
#: The labels a coder gives each child (PInSoRo names), in the order of ``Step.coded[seat]``.
CODED_LABELS = ("task_engagement", "social_engagement", "social_attitude")
#: Per axis of CODED_LABELS, its labels in the coding scheme's order: VecEnv's ``infos["coded"]`` holds indices.
LABEL_NAMES = dict(zip(CODED_LABELS, _freeplay.LABELS))


def observation_space():
    """The observation (a :class:`freeplay.Observation`) described in plain Python: field → description."""
    return {
        "t": "float: simulated seconds since free play started",
        "items": "list of ItemObservation: name, pose (x, y, theta), position (2,) array, touched_by_child, "
                 "held_by_robot, visible",
        "zones": "list of ZoneObservation: colour, polygon (n, 2) array, centroid (2,) array",
        "touches": "list of TouchObservation: finger (1-6), position (2,) array",
        "interaction_events": "list of str: sandtray/interaction_events since the last decision",
        "children": "list of PerceivedChild (empty unless perceives_children): seat, face_detected, gaze, "
                    "gaze_on_screen, speaking, addressing_robot, seconds_since_touch, moving_item",
        "self": "RobotSelf: moving_item, current_item, speaking, arm_reach_centre (2,), arm_reach_radius, "
                "arm_reach_known",
    }


def action_space():
    """The action (a list of these, possibly empty, or one of them, or None) described in plain Python."""
    return {
        "MoveItem": "MoveItem(item: str, target: (x, y) metres in sandtray)",
        "LookAt": "LookAt(point=(x, y, z)) or LookAt(child='purple'|'yellow')",
        "PointAt": "PointAt(point=(x, y))",
        "Say": "Say(text, addressee='purple'|'yellow'|'')",
        "Wait": "Wait(seconds)",
        "CancelMove": "CancelMove()",
    }


def _gymnasium():
    """The gymnasium module when it imports, else None (Debian 12 has none; the module never requires it)."""
    try:
        import gymnasium
    except ImportError:
        return None
    return gymnasium


def gymnasium_spaces(gymnasium):
    """(observation space, action space) as ``gymnasium.spaces`` objects describing the same layout as
    :func:`observation_space` and :func:`action_space`. Observations stay :class:`freeplay.Observation` objects and
    actions freeplay action objects: the spaces give a learner the structure, shapes and bounds (points are Box(2,)
    in metres, flags Discrete(2), names Text); they are not what ``reset``/``step`` return."""
    spaces = gymnasium.spaces
    inf = float("inf")
    point = spaces.Box(-inf, inf, shape=(2,), dtype=numpy.float64)
    scalar = spaces.Box(0.0, inf, shape=(), dtype=numpy.float64)
    flag = spaces.Discrete(2)
    name = spaces.Text(max_length=64, charset=_NAME_CHARSET)
    observation = spaces.Dict({
        "t": scalar,
        "items": spaces.Sequence(spaces.Dict({
            "name": name, "position": point, "theta": spaces.Box(-numpy.pi, numpy.pi, shape=(), dtype=numpy.float64),
            "touched_by_child": flag, "held_by_robot": flag, "visible": flag})),
        "zones": spaces.Sequence(spaces.Dict({"colour": name, "polygon": spaces.Sequence(point), "centroid": point})),
        "touches": spaces.Sequence(spaces.Dict({"finger": spaces.Discrete(6, start=1), "position": point})),
        "interaction_events": spaces.Sequence(name),
        "children": spaces.Sequence(spaces.Dict({
            "seat": name, "face_detected": flag, "gaze": spaces.Discrete(len(_freeplay.PerceivedGaze.__members__)),
            "gaze_on_screen": flag, "speaking": flag, "addressing_robot": flag, "seconds_since_touch": scalar,
            "moving_item": flag})),
        "self": spaces.Dict({
            "moving_item": flag, "current_item": name, "speaking": flag, "arm_reach_centre": point,
            "arm_reach_radius": scalar, "arm_reach_known": flag}),
    })
    action = spaces.Sequence(spaces.Dict({
        "kind": spaces.Discrete(len(ACTION_KINDS)),  # index into ACTION_KINDS
        "item": name,                                 # MoveItem
        "point": spaces.Box(-inf, inf, shape=(3,), dtype=numpy.float64),  # MoveItem/PointAt (x, y), LookAt (x, y, z)
        "text": spaces.Text(max_length=256, charset=_NAME_CHARSET + " ,.!?'"),  # Say
        "addressee": name,                            # Say, LookAt(child=…)
        "seconds": scalar,                            # Wait
    }))
    return observation, action


#: The action kinds in the order of the gymnasium action space's ``kind``.
ACTION_KINDS = ("MoveItem", "LookAt", "PointAt", "Say", "Wait", "CancelMove")
_NAME_CHARSET = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-/:."


@dataclass
class Step:
    """What a reward function sees of one step: observable events and coded labels; hidden child state only when
    the Env was asked for it (``privileged=True``)."""

    observation: object                           #: the next observation (freeplay.Observation)
    events: list = field(default_factory=list)    #: event-log entries (dicts t, source, type, data) of the step
    coded: dict = field(default_factory=dict)     #: seat → {task_engagement, social_engagement, social_attitude}
    results: list = field(default_factory=list)   #: ActionResults of moves and utterances that ended
    dt: float = 1.0 / DECISION_HZ                 #: simulated seconds of free play in the step
    finished: bool = False                        #: the episode ended in this step
    record: dict = None                           #: the episode's record once finished (duration_s, …)
    #: None unless the Env was made with ``privileged=True``: then seat → the child model's hidden state (``labels``
    #: the child intends, ``motivation``, ``boredom``, ``answer_expectation``, ``wants_to_stop``)
    privileged: dict = None


class Env:
    """One child-robot scenario as an environment: ``reset(seed) -> (obs, info)``, ``step(actions) -> (obs, reward,
    terminated, truncated, info)`` at the 10 Hz decision rate.

    ``reward`` is a callable over a :class:`Step` (see :mod:`freeplay.rewards`; default: zero).
    ``perceives_children`` fills ``observation.children`` (as a perceiving C++ policy would). ``privileged=True``
    adds the children's hidden state (what no camera, coder or policy sees) to ``info["privileged"]`` and
    ``Step.privileged``; by default neither the reward nor the observation sees it. ``reset(seed=s)``
    plays episode 0 of root seed ``s`` (as ``freeplay run --seed s``); further resets play episodes 1, 2, …;
    ``options={"episode": i}`` picks one.
    """

    metadata = {"render_modes": [], "decision_hz": DECISION_HZ}

    def __init__(self, scenario, overrides=(), reward=None, perceives_children=False, privileged=False,
                 **set_values):
        self.scenario_file = os.fspath(scenario)
        self.overrides = overrides_list(overrides, **set_values)
        self.scenario = load(self.scenario_file, self.overrides)["variants"][0]
        self.reward = reward or rewards.zero
        self.perceives_children = perceives_children
        self.privileged = bool(privileged)
        #: plain-Python descriptions of the observation and the actions (always present)
        self.observation_layout, self.action_layout = observation_space(), action_space()
        gymnasium = _gymnasium()
        if gymnasium is None:
            self.observation_space, self.action_space = self.observation_layout, self.action_layout
        else:
            self.observation_space, self.action_space = gymnasium_spaces(gymnasium)
        self._episode = _freeplay._EnvEpisode(self.scenario_file, self.overrides, perceives_children,
                                              self.privileged)
        self._seed = self.scenario["seed"]
        self._next_index = 0
        self.episode_index = None
        self.episode_seed = None

    def reset(self, seed=None, options=None):
        """Starts an episode; returns its first observation and info (events so far, coded labels, seed, and the
        ``context`` and ``rng`` a policy of a run gets in ``reset``: pass them on and a Python policy's rollout equals
        its run)."""
        options = options or {}
        if seed is not None:
            self._seed = int(seed)
            self._next_index = 0
        self.episode_index = int(options.get("episode", self._next_index))
        self._next_index = self.episode_index + 1
        self.episode_seed = _freeplay.episode_seed(self._seed, self.episode_index)
        self._episode.start(self.episode_seed)
        obs, _, _, _, info = self._outcome(reward=False)
        info["context"] = self._episode.context
        info["rng"] = self._episode.policy_rng  # the stream a policy of a run of this episode gets
        return obs, info

    def step(self, action):
        """Hands the actions of this decision (a list, one action or None) to the episode and runs it to the next
        decision; returns (observation, reward, terminated, truncated, info). ``terminated``: the children stopped;
        ``truncated``: free play hit its cap; ``info["record"]``: the episode's record once it ended."""
        self._episode.act(action)
        return self._outcome(reward=True)

    def events(self):
        """The finished episode's event log as JSON Lines text (what ``events/<id>.jsonl`` of a run holds)."""
        return self._episode.events_jsonl()

    def close(self):
        """Stops the running episode."""
        self._episode = None

    def _step(self):
        """The current decision as a reward sees it (a :class:`Step`), and the info dict of ``reset``/``step``."""
        e = self._episode
        raw = e.info()
        finished = e.finished
        coded = {seat: dict(zip(CODED_LABELS, labels)) for seat, labels in raw["coded"].items()}
        record = e.record() if finished else None
        privileged = raw.get("privileged")
        step = Step(e.observation, raw["events"], coded, raw["results"], finished=finished, record=record,
                    privileged=privileged)
        info = {"t": raw["t"], "events": raw["events"], "coded": coded, "results": raw["results"],
                "episode": self.episode_index, "seed": self.episode_seed}
        if privileged is not None:
            info["privileged"] = privileged
        if record is not None:
            info["record"] = record
        return step, info

    def _outcome(self, reward):
        step, info = self._step()
        value = float(self.reward(step)) if reward else 0.0
        hit_cap = step.finished and self._episode.hit_cap
        return step.observation, value, step.finished and not hit_cap, hit_cap, info


def batched_observation_layout(items, seats, perceives_children=False):
    """One environment's row of :class:`VecEnv`'s batched observation, described in plain Python: key → (shape of
    the row, dtype, description). ``items`` and ``seats`` name the item and child-seat axes."""
    i, s = len(items), len(seats)
    layout = {
        "t": ((), "float64", "simulated seconds since free play started"),
        "item_pose": ((i, 3), "float64", "x, y (m, sandtray), theta (rad) of each item (item_names order; NaN if "
                                         "the observation lacks it)"),
        "item_touched_by_child": ((i,), "bool", "a child's finger drags the item"),
        "item_held_by_robot": ((i,), "bool", "the robot's finger drags the item"),
        "item_visible": ((i,), "bool", "the item is shown on screen"),
        "touch_active": ((6,), "bool", "finger k+1 touches the screen"),
        "touch_position": ((6, 2), "float64", "where finger k+1 touches (NaN when it does not)"),
    }
    if perceives_children:
        layout.update({
            "child_perceived": ((s,), "bool", "the perception reports the child of this seat (child_seats order)"),
            "child_face_detected": ((s,), "bool", "face found"),
            "child_gaze": ((s,), "int8", "PerceivedGaze value (0 Unknown, 1 Robot, 2 Partner, 3 Screen, 4 Away)"),
            "child_gaze_on_screen": ((s, 2), "float64", "estimated gaze point on the screen (NaN when none)"),
            "child_speaking": ((s,), "bool", "voice activity"),
            "child_addressing_robot": ((s,), "bool", "speech seems addressed to the robot"),
            "child_seconds_since_touch": ((s,), "float64", "seconds since the child's last touch began (NaN when "
                                                           "not perceived)"),
            "child_moving_item": ((s,), "int16", "index of the item the child drags, -1 for none"),
        })
    layout.update({
        "self_moving_item": ((), "bool", "a move_sandbox_items goal is running"),
        "self_current_item": ((), "int16", "index of the item being moved, -1 for none"),
        "self_speaking": ((), "bool", "a Say is running"),
        "self_arm_reach_centre": ((2,), "float64", "RShoulder projected on the table"),
        "self_arm_reach_radius": ((), "float64", "radius of the reachable disc at table level"),
        "self_arm_reach_known": ((), "bool", "the arm_reach frame is published"),
        "zones": (None, "object", "tuple of ZoneObservation (colour, polygon, centroid)"),
        "interaction_events": (None, "object", "tuple of str: sandtray/interaction_events since the last decision"),
    })
    return layout


def batched_gymnasium_space(gymnasium, layout):
    """A ``gymnasium.spaces.Dict`` of one row of the batched observation ``layout`` (Box for numbers, MultiBinary
    for flags, Sequence for zones and interaction events)."""
    spaces = gymnasium.spaces
    inf = float("inf")
    entries = {}
    for key, (shape, dtype, _) in layout.items():
        if dtype == "bool":
            entries[key] = spaces.MultiBinary(list(shape)) if shape else spaces.Discrete(2)
        elif dtype == "float64":
            entries[key] = spaces.Box(-inf, inf, shape=shape, dtype=numpy.float64)
        elif dtype in ("int8", "int16"):
            entries[key] = spaces.Box(-1, numpy.iinfo(dtype).max, shape=shape, dtype=numpy.dtype(dtype))
        else:
            entries[key] = spaces.Sequence(spaces.Text(max_length=256, charset=_NAME_CHARSET))
    return spaces.Dict(entries)


class VecEnv:
    """``n`` copies of an :class:`Env` stepped together: each episode runs on its own C++ thread, and one call hands
    every environment its actions, waits for all of them with the GIL released and returns their decisions in a
    batched layout (dicts of NumPy arrays with a leading environment dimension, as gymnasium's vector environments
    do; :func:`batched_observation_layout`). Finished episodes restart at once with the next episode index
    (``infos["final_observation"]`` and ``infos["final_info"]`` keep the end).

    A built-in reward of :mod:`freeplay.rewards` is computed in C++ inside the step (``native_reward`` names it);
    any other callable is called once per environment and step with that environment's :class:`Step`, in Python.

    Asynchronous stepping (as envpool's): :meth:`async_reset`, then :meth:`send` actions to some environments and
    :meth:`recv` the next ``batch_size`` environments that are ready, whichever they are (``infos["env_id"]`` says
    which); no environment waits for a slower one. Environment k then plays episodes k, k + n, k + 2n, … of the root
    seed, whatever order the environments come back in.
    """

    metadata = Env.metadata

    def __init__(self, n, scenario, overrides=(), reward=None, perceives_children=False, privileged=False,
                 batch_size=None, **set_values):
        if int(n) < 1:
            raise ValueError(f"a VecEnv needs at least one environment, not {n}")
        #: how many environments :meth:`recv` returns (1 … n; default n)
        self.batch_size = int(n) if batch_size is None else int(batch_size)
        if not 1 <= self.batch_size <= int(n):
            raise ValueError(f"batch_size must be 1 to {n}, not {batch_size}")
        self.envs = [Env(scenario, overrides, reward, perceives_children, privileged, **set_values)
                     for _ in range(int(n))]
        self.num_envs = len(self.envs)
        self.reward = self.envs[0].reward
        #: the built-in reward computed in C++ inside the step, or None when the reward is a Python callable
        self.native_reward = getattr(self.reward, "native", None)
        items, seats = _freeplay._vec_layout()
        #: the item axis of the batched arrays (PolicyContext.item_names) and the child-seat axis
        self.item_names, self.child_seats = tuple(items), tuple(seats)
        #: one row of the batched observation in plain Python (key → (shape, dtype, description))
        self.single_observation_layout = batched_observation_layout(items, seats, perceives_children)
        gymnasium = _gymnasium()
        #: the spaces of one environment (as gymnasium's vector environments name them)
        self.single_observation_space = (self.single_observation_layout if gymnasium is None
                                         else batched_gymnasium_space(gymnasium, self.single_observation_layout))
        self.single_action_space = self.envs[0].action_space
        self._stepper = _freeplay._VecStepper([env._episode for env in self.envs], items, seats,
                                              perceives_children, self.envs[0].privileged, self.native_reward,
                                              1.0 / DECISION_HZ)
        self._next_index = 0
        self._started = False
        self._async_next = None  # per environment, the episode index of its next automatic reset (async stepping)

    def reset(self, seed=None, options=None):
        """Starts episodes 0…n-1 of root seed ``seed`` (without a seed: the next n episodes); returns the batched
        (observations, infos); ``infos["context"]`` and ``infos["rng"]`` hold each environment's PolicyContext and
        policy Rng (object arrays)."""
        contexts, rngs = self._reset_all(seed)
        self._stepper.begin(False)
        observations, infos = self._stepper.gather()
        infos["context"], infos["rng"] = contexts, rngs
        return observations, infos

    def async_reset(self, seed=None, options=None):
        """Starts episodes 0…n-1 of root seed ``seed`` (without a seed: the next n episodes) as :meth:`reset` does,
        but returns nothing: :meth:`recv` then returns their first decisions (reward 0, ``infos["context"]`` and
        ``infos["rng"]``). Each environment's next episodes are its index plus multiples of n."""
        base = 0 if seed is not None else self._next_index
        self._reset_all(seed)
        self._stepper.begin(True)
        self._async_next = [base + k + self.num_envs for k in range(self.num_envs)]

    def send(self, actions, env_ids):
        """Hands environment ``env_ids[j]`` the action list ``actions[j]`` and returns at once; each must have been
        received by :meth:`recv` since its last send (or since :meth:`async_reset`)."""
        if self._async_next is None:
            raise RuntimeError("VecEnv.send() before async_reset()")
        if isinstance(env_ids, numpy.ndarray):
            env_ids = env_ids.tolist()  # recv's infos["env_id"], as Python ints
        elif isinstance(env_ids, (int, numpy.integer)):
            env_ids = [int(env_ids)]
        self._stepper.send(actions, env_ids)

    def recv(self):
        """Waits until ``batch_size`` environments that were sent actions (or reset by :meth:`async_reset`) are
        ready and returns them, batched as :meth:`step` does but with rows for those environments only:
        (observations, rewards, terminated, truncated, infos); ``infos["env_id"]`` lists their environment
        indices. An environment whose episode ended restarts at once, as in :meth:`step`."""
        if self._async_next is None:
            raise RuntimeError("VecEnv.recv() before async_reset()")
        observations, rewards_, terminated, truncated, infos, finished, reset = self._stepper.recv(self.batch_size)
        env_ids = infos["env_id"]
        if self.native_reward is None:
            fresh = set(reset)
            for row, k in enumerate(env_ids):
                if row not in fresh:
                    rewards_[row] = float(self.reward(self.envs[k]._step()[0]))
        if finished or reset:
            self._restart(finished, env_ids, observations, infos, self._next_async_episode, reset)
        return observations, rewards_, terminated, truncated, infos

    def step(self, actions):
        """Steps every environment with its actions (one action list per environment); returns the batched
        observations, NumPy arrays of rewards, terminated and truncated, and the batched infos."""
        if not self._started:
            raise RuntimeError("VecEnv.step() before reset()")
        observations, rewards_, terminated, truncated, infos, finished = self._stepper.step(actions)
        if self.native_reward is None:
            for k, env in enumerate(self.envs):
                rewards_[k] = float(self.reward(env._step()[0]))
        if finished:
            self._restart(finished, range(self.num_envs), observations, infos, self._next_sync_episode)
        return observations, rewards_, terminated, truncated, infos

    def observation(self, k):
        """Environment k's current observation as a typed :class:`freeplay.Observation` (what Env returns)."""
        return self.envs[k]._episode.observation

    def close(self):
        """Stops the running episodes."""
        for env in self.envs:
            env.close()
        self._stepper = None

    def _reset_all(self, seed):
        """Starts episodes base…base+n-1 of root seed ``seed`` (base 0 with a seed, else the next index); returns
        the environments' PolicyContexts and policy Rngs (object arrays)."""
        base = 0 if seed is not None else self._next_index
        contexts = numpy.full(self.num_envs, None, dtype=object)
        rngs = numpy.full(self.num_envs, None, dtype=object)
        for k, env in enumerate(self.envs):
            _, info = env.reset(seed=seed, options={"episode": base + k})
            contexts[k], rngs[k] = info["context"], info["rng"]
            self._stepper.set_episode(k, env.episode_index, env.episode_seed)
        self._next_index = base + self.num_envs
        self._started = True
        self._async_next = None
        return contexts, rngs

    def _next_sync_episode(self, k):
        """The episode index of environment k's automatic reset in :meth:`step`: the next of the VecEnv."""
        self._next_index += 1
        return self._next_index - 1

    def _next_async_episode(self, k):
        """The episode index of environment k's automatic reset in :meth:`recv`: its own next (k + multiples of n),
        so that no order of the environments changes what each plays."""
        self._async_next[k] += self.num_envs
        return self._async_next[k] - self.num_envs

    def _restart(self, finished, env_ids, observations, infos, next_episode, reset=()):
        """Automatic reset of the environments (``env_ids[row]`` for each ``row`` of ``finished``) whose episode
        ended (gymnasium's ``final_*`` entries, with masks); ``next_episode(k)`` gives environment k's next episode
        index. Rows in ``reset`` (just reset by async_reset) also get their context and rng."""
        n = len(env_ids)
        final_observation = numpy.full(n, None, dtype=object)
        final_info = numpy.full(n, None, dtype=object)
        contexts = numpy.full(n, None, dtype=object)
        rngs = numpy.full(n, None, dtype=object)
        mask = numpy.zeros(n, dtype=bool)
        started = numpy.zeros(n, dtype=bool)
        for row in reset:
            episode = self.envs[env_ids[row]]._episode
            contexts[row], rngs[row] = episode.context, episode.policy_rng
            started[row] = True
        for row in finished:
            k = int(env_ids[row])
            env = self.envs[k]
            final_observation[row] = {key: value[row].copy() if isinstance(value, numpy.ndarray) else value[row]
                                      for key, value in observations.items()}
            final_info[row] = env._step()[1]
            mask[row] = started[row] = True
            _, info = env.reset(options={"episode": next_episode(k)})
            contexts[row], rngs[row] = info["context"], info["rng"]
            self._stepper.set_episode(k, env.episode_index, env.episode_seed)
            self._stepper.write_row(row, k, observations, infos)
        if finished:
            infos.update({"final_observation": final_observation, "_final_observation": mask,
                          "final_info": final_info, "_final_info": mask.copy()})
        infos.update({"context": contexts, "_context": started, "rng": rngs, "_rng": started.copy()})


def _register_with_gymnasium():
    """Registers ``freeplay/Sandtray-v0`` (``gymnasium.make("freeplay/Sandtray-v0", scenario=FILE, …)``) when
    gymnasium imports. Its environment checker is off: observations are typed freeplay objects, not the dicts that
    the checker would test against the space."""
    gymnasium = _gymnasium()
    if gymnasium is not None and "freeplay/Sandtray-v0" not in gymnasium.registry:
        gymnasium.register(id="freeplay/Sandtray-v0", entry_point="freeplay.env:Env", disable_env_checker=True)


_register_with_gymnasium()
