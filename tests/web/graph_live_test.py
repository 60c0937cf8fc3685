"""`freeplay serve --web --web-graph`: the web page and the live ROS graph drive one served episode together.

Usage: graph_live_test.py FREEPLAY SCENARIO. Starts its own rosmaster on a free loopback port and a web session that
also serves the game on it, then checks, with rospy beside the page's HTTP API: the game's /tf and the Nao's
/joint_states reach the graph; the page's Tutorial button moves the episode to the tutorial and the graph hears
`sandtray/signals/start_tutorial`; the graph's `sandtray/signals/start_freeplay` moves the same episode to free play;
the wizard's `say` is the robot's `speech` on the graph. Exit status 77 (ctest: skipped) only when rosmaster or rospy
is missing.
"""
import json
import os
import subprocess
import sys
import time
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sparc_live_test import ros_environment, start_rosmaster, until  # noqa: E402  (the same harness)

FREEPLAY, SCENARIO = sys.argv[1], sys.argv[2]


def main():
    try:
        import rospy
        from sensor_msgs.msg import JointState
        from std_msgs.msg import Empty, String
        from tf2_msgs.msg import TFMessage
    except ImportError as e:
        print(f"SKIPPED: rospy or the ROS messages missing ({e}); scripts/setup.sh installs them")
        return 77
    home, port = ros_environment("freeplay-web-graph-")
    procs = []
    failures = []

    def check(ok, what):
        print(f"{'ok  ' if ok else 'FAIL'} {what}")
        if not ok:
            failures.append(what)

    try:
        if not start_rosmaster(port, procs):
            return 77
        # Greetings and tutorial last until the buttons; free play 60 s at most.
        serve = subprocess.Popen([FREEPLAY, "serve", SCENARIO, "--web", "0", "--web-graph", "--web-mode", "wizard",
                                  "--web-out", os.path.join(home, "session"), "--web-no-linger", "--seed", "7",
                                  "--set", "protocol.greeting_s=600", "--set", "protocol.tutorial_s=600",
                                  "--set", "protocol.freeplay_cap_s=60", "--set", "protocol.debriefing_s=1"],
                                 stdout=subprocess.PIPE, text=True, start_new_session=True)
        procs.append(serve)
        base = serve.stdout.readline().strip().removeprefix("web: ").rstrip("/")
        state = lambda: json.load(urllib.request.urlopen(base + "/api/state"))
        post = lambda body: urllib.request.urlopen(urllib.request.Request(
            base + "/api/command", data=json.dumps(body).encode(), method="POST")).status

        rospy.init_node("graph_test", anonymous=True, disable_signals=True)
        heard = {"tf": 0, "joints": 0, "tutorial": 0, "speech": []}
        rospy.Subscriber("/tf", TFMessage, lambda m: heard.__setitem__("tf", heard["tf"] + 1))
        rospy.Subscriber("/joint_states", JointState, lambda m: heard.__setitem__("joints", len(m.name)))
        rospy.Subscriber("sandtray/signals/start_tutorial", Empty,
                         lambda m: heard.__setitem__("tutorial", heard["tutorial"] + 1))
        rospy.Subscriber("speech", String, lambda m: heard["speech"].append(m.data))
        freeplay = rospy.Publisher("sandtray/signals/start_freeplay", Empty, queue_size=1)
        until("the game's topics on the graph", lambda: heard["tf"] > 10 and heard["joints"] > 20, 30)
        check(True, "the game's /tf and the Nao's /joint_states reach the graph")

        time.sleep(1.0)  # the subscribers are connected to the game's publishers
        check(post({"type": "signal", "name": "start_tutorial"}) == 202, "the page's Tutorial button is accepted")
        until("the tutorial", lambda: state()["stage"] == "tutorial", 20)
        until("start_tutorial on the graph", lambda: heard["tutorial"] > 0, 20)
        check(True, "the page's Tutorial button moves the episode on and the graph hears sandtray/signals/start_tutorial")

        until("the game's signal subscriber", lambda: freeplay.get_num_connections() > 0, 20)
        freeplay.publish(Empty())
        until("free play", lambda: state()["stage"] == "freeplay", 20)
        events = json.load(urllib.request.urlopen(base + "/api/events"))
        received = [e["data"]["name"] for e in events if e["type"] == "signal_received"]
        check(received == ["start_tutorial", "start_freeplay"],
              f"the graph's start_freeplay moves the same episode to free play (received: {received})")

        until("the robot's reach", lambda: state()["freeplay_t"] >= 1.0, 20)
        post({"type": "say", "text": "Hello from the page"})
        until("the robot's speech on the graph", lambda: "Hello from the page" in heard["speech"], 20)
        check(True, "the wizard's say is the robot's speech on the graph")
        post({"type": "signal", "name": "blank_interface"})
        serve.wait(30)
        check(serve.returncode == 0, f"the session ends cleanly (exit {serve.returncode})")
        return 1 if failures else 0
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()


if __name__ == "__main__":
    sys.exit(main())
