"""Python policies the tests name as python:policies_for_tests:CLASS."""

import freeplay


class Idle(freeplay.Policy):
    """`idle` in Python: present at the table, does nothing."""

    def __init__(self, params=None):
        super().__init__(params)
        if self.params:
            raise ValueError("the idle policy takes no parameters")

    def decide(self, observation):
        return []


class Mover(freeplay.Policy):
    """Every 5 s, drags the first visible item nobody touches to a random point of the robot's reach."""

    def reset(self, context, rng):
        self.rng = rng
        self.next_t = 5.0

    def decide(self, observation):
        me = observation.self
        if observation.t < self.next_t or me.moving_item or not me.arm_reach_known:
            return []
        self.next_t = observation.t + 5.0
        free = [i for i in observation.items if i.visible and not i.touched_by_child]
        if not free:
            return []
        item = free[self.rng.uniform_int(0, len(free) - 1)]
        r = me.arm_reach_radius * 0.5 * self.rng.uniform()
        angle = self.rng.uniform(0.0, 6.283185307179586)
        target = me.arm_reach_centre + r * __import__("numpy").array([__import__("math").cos(angle), __import__("math").sin(angle)])
        return [freeplay.MoveItem(item.name, target)]


class BadAction(freeplay.Policy):
    """Returns something that is not an action after 2 s."""

    def decide(self, observation):
        return ["dance"] if observation.t > 2.0 else []


class Raises(freeplay.Policy):
    """Raises inside decide after 3 s in about half of the episodes (by its own stream), so some episodes finish."""

    def reset(self, context, rng):
        self.fail = rng.uniform() < 0.5

    def decide(self, observation):
        if observation.t > 3.0 and self.fail:
            return 1 / 0
        return []


class Recorder(freeplay.Policy):
    """Keeps every observation it saw (in the class, for the tests)."""

    seen = []

    def decide(self, observation):
        type(self).seen.append(observation)
        return []


class PerceivingRecorder(Recorder):
    """A Recorder that perceives the children."""

    perceives_children = True
    seen = []
