"""Speed of the freeplay Python module beside the C++ engine, on the same scenario (docs/python.md, Speed).

  PYTHONPATH=build/python /usr/bin/python3 bench/python/bench_python.py [--episodes N] [--scenario FILE]

1. a trivial Python policy (returns no action) against the C++ `idle` policy: simulated free-play seconds per
   wall second on one worker;
2. Env.step: wall time per decision of an Env rollout minus that of the same episodes run by `idle` in C++;
3. VecEnv with 1 and 2 environments: decisions per wall second, beside the C++ engine's own scaling from 1 to 2
   workers on the same episodes (what this machine allows at the moment: a VecEnv cannot scale better), with the
   default reward (built-in: computed in C++ inside the batched step) and with a Python callable (called per
   environment and step);
4. (--async, alone) VecEnv stepped asynchronously: 2 environments, batch_size 1 (send/recv, a trivial policy that
   sends no action), and 1 environment so, beside the synchronous VecEnv of 1 and 2 environments and the engine's
   1 -> 2 workers, all alternating in 3 rounds (best of each); --policy-us adds busy Python per decision;
Wall-clock numbers: run on a quiet machine and report them with the machine.
"""

import argparse
import os
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import freeplay  # noqa: E402


class Trivial(freeplay.Policy):
    """Does nothing, in Python."""

    def decide(self, observation):
        return []


def timed_run(scenario, overrides, episodes, jobs=1, repetitions=3):
    """The fastest of `repetitions` runs: (wall seconds, simulated free-play seconds)."""
    best = None
    for _ in range(repetitions):
        with tempfile.TemporaryDirectory() as out:
            start = time.perf_counter()
            run = freeplay.run(scenario, episodes=episodes, seed=1, jobs=jobs, overrides=overrides,
                               out=os.path.join(out, "run"), events="none")
            wall = time.perf_counter() - start
            best = min(best or wall, wall)
            simulated = sum(r["duration_s"] for r in run.records)
    return best, simulated


def alternating(first, second, best, repetitions=3):
    """(best of `first`, best of `second`) over `repetitions` alternating calls of each."""
    a, b = [], []
    for _ in range(repetitions):
        a.append(first())
        b.append(second())
    return best(a), best(b)


def env_rollouts(env, episodes):
    """Wall seconds and steps of Env rollouts of episodes 0…episodes-1 (seed 1) that do nothing."""
    steps = 0
    start = time.perf_counter()
    for i in range(episodes):
        env.reset(seed=1, options={"episode": i})
        while True:
            *_, terminated, truncated, _ = env.step([])
            steps += 1
            if terminated or truncated:
                break
    return time.perf_counter() - start, steps


def python_reward(step):
    """A reward written in Python (VecEnv calls it once per environment and step)."""
    return step.dt


def think(seconds):
    """A policy's own work on one decision: `seconds` of busy Python (0: none)."""
    if seconds:
        until = time.perf_counter() + seconds
        while time.perf_counter() < until:
            pass
    return []


def vec_rate(scenario, overrides, n, steps, reward=None, policy_s=0.0):
    """Decisions per wall second of a VecEnv of n environments doing nothing (after `policy_s` of thinking per
    environment and decision)."""
    vec = freeplay.VecEnv(n, scenario, overrides, reward=reward)
    vec.reset(seed=1)
    start = time.perf_counter()
    for _ in range(steps):
        vec.step([think(policy_s) for _ in range(n)])
    return n * steps / (time.perf_counter() - start)


