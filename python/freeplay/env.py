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

    def _outcome(self, reward):
        e = self._episode
        raw = e.info()
        finished = e.finished
        coded = {seat: dict(zip(CODED_LABELS, labels)) for seat, labels in raw["coded"].items()}
        record = e.record() if finished else None
        obs = e.observation
        privileged = raw.get("privileged")
        step = Step(obs, raw["events"], coded, raw["results"], finished=finished, record=record,
                    privileged=privileged)
        info = {"t": raw["t"], "events": raw["events"], "coded": coded, "results": raw["results"],
                "episode": self.episode_index, "seed": self.episode_seed}
        if privileged is not None:
            info["privileged"] = privileged
        if record is not None:
            info["record"] = record
        value = float(self.reward(step)) if reward else 0.0
        hit_cap = finished and e.hit_cap
        return obs, value, finished and not hit_cap, hit_cap, info


class VecEnv:
    """``n`` copies of an :class:`Env` stepped together: each episode runs on its own C++ thread, so a step of all
    of them runs in parallel. Finished episodes restart at once with the next episode index (``info["final_info"]``
    and ``info["final_observation"]`` keep the end)."""

    def __init__(self, n, scenario, overrides=(), reward=None, perceives_children=False, privileged=False,
                 **set_values):
        self.envs = [Env(scenario, overrides, reward, perceives_children, privileged, **set_values)
                     for _ in range(n)]
        self.num_envs = n
        #: the spaces of one environment (as gymnasium's vector environments name them)
        self.single_observation_space = self.envs[0].observation_space
        self.single_action_space = self.envs[0].action_space
        self._next_index = 0

    def reset(self, seed=None):
        """Starts episodes 0…n-1 of root seed ``seed`` (without a seed: the next n episodes); returns
        (observations, infos)."""
        observations, infos = [], []
        base = 0 if seed is not None else self._next_index
        for k, env in enumerate(self.envs):
            obs, info = env.reset(seed=seed, options={"episode": base + k})
            observations.append(obs)
            infos.append(info)
        self._next_index = base + self.num_envs
        return observations, infos

    def step(self, actions):
        """Steps every environment with its actions; returns lists of observations and infos and NumPy arrays of
        rewards, terminated and truncated."""
        _freeplay._act_all([env._episode for env in self.envs], list(actions))
        observations, rewards_, terminated, truncated, infos = [], [], [], [], []
        for env in self.envs:
            obs, reward, term, trunc, info = env._outcome(reward=True)
            if term or trunc:
                info = {"final_observation": obs, "final_info": info}
                obs, _ = env.reset(options={"episode": self._next_index})
                self._next_index += 1
            observations.append(obs)
            rewards_.append(reward)
            terminated.append(term)
            truncated.append(trunc)
            infos.append(info)
        return observations, numpy.array(rewards_), numpy.array(terminated), numpy.array(truncated), infos


def _register_with_gymnasium():
    """Registers ``freeplay/Sandtray-v0`` (``gymnasium.make("freeplay/Sandtray-v0", scenario=FILE, …)``) when
    gymnasium imports. Its environment checker is off: observations are typed freeplay objects, not the dicts that
    the checker would test against the space."""
    gymnasium = _gymnasium()
    if gymnasium is not None and "freeplay/Sandtray-v0" not in gymnasium.registry:
        gymnasium.register(id="freeplay/Sandtray-v0", entry_point="freeplay.env:Env", disable_env_checker=True)


_register_with_gymnasium()
