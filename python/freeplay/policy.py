"""The base class of robot play policies written in Python."""


class Policy:
    """A robot play policy, called by the episode loop at the 10 Hz decision rate.

    Subclass it and name the subclass in a scenario as ``robot.policy: python:MODULE:CLASS`` (MODULE importable
    from ``PYTHONPATH``). One instance is made per episode with the scenario's ``robot.params`` as a dict. It sees
    exactly what a C++ policy sees: a :class:`freeplay.Observation` per decision.
    """

    #: True when the policy uses perceived children (``observation.children``); False skips perception.
    perceives_children = False

    def __init__(self, params=None):
        """Keeps the scenario's ``robot.params`` (a dict, empty when absent)."""
        self.params = dict(params or {})

    def reset(self, context, rng):
        """Prepares for a new episode: ``context`` (:class:`freeplay.PolicyContext`) and the policy's own
        :class:`freeplay.Rng` stream (use it for every random choice, so that runs are deterministic)."""

    def decide(self, observation):
        """Returns the actions to start now (a list of MoveItem, LookAt, PointAt, Say, Wait, CancelMove; often
        empty)."""
        return []

    def on_result(self, result):
        """Told when a move or an utterance ended (:class:`freeplay.ActionResult`)."""
