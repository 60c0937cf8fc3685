"""Reward functions for :class:`freeplay.Env` and :class:`freeplay.VecEnv` over observable events and coded labels
(never hidden child state).

A reward function takes a :class:`freeplay.env.Step` and returns a float. The built-in rewards below are computed
in C++ (python/src/vec_env.cpp, one home for both fronts): an Env calls them like any callable, and a VecEnv given
one computes every environment's reward inside its batched step without calling Python. Any other callable is
called in Python, once per environment and step.
"""

from . import _freeplay

#: The coder's social-engagement labels that count as playing together (PInSoRo names).
JOINT_PLAY = tuple(_freeplay.JOINT_PLAY)


class Builtin:
    """A built-in reward: a callable over a :class:`freeplay.env.Step` like any reward, whose C++ fast path
    ``native`` names."""

    def __init__(self, native, doc):
        self.native = native
        self.__doc__ = doc

    def __call__(self, step):
        social = [labels.get("social_engagement", "") for labels in step.coded.values()]
        return _freeplay._builtin_reward(self.native, step.dt, social)

    def __repr__(self):
        return f"freeplay.rewards.{self.native}"


zero = Builtin("zero", "No reward.")
session_length = Builtin(
    "session_length",
    "The free-play seconds of this step: the return is the session's length (children who stay, play longer).")
coded_joint_play = Builtin(
    "coded_joint_play",
    "The seconds of this step in which a child is coded as playing with the robot (associative or cooperative "
    "social engagement).")
