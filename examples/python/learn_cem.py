"""Learning against the synthetic children: cross-entropy search over a 3-parameter Python policy.

  PYTHONPATH=build/python:examples/python /usr/bin/python3 examples/python/learn_cem.py \
      [--iterations 6] [--population 8] [--episodes 4] [--check-sessions 100] [--out FOLDER]

The policy (JoinIn) waits `delay_s` after the child's last touch, then moves an item next to the child's last item
with probability `move_p` and talks with probability `say_p`. The objective is the mean free-play duration (how
long the synthetic child keeps playing; records' `duration_s`), estimated on common random numbers (the same seeds
for every candidate). It prints the learning curve (and draws it with python3-matplotlib). Session length is a
proxy that a policy can also raise by shortcuts the child model rewards (e.g. talking often): read the learned
parameters before believing them.

Then it checks what was learned, on children the search never met (seed 4242, the validity panel's, against the
search's 42): the learned policy, its yoked control (`policy: yoked`: each child gets the learned robot's session
with another child, the same activity without contingency; docs/validity.md) and the asocial robot (the panel's
reference), `--check-sessions` sessions each, into OUT/learned, OUT/yoked-learned and OUT/asocial. It prints their
durations and coded shares, the panel's bounds for a robot that ignores the child (applied to the yoked control),
and learned − yoked paired by child from `freeplay compare` (it needs build/freeplay).
"""

import argparse
import json
import os
import tempfile
import time

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


#: The search's root seed; the check uses other children (the validity panel's seed).
SEARCH_SEED, CHECK_SEED = 42, 4242
#: The coded shares the check reports (purple: the child of a child-robot session).
SHARES = ("associative", "cooperative")


def policy_overrides(theta):
    """The overrides that make the scenario's robot JoinIn with parameters theta."""
    params = {"delay_s": float(theta[0]), "move_p": float(theta[1]), "say_p": float(theta[2])}
    return ["robot.policy=python:learn_cem:JoinIn", ("robot.params", params)]


def evaluate(theta, episodes, jobs, extra):
    """Mean free-play duration (min) of JoinIn(theta) over the search's children."""
    with tempfile.TemporaryDirectory() as out:  # candidates' run folders are not kept
        run = freeplay.run(SCENARIO, episodes=episodes, seed=SEARCH_SEED, jobs=jobs, events="none",
                           out=os.path.join(out, "run"), overrides=policy_overrides(theta) + extra)
        return numpy.mean([r["duration_s"] for r in run.records]) / 60.0


def share(record, label):
    """The purple child's coded share of `label` in one session."""
    return record["metrics"]["label_share"]["purple"][label]


def check_learned(theta, sessions, jobs, extra, out):
    """Runs the learned policy, its yoked control and the asocial robot on fresh children; prints what they did."""
    common = dict(episodes=sessions, seed=CHECK_SEED, jobs=jobs, quiet=True)
    runs = {"learned": freeplay.run(SCENARIO, out=os.path.join(out, "learned"), events="all",
                                    overrides=policy_overrides(theta) + extra, **common)}
    runs["yoked-learned"] = freeplay.run(
        SCENARIO, out=os.path.join(out, "yoked-learned"), events="none",
        overrides=["robot.policy=yoked", ("robot.params", {"from": os.path.join(out, "learned")})] + extra, **common)
    runs["asocial"] = freeplay.run(SCENARIO, out=os.path.join(out, "asocial"), events="none",
                                   overrides=["robot.policy=asocial"] + extra, **common)
    means = {}
    print(f"\ncheck on {sessions} fresh children (seed {CHECK_SEED}), purple child's coded shares")
    print("| robot | sessions | free play (min) | associative | cooperative | joint play |\n|---|---|---|---|---|---|")
    for name, run in runs.items():
        rows = run.records
        means[name] = {"duration": numpy.mean([r["duration_s"] for r in rows]) / 60.0,
                       **{label: numpy.mean([share(r, label) for r in rows]) for label in SHARES}}
        m = means[name]
        print(f"| {name} | {len(rows)} | {m['duration']:.2f} | {m['associative']:.3f} | {m['cooperative']:.3f} | "
              f"{m['associative'] + m['cooperative']:.3f} |")
    yoked, asocial = means["yoked-learned"], means["asocial"]
    print("\nthe validity panel's bounds for a robot that ignores the child, on the yoked control:")
    for what, value, bound in (("cooperative share", yoked["cooperative"], 0.05),
                               ("associative share", yoked["associative"], asocial["associative"] + 0.05),
                               ("free play (min)", yoked["duration"], asocial["duration"] + 2.0)):
        print(f"  {'ok  ' if value <= bound else 'FAIL'} {what} = {value:.3f} (bound {bound:.3f})")
    comparison = freeplay.compare(os.path.join(out, "yoked-learned"), os.path.join(out, "learned"),
                                  metrics=["duration_s"] + [f"metrics.label_share.purple.{label}" for label in SHARES])
    print("\nlearned − yoked, paired by child (the same children), 95 % bootstrap CI:")
    paired = {}
    for metric in comparison["comparisons"][0]["metrics"]:
        p = metric["paired"]
        low, high = p["ci"]
        verdict = "above zero" if low > 0 else "below zero" if high < 0 else "includes zero"
        paired[metric["metric"]] = {"mean": p["mean_difference"], "ci": [low, high]}
        print(f"  {metric['metric']}: {p['mean_difference']:+.3f} [{low:+.3f}, {high:+.3f}] ({verdict})")
    with open(os.path.join(out, "check.json"), "w") as f:
        json.dump({"theta": [float(x) for x in theta], "means": means, "paired": paired}, f, indent=1)


def main():
    parser = argparse.ArgumentParser(description="cross-entropy search over a Python policy")
    parser.add_argument("--iterations", type=int, default=6)
    parser.add_argument("--population", type=int, default=8)
    parser.add_argument("--episodes", type=int, default=4)
    parser.add_argument("--jobs", type=int, default=os.cpu_count())
    parser.add_argument("--set", action="append", default=[], help="extra KEY=VALUE overrides")
    parser.add_argument("--check-sessions", type=int, default=100,
                        help="sessions of the check of the learned policy (0: no check)")
    parser.add_argument("--out", default=None,
                        help="folder of the check's run folders (default: learn_cem-runs/<UTC time>; an existing "
                             "folder is resumed, which needs the same learned parameters)")
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
    if args.check_sessions > 0:
        out = args.out or os.path.join("learn_cem-runs", time.strftime("%Y%m%dT%H%M%SZ", time.gmtime()))
        check_learned(mean, args.check_sessions, args.jobs, args.set, out)


if __name__ == "__main__":
    main()
