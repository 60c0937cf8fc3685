"""A robot play policy in 40 lines of Python, run against the PInSoRo baselines beside `asocial` and `social`.

  PYTHONPATH=build/python:examples/python /usr/bin/python3 examples/python/follow_the_child.py [--episodes 20]

Follow the child: when the child drags an item, the robot looks at it; a few seconds after the child lets go,
it moves another item next to the one the child last played with, and sometimes says so.
"""

import argparse
import os

import numpy

import freeplay

HERE = os.path.dirname(os.path.abspath(__file__))
SCENARIO = os.path.join(HERE, "..", "..", "scenarios", "child-robot-asocial.yaml")


class FollowTheChild(freeplay.Policy):
    """Joins in next to where the child plays."""

    perceives_children = True

    def reset(self, context, rng):
        self.rng, self.last_item, self.idle_since = rng, None, 0.0

    def decide(self, obs):
        me = obs.self
        touched = [i for i in obs.items if i.touched_by_child]
        if touched:
            self.last_item, self.idle_since = touched[0], obs.t
            return [freeplay.LookAt(point=(*touched[0].position, 0.0))]
        if me.moving_item or me.speaking or self.last_item is None or obs.t - self.idle_since < 3.0:
            return []
        self.idle_since = obs.t + 5.0  # wait before joining in again
        others = [i for i in obs.items if i.visible and i.name != self.last_item.name and not i.touched_by_child]
        if not others or not me.arm_reach_known:
            return []
        item = others[self.rng.uniform_int(0, len(others) - 1)]
        target = self.last_item.position + 0.08 * numpy.array([self.rng.normal(), self.rng.normal()])
        offset = target - me.arm_reach_centre  # keep the goal inside the arm's reach
        if numpy.linalg.norm(offset) > 0.9 * me.arm_reach_radius:
            target = me.arm_reach_centre + offset * 0.9 * me.arm_reach_radius / numpy.linalg.norm(offset)
        actions = [freeplay.MoveItem(item.name, target)]
        if self.rng.bernoulli(0.3):
            actions.append(freeplay.Say(f"I put the {item.name} next to your {self.last_item.name}!"))
        return actions


def main():
    parser = argparse.ArgumentParser(description="a Python policy beside asocial and social")
    parser.add_argument("--episodes", type=int, default=20)
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    parser.add_argument("--figure", default="follow_the_child.png")
    parser.add_argument("--set", action="append", default=[], help="extra KEY=VALUE overrides (e.g. short runs)")
    args = parser.parse_args()
    durations = {}
    for policy in ("asocial", "social", "python:follow_the_child:FollowTheChild"):
        run = freeplay.run(SCENARIO, episodes=args.episodes, seed=2017, jobs=args.jobs,
                           overrides=[f"robot.policy={policy}"] + args.set, events="none")
        durations[policy.split(":")[-1]] = numpy.array([r["duration_s"] for r in run.records]) / 60.0
    print(f"| policy | sessions | free play, min (mean ± SD) | ≥ 10 min |\n|---|---|---|---|")
    for name, d in durations.items():
        print(f"| {name} | {len(d)} | {d.mean():.1f} ± {d.std(ddof=1) if len(d) > 1 else 0:.1f} | "
              f"{(d >= 10).mean():.0%} |")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("(no matplotlib: python3-matplotlib draws the figure)")
        return
    plt.boxplot(list(durations.values()), labels=list(durations))
    plt.ylabel("free-play duration (min)")
    plt.savefig(args.figure, dpi=120)
    print(f"figure: {args.figure}")


if __name__ == "__main__":
    main()
