"""Python policies the tests name as python:policies_for_tests:CLASS."""

import math

import numpy

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
        target = me.arm_reach_centre + r * numpy.array([math.cos(angle), math.sin(angle)])
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


#: The real play node's item order and habitats (policies/src/asocial.cpp).
ASOCIAL_ITEMS = ["zebra", "elephant", "ball", "lion", "giraffe", "caravan", "crocodile", "hippo", "boy", "girl"]
ASOCIAL_HABITATS = {
    "zebra": ["yellow", "green"], "elephant": ["green"], "lion": ["yellow"], "giraffe": ["yellow", "green"],
    "crocodile": ["blue"], "hippo": ["blue"], "ball": ["yellow", "green", "purple", "white"],
    "caravan": ["yellow", "green", "purple", "white"], "boy": ["yellow", "green", "purple", "white"],
    "girl": ["yellow", "green", "purple", "white"],
}


def distance(a, b):
    """Euclidean distance as Eigen computes it (sqrt of x² + y²)."""
    dx, dy = float(a[0] - b[0]), float(a[1] - b[1])
    return math.sqrt(dx * dx + dy * dy)


class Asocial(freeplay.Policy):
    """A Python port of the C++ `asocial` policy (same parameters, same draws from the policy's stream)."""

    def reset(self, context, rng):
        self.rng, self.resume_at, self.waiting, self.arrived = rng, 0.0, False, False
        self.pause = (self.params.get("pause_min_s", 1.2), self.params.get("pause_max_s", 2.5))
        self.idle_pause = self.params.get("idle_pause_s", 0.3)

    @staticmethod
    def reachable(me, point):
        return not me.arm_reach_known or distance(point, me.arm_reach_centre) < me.arm_reach_radius

    def choose_move(self, obs):
        order = list(range(len(ASOCIAL_ITEMS)))
        self.rng.shuffle(order)
        for index in order:
            name = ASOCIAL_ITEMS[index]
            item = obs.item(name)
            if item is None or not self.reachable(obs.self, item.position):
                continue
            habitat = ASOCIAL_HABITATS[name]
            if any(z.colour in habitat and freeplay.point_in_polygon(z.polygon, item.position) for z in obs.zones):
                continue
            colour = habitat[self.rng.uniform_int(0, len(habitat) - 1)]
            best, best_distance = None, math.inf
            for zone in obs.zones:
                if zone.colour != colour or not self.reachable(obs.self, zone.centroid):
                    continue
                d = distance(zone.centroid, item.position)
                if d < best_distance:
                    best, best_distance = zone, d
            if best is not None:
                return freeplay.MoveItem(name, best.centroid)
        return None

    def decide(self, obs):
        if self.waiting:
            if not self.arrived:
                return []
            self.waiting = False
            self.resume_at = obs.t + self.rng.uniform(*self.pause)
            return []
        if obs.t < self.resume_at:
            return []
        move = self.choose_move(obs)
        if move is not None:
            self.waiting, self.arrived = True, False
            return [move]
        self.resume_at = obs.t + self.idle_pause
        return []

    def on_result(self, result):
        if result.kind != freeplay.ActionResult.Kind.SpeechFinished:
            self.arrived = True
