#!/usr/bin/python3
"""Live check of the fiducial localisation in `freeplay serve` through a real rosmaster.

Usage: live_localisation_test.py FREEPLAY SCENARIO localisation

Uses the harness of live_graph_test.py (own rosmaster on a free loopback port, bounded waits, every process
stopped; exit 77 only when the master cannot start). With the simulated NAO's head level the camera misses the
screen: `robot_localising` ends in "I am lost!" and no odom -> sandtray. After a gaze target on the screen, the next
`robot_localising` makes TF odom -> sandtray (and the localised arm_reach) appear, with "I know where I am now!".
"""
import os
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_graph_test import Graph, check, rospy_client  # noqa: E402  (the shared live-graph harness)


def case_localisation(g):
    g.serve("--robot", "external")
    rospy = rospy_client()
    from geometry_msgs.msg import PointStamped
    from std_msgs.msg import Empty, String
    from tf2_msgs.msg import TFMessage
    lock = threading.Lock()
    speech, frames = [], {}

    def on_speech(msg):
        with lock:
            speech.append(msg.data)

    def on_tf(msg):
        with lock:
            for t in msg.transforms:
                frames[(t.header.frame_id.lstrip("/"), t.child_frame_id)] = t.transform

    rospy.Subscriber("/speech", String, on_speech)
    rospy.Subscriber("/tf", TFMessage, on_tf)
    signal = rospy.Publisher("/sandtray/signals/robot_localising", Empty, queue_size=1)
    look = rospy.Publisher("freeplay/robot/look_at", PointStamped, queue_size=1)
    deadline = time.monotonic() + 30
    while signal.get_num_connections() == 0 or look.get_num_connections() == 0:
        check(time.monotonic() < deadline, "serve did not subscribe robot_localising and look_at within 30 s")
        time.sleep(0.1)
    time.sleep(3.0)  # free play has started (short protocol): the external robot's gaze is applied

    def wait_for(condition, timeout, what):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            with lock:
                if condition():
                    return
            time.sleep(0.1)
        with lock:
            raise AssertionError(f"{what} within {timeout} s (speech {speech}, frames {sorted(frames)})")

    # 1. Head level: the field is below the camera's view; after the 5 s search the robot is lost.
    signal.publish(Empty())
    wait_for(lambda: "I am lost!" in speech, 20, "'I am lost!' after an unsuccessful search")
    with lock:
        check(("odom", "sandtray") not in frames, "no odom -> sandtray before a successful localisation")
        check("I know where I am now!" not in speech, "no success announced while lost")
    # 2. Looking at the screen centre, the next signal localises.
    target = PointStamped()
    target.header.frame_id = "sandtray"
    target.point.x, target.point.y = 0.30, -0.17
    for _ in range(5):
        look.publish(target)
        time.sleep(0.4)
    signal.publish(Empty())
    wait_for(lambda: ("odom", "sandtray") in frames and "I know where I am now!" in speech, 20,
             "TF odom -> sandtray and 'I know where I am now!'")
    with lock:
        first = frames[("odom", "sandtray")]
    time.sleep(1.5)  # held and re-broadcast at every tick, unchanged
    with lock:
        again = frames[("odom", "sandtray")]
        reach = frames.get(("sandtray", "arm_reach"))
    check(first == again, f"odom -> sandtray held after the first success ({first} vs {again})")
    t = first.translation
    print(f"odom -> sandtray: ({t.x:.4f}, {t.y:.4f}, {t.z:.4f}); arm_reach: {reach.translation if reach else None}")
    check(t.z > 0.2, f"the sandtray origin (screen) lies above the robot's odom (floor) frame: z {t.z}")
    check(reach is not None and 0.2 < reach.translation.z < 0.5, f"arm_reach z is the reachable disc's radius: {reach}")
    log = g.log("serve")
    line = next((l for l in log.splitlines() if "off the simulator's ground truth" in l), "")
    print(line)
    mm = float(line.split(" by ")[1].split(" mm")[0])
    deg = float(line.split(", ")[-1].split(" deg")[0])
    check(mm < 10 and deg < 2, f"localised within 1 cm and 2 degrees of the ground truth ({mm} mm, {deg} deg)")


def main():
    with Graph() as g:
        try:
            case_localisation(g)
        except Exception:
            g.stop()
            print("---- serve log (last 40 lines) ----")
            print("\n".join(g.log("serve").splitlines()[-40:]))
            raise
        g.stop()
        print("serve timing:", next((l for l in reversed(g.log("serve").splitlines()) if '"timing"' in l), "?"))
    print("localisation: ok")


if __name__ == "__main__":
    main()