def async_rate(scenario, overrides, n, batch_size, steps, policy_s=0.0):
    """Decisions per wall second of a VecEnv of n environments stepped with send/recv (batch_size each), doing
    nothing: each recv's environments are sent their (empty) actions at once (after `policy_s` of thinking each)."""
    vec = freeplay.VecEnv(n, scenario, overrides, batch_size=batch_size)
    vec.async_reset(seed=1)
    env_ids = vec.recv()[4]["env_id"]
    done = 0
    start = time.perf_counter()
    while done < steps:
        vec.send([think(policy_s) for _ in env_ids], env_ids)
        env_ids = vec.recv()[4]["env_id"]
        done += len(env_ids)
    return done / (time.perf_counter() - start)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--episodes", type=int, default=6)
    parser.add_argument("--scenario", default=os.path.join(os.path.dirname(__file__), "..", "..", "scenarios",
                                                             "child-robot-asocial.yaml"))
    parser.add_argument("--vec-steps", type=int, default=3000)
    parser.add_argument("--python-reward", action="store_true",
                        help="also time VecEnv with a reward written in Python")
    parser.add_argument("--vec-only", action="store_true", help="only the C++ engine's 1 -> 2 workers and VecEnv")
    parser.add_argument("--async", dest="asynchronous", action="store_true",
                        help="only the C++ engine's 1 -> 2 workers, the 1-environment VecEnv and 2 environments "
                             "stepped with send/recv (batch_size 1), alternating")
    parser.add_argument("--policy-us", type=float, default=0.0,
                        help="with --async: microseconds of busy Python per decision (a policy's own work), which "
                             "send/recv can overlap with the other environments' simulation and step cannot")
    args = parser.parse_args()
    short = ["protocol.greeting_s=0", "protocol.tutorial_s=1", "protocol.debriefing_s=0"]

    timed_run(args.scenario, short + ["robot.policy=idle"], 1, repetitions=1)  # loads the shared models once
    if args.asynchronous:
        policy_s = args.policy_us * 1e-6
        measure = {
            "engine 1 worker": lambda: timed_run(args.scenario, short + ["robot.policy=idle"], args.episodes,
                                                 repetitions=1)[0],
            "engine 2 workers": lambda: timed_run(args.scenario, short + ["robot.policy=idle"], args.episodes,
                                                  jobs=2, repetitions=1)[0],
            "VecEnv 1 env": lambda: vec_rate(args.scenario, short, 1, args.vec_steps, policy_s=policy_s),
            "VecEnv 2 envs": lambda: vec_rate(args.scenario, short, 2, args.vec_steps, policy_s=policy_s),
            "async 1 env, batch 1": lambda: async_rate(args.scenario, short, 1, 1, args.vec_steps, policy_s=policy_s),
            "async 2 envs, batch 1": lambda: async_rate(args.scenario, short, 2, 1, 2 * args.vec_steps,
                                                        policy_s=policy_s),
        }
        seen = {name: [] for name in measure}
        for _ in range(3):  # alternating: every measurement of a round sees about the same load
            for name, run in measure.items():
                seen[name].append(run())
        best = {name: (min if name.startswith("engine") else max)(values) for name, values in seen.items()}
        print(f"C++ idle run, 2 workers: {best['engine 1 worker'] / best['engine 2 workers']:.2f}x the speed of "
              f"1 worker (this machine's ceiling now)")
        one = best["VecEnv 1 env"]
        print(f"VecEnv: 1 env {one:,.0f} steps/s, 2 envs (step) {best['VecEnv 2 envs']:,.0f} steps/s "
              f"({best['VecEnv 2 envs'] / one:.2f}x), 2 envs (send/recv, batch 1) "
              f"{best['async 2 envs, batch 1']:,.0f} steps/s ({best['async 2 envs, batch 1'] / one:.2f}x); "
              f"1 env (send/recv) {best['async 1 env, batch 1']:,.0f} steps/s")
        for name, values in seen.items():
            print(f"  {name}: " + ", ".join(f"{v:,.3f} s" if name.startswith("engine") else f"{v:,.0f} steps/s"
                                            for v in values))
        return
    if not args.vec_only:
        cpp_wall, cpp_sim = timed_run(args.scenario, short + ["robot.policy=idle"], args.episodes)
        py_wall, py_sim = timed_run(args.scenario, short + ["robot.policy=python:bench_python:Trivial"],
                                    args.episodes)
        print(f"free play, 1 worker, {args.episodes} episodes: C++ idle {cpp_sim / cpp_wall:,.0f}x real time; "
              f"Python trivial {py_sim / py_wall:,.0f}x real time; ratio {py_wall / cpp_wall:.2f}")
        env = freeplay.Env(args.scenario, short + ["robot.policy=idle"])
        env_wall, steps = min(env_rollouts(env, args.episodes) for _ in range(3))
        print(f"Env: {steps} steps in {env_wall:.2f} s; C++ idle run of the same episodes {cpp_wall:.2f} s; "
              f"overhead {(env_wall - cpp_wall) / steps * 1e6:.1f} us per step")

    # Each pair below alternates its two measurements (best of 3 each), so that both see the same machine load.
    cpp_one_wall, cpp_two_wall = alternating(
        lambda: timed_run(args.scenario, short + ["robot.policy=idle"], args.episodes, repetitions=1)[0],
        lambda: timed_run(args.scenario, short + ["robot.policy=idle"], args.episodes, jobs=2, repetitions=1)[0],
        min)
    print(f"C++ idle run, 2 workers: {cpp_one_wall / cpp_two_wall:.2f}x the speed of 1 worker "
          f"(this machine's ceiling now)")
    one, two = alternating(lambda: vec_rate(args.scenario, short, 1, args.vec_steps),
                           lambda: vec_rate(args.scenario, short, 2, args.vec_steps), max)
    print(f"VecEnv: 1 env {one:,.0f} steps/s, 2 envs {two:,.0f} steps/s, scaling {two / one:.2f}x")
    if args.python_reward:
        one, two = alternating(lambda: vec_rate(args.scenario, short, 1, args.vec_steps, python_reward),
                               lambda: vec_rate(args.scenario, short, 2, args.vec_steps, python_reward), max)
        print(f"VecEnv, Python reward: 1 env {one:,.0f} steps/s, 2 envs {two:,.0f} steps/s, "
              f"scaling {two / one:.2f}x")


if __name__ == "__main__":
    main()
