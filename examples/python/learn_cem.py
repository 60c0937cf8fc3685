"""Learning against the synthetic children: cross-entropy search over a 3-parameter Python policy.

  PYTHONPATH=build/python:examples/python /usr/bin/python3 examples/python/learn_cem.py \
      [--iterations 6] [--population 8] [--episodes 4]

The policy (JoinIn) waits `delay_s` after the child's last touch, then moves an item next to the child's last item
with probability `move_p` and talks with probability `say_p`. The objective is the mean free-play duration (how
long the synthetic child keeps playing; records' `duration_s`), estimated on common random numbers (the same seeds
for every candidate). It prints the learning curve (and draws it with python3-matplotlib). Session length is a
proxy that a policy can also raise by shortcuts the child model rewards (e.g. talking often): read the learned
parameters before believing them.
"""

import argparse
import os
import tempfile

import numpy

import freeplay

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIO = os.path.join(HERE, "..", "..", "scenarios", "child-robot-asocial.yaml")
LOW, HIGH = numpy.array([0.5, 0.0, 0.0]), numpy.array([20.0, 1.0, 1.0])


class JoinIn(freeplay.Policy):
    """Moves an item next to the child's after a pause; parameters delay_s, move_p, say_p."""

    def reset(self, context, rng):
        self.rng, self.last, self.since = rng, None, 0.0

    def decide(self, obs):
        touched = [i for i in obs.items if i.touched_by_child]
        if touched:
            self.last, self.since = touched[0], obs.t
            return []
        me = obs.self
        if self.last is None or me.moving_item or not me.arm_reach_known or obs.t - self.since < self.params["delay_s"]:
            return []
        self.since = obs.t
        actions = []
        others = [i for i in obs.items if i.visible and i.name != self.last.name]
        if others and self.rng.bernoulli(self.params["move_p"]):
            item = others[self.rng.uniform_int(0, len(others) - 1)]
            offset = self.last.position - me.arm_reach_centre
            reach = 0.8 * me.arm_reach_radius
            target = me.arm_reach_centre + offset * min(1.0, reach / max(numpy.linalg.norm(offset), 1e-9))
            actions.append(freeplay.MoveItem(item.name, target))
        if self.rng.bernoulli(self.params["say_p"]):
            actions.append(freeplay.Say("Look what I did!"))
        return actions


def evaluate(theta, episodes, jobs, extra):
    params = {"delay_s": float(theta[0]), "move_p": float(theta[1]), "say_p": float(theta[2])}
    with tempfile.TemporaryDirectory() as out:  # candidates' run folders are not kept
        run = freeplay.run(SCENARIO, episodes=episodes, seed=42, jobs=jobs, events="none", out=os.path.join(out, "run"),
                           overrides=["robot.policy=python:learn_cem:JoinIn", ("robot.params", params)] + extra)
        return numpy.mean([r["duration_s"] for r in run.records]) / 60.0


def main():
    parser = argparse.ArgumentParser(description="cross-entropy search over a Python policy")
    parser.add_argument("--iterations", type=int, default=6)
    parser.add_argument("--population", type=int, default=8)
    parser.add_argument("--episodes", type=int, default=4)
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    parser.add_argument("--set", action="append", default=[], help="extra KEY=VALUE overrides")
    args = parser.parse_args()
    rng = numpy.random.default_rng(0)
    mean, sd = (LOW + HIGH) / 2, (HIGH - LOW) / 3
    curve = []
    for iteration in range(args.iterations):
        thetas = numpy.clip(rng.normal(mean, sd, size=(args.population, 3)), LOW, HIGH)
        scores = numpy.array([evaluate(t, args.episodes, args.jobs, args.set) for t in thetas])
        elite = thetas[numpy.argsort(scores)[-max(2, args.population // 4):]]
        mean, sd = elite.mean(axis=0), elite.std(axis=0) + 0.02 * (HIGH - LOW)
        curve.append((scores.mean(), scores.max()))
        print(f"iteration {iteration}: mean {scores.mean():.2f} min, best {scores.max():.2f} min, "
              f"theta (delay_s, move_p, say_p) = {numpy.round(mean, 2)}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        plt.plot([c[0] for c in curve], label="population mean")
        plt.plot([c[1] for c in curve], label="best")
        plt.xlabel("iteration")
        plt.ylabel("mean free-play duration (min)")
        plt.legend()
        plt.savefig("learn_cem.png", dpi=120)
    except ImportError:
        pass


if __name__ == "__main__":
    main()
