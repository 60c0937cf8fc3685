"""freeplay — freeplay-sim's engine from Python (docs/python.md).

Experiments (load, validate, run scenarios and suites; records and summaries as Python data and pandas
DataFrames), robot play policies written in Python (subclass :class:`Policy`, name them
``python:MODULE:CLASS``), and a Gymnasium-style environment (:class:`Env`, :class:`VecEnv`).
Build with ``scripts/build.sh``; import with ``PYTHONPATH=build/python /usr/bin/python3``.
"""

from ._freeplay import (  # noqa: F401  (the C++ types a policy sees and returns)
    ActionResult,
    CancelMove,
    InputError,
    ItemObservation,
    LookAt,
    MoveItem,
    Observation,
    PerceivedChild,
    PerceivedGaze,
    PointAt,
    PolicyContext,
    Pose2,
    RobotSelf,
    Rng,
    Say,
    TouchObservation,
    Wait,
    ZoneObservation,
    episode_seed,
    point_in_polygon,
    policy_names,
)
from .experiments import Run, compare, load, run, validate  # noqa: F401
from .policy import Policy  # noqa: F401
from .env import Env, VecEnv, observation_space, action_space  # noqa: F401
from . import rewards  # noqa: F401

__all__ = [
    "ActionResult", "CancelMove", "Env", "InputError", "ItemObservation", "LookAt", "MoveItem", "Observation",
    "PerceivedChild", "PerceivedGaze", "PointAt", "Policy", "PolicyContext", "Pose2", "RobotSelf", "Rng", "Run",
    "Say", "TouchObservation", "VecEnv", "Wait", "ZoneObservation", "action_space", "compare", "episode_seed", "load",
    "observation_space", "point_in_polygon", "policy_names", "rewards", "run", "validate",
]
