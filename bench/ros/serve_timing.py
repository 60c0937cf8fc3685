#!/usr/bin/python3
"""Measures `freeplay serve` on a live ROS 1 graph: publishing jitter per topic at real time, and whether `--rate X`
holds X× with /clock. A measuring script, not a test (no pass/fail): it prints the figures docs/hardware.md quotes.

Usage: bench/ros/serve_timing.py build/freeplay [--seconds 60] [--rate 20] [--scenario scenarios/child-robot-asocial.yaml]
       (PYTHONPATH must hold build/ros/gen/python for the freeplay_sandbox_msgs classes; run from the repository root)

It starts its own rosmaster on a free loopback port, one `freeplay serve` per run (real time, then --rate), and a
rospy subscriber that stamps every arrival with the wall clock. Jitter of a topic = |arrival interval − nominal
period| (nominal: 1 / the rate the real node publishes at); p50 and p99 over the run. The subscriber's own Python
overhead is in the figures (they are an upper bound on serve's own jitter); serve's summary adds how late each
10 Hz tick went out against its schedule, measured inside serve.
"""
import argparse
import json
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import xmlrpc.client

NOMINAL_HZ = {"/tf": 10.0, "/joint_states": 10.0, "/map": 5.0}


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def percentile(values, q):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(q * (len(ordered) - 1)))] if ordered else float("nan")


def spawn(argv, log_dir, name):
    out = open(os.path.join(log_dir, name + ".log"), "w")
    return subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)


def stop(proc):
    if proc.poll() is None:
        os.killpg(proc.pid, signal.SIGINT)
        try:
            proc.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()


def serve_summary(log_dir):
    with open(os.path.join(log_dir, "serve.log")) as f:
        lines = [line for line in f.read().splitlines() if line.startswith("{")]
    return json.loads(lines[-1]) if lines else {}


def measure(args, rospy, log_dir, rate):
    from rosgraph_msgs.msg import Clock
    from sensor_msgs.msg import JointState
    from tf2_msgs.msg import TFMessage
    from nav_msgs.msg import OccupancyGrid
    argv = [args.freeplay, "serve", args.scenario, "--set", "protocol.greeting_s=2", "--set", "protocol.tutorial_s=2",
            "--set", f"protocol.freeplay_cap_s={max(60, int(args.seconds * rate) + 30)}", "--set",
            "protocol.debriefing_s=1"]
    if rate != 1.0:
        argv += ["--rate", str(rate)]
    arrivals = {topic: [] for topic in NOMINAL_HZ}
    clock = []
    subscribers = [rospy.Subscriber(topic, kind, lambda m, t=topic: arrivals[t].append(time.monotonic()),
                                    queue_size=100)
                   for topic, kind in [("/tf", TFMessage), ("/joint_states", JointState), ("/map", OccupancyGrid)]]
    subscribers.append(rospy.Subscriber("/clock", Clock, lambda m: clock.append((time.monotonic(), m.clock.to_sec())),
                                        queue_size=1000))
    serve = spawn(argv, log_dir, "serve")
    try:
        deadline = time.monotonic() + 60
        while not arrivals["/tf"]:
            if time.monotonic() > deadline or serve.poll() is not None:
                sys.exit(f"serve published no /tf:\n{open(os.path.join(log_dir, 'serve.log')).read()}")
            time.sleep(0.1)
        time.sleep(3.0)  # past the greeting and tutorial
        for values in arrivals.values():
            values.clear()
        clock.clear()
        time.sleep(args.seconds)
        snapshot = {topic: list(values) for topic, values in arrivals.items()}
        clock_snapshot = list(clock)
    finally:
        for s in subscribers:
            s.unregister()
        stop(serve)
    result = {"rate": rate, "topics": {}}
    for topic, times in snapshot.items():
        intervals = [b - a for a, b in zip(times, times[1:])]
        period = 1.0 / (NOMINAL_HZ[topic] * rate)
        jitter_ms = [abs(i - period) * 1000.0 for i in intervals]
        span = times[-1] - times[0] if len(times) > 1 else float("nan")
        result["topics"][topic] = {"messages": len(times), "hz": (len(times) - 1) / span if span == span else 0.0,
                                   "jitter_p50_ms": percentile(jitter_ms, 0.5),
                                   "jitter_p99_ms": percentile(jitter_ms, 0.99)}
    if len(clock_snapshot) > 1:
        (w0, c0), (w1, c1) = clock_snapshot[0], clock_snapshot[-1]
        result["clock_speed"] = (c1 - c0) / (w1 - w0)
    result["serve_timing"] = serve_summary(log_dir).get("timing", {})
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("freeplay")
    parser.add_argument("--seconds", type=float, default=60.0, help="wall seconds measured per run")
    parser.add_argument("--rate", type=float, default=20.0, help="the faster-than-real-time run's --rate")
    parser.add_argument("--scenario", default="scenarios/child-robot-asocial.yaml")
    args = parser.parse_args()
    log_dir = tempfile.mkdtemp(prefix="freeplay-serve-timing-")
    port = free_port()
    os.environ.update({"ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_IP": "127.0.0.1", "ROS_HOME": log_dir,
                       "ROS_LOG_DIR": log_dir})
    master = spawn(["/usr/bin/rosmaster", "--core", "-p", str(port)], log_dir, "rosmaster")
    try:
        deadline = time.monotonic() + 15
        while True:
            try:
                xmlrpc.client.ServerProxy(os.environ["ROS_MASTER_URI"]).getSystemState("/timing")
                break
            except OSError:
                if time.monotonic() > deadline:
                    sys.exit("rosmaster did not start")
                time.sleep(0.2)
        import rospy
        rospy.init_node("freeplay_serve_timing", anonymous=True, disable_signals=True)
        results = [measure(args, rospy, log_dir, 1.0), measure(args, rospy, log_dir, args.rate)]
    finally:
        stop(master)
    print(json.dumps({"load_average": os.getloadavg(), "cpus": os.cpu_count(), "seconds": args.seconds,
                      "runs": results}, indent=1))


if __name__ == "__main__":
    main()
