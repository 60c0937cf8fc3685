"""Reward functions for :class:`freeplay.Env` over observable events and coded labels (never hidden child state).

A reward function takes a :class:`freeplay.env.Step` and returns a float.
"""

#: The coder's social-engagement labels that count as playing together (PInSoRo names).
JOINT_PLAY = ("associative", "cooperative")


def zero(step):
    """No reward."""
    return 0.0


def session_length(step):
    """The free-play seconds of this step: the return is the session's length (children who stay, play longer)."""
    return step.dt


def coded_joint_play(step):
    """The seconds of this step in which a child is coded as playing with the robot (associative or
    cooperative social engagement)."""
    return step.dt if any(labels.get("social_engagement") in JOINT_PLAY for labels in step.coded.values()) else 0.0
