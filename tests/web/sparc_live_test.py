"""`freeplay serve --web --web-ros` takes the real Wizard-of-Oz GUI's `sparc/selected_action` from a live ROS master.

Usage: sparc_live_test.py FREEPLAY SCENARIO. Starts its own rosmaster on a free loopback port and the web session,
publishes one geometry_msgs/PoseStamped (frame_id = item name, the drop point in the item's frame) with rospy, and
checks that the simulated robot moved that item to the drop point (within 1 cm) and that the session log names the
topic. Exit status 77 (ctest: skipped) only when rosmaster or rospy is missing.
"""
import json
import math
import os
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
import xmlrpc.client

FREEPLAY, SCENARIO = sys.argv[1], sys.argv[2]


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def until(what, predicate, timeout=60):
    deadline = time.monotonic() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise TimeoutError(f"timed out waiting for {what}")
        time.sleep(0.1)


def ros_environment(prefix):
    """Points this process (and its children) at a master on a free loopback port, logs in a new temporary folder;
    returns (that folder, the port)."""
    home = tempfile.mkdtemp(prefix=prefix)
    port = free_port()
    os.environ.update({"ROS_MASTER_URI": f"http://127.0.0.1:{port}/", "ROS_IP": "127.0.0.1", "ROS_HOME": home,
                       "ROS_LOG_DIR": home})
    os.environ.pop("ROS_HOSTNAME", None)
    return home, port


def start_rosmaster(port, procs):
    """Starts rosmaster on `port` (appended to `procs`) and waits for it; False (said) when it cannot start."""
    try:
        procs.append(subprocess.Popen(["/usr/bin/rosmaster", "--core", "-p", str(port)], stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL, start_new_session=True))
    except OSError as e:
        print(f"SKIPPED: rosmaster cannot start ({e})")
        return False
    until("rosmaster", lambda: _answers(f"http://127.0.0.1:{port}/"), 20)
    return True


def main():
    try:
        import rospy
        from geometry_msgs.msg import PoseStamped
    except ImportError as e:
        print(f"SKIPPED: rospy or geometry_msgs missing ({e}); scripts/setup.sh installs them")
        return 77
    home, port = ros_environment("freeplay-web-ros-")
    procs = []
    try:
        if not start_rosmaster(port, procs):
            return 77
        serve = subprocess.Popen([FREEPLAY, "serve", SCENARIO, "--web", "0", "--web-ros", "--web-mode", "wizard",
                                  "--web-out", os.path.join(home, "session"), "--web-no-linger", "--seed", "7",
                                  "--set", "protocol.greeting_s=1", "--set", "protocol.tutorial_s=1",
                                  "--set", "protocol.freeplay_cap_s=60", "--set", "protocol.debriefing_s=1"],
                                 stdout=subprocess.PIPE, text=True, start_new_session=True)
        procs.append(serve)
        base = serve.stdout.readline().strip().removeprefix("web: ").rstrip("/")
        state = lambda: json.load(urllib.request.urlopen(base + "/api/state"))
        until("free play", lambda: state().get("stage") == "freeplay" and state()["freeplay_t"] >= 2.0)
        items = [i for i in state()["items"] if i["visible"] and i["holder"] == "none"]
        item = max(items, key=lambda i: i["z"])  # the top-most: the robot finger grabs what lies on top
        target = (0.25, -0.15)
        dx, dy = target[0] - item["x"], target[1] - item["y"]
        c, s = math.cos(-item["theta"]), math.sin(-item["theta"])
        rospy.init_node("woz_gui_test", anonymous=True, disable_signals=True)
        pub = rospy.Publisher("sparc/selected_action", PoseStamped, queue_size=1)
        until("the subscriber", lambda: pub.get_num_connections() > 0, 20)
        msg = PoseStamped()
        msg.header.frame_id = item["name"]
        msg.header.stamp = rospy.Time.now()
        msg.pose.position.x, msg.pose.position.y = c * dx - s * dy, s * dx + c * dy
        msg.pose.orientation.w = 1.0
        pub.publish(msg)
        events = lambda: json.load(urllib.request.urlopen(base + "/api/events"))
        result = until("the move's result", lambda: next((e for e in events() if e["source"] == "wizard" and
                                                          e["type"] == "move_result" and e["data"]["item"] == item["name"]), None))
        time.sleep(1.5)
        moved = next(i for i in state()["items"] if i["name"] == item["name"])
        error = math.hypot(moved["x"] - target[0], moved["y"] - target[1])
        via = any(e["type"] == "command" and e["data"]["args"].get("via") == "sparc/selected_action" for e in events())
        print(f"{item['name']}: {result['data']['status']}, {error * 1000:.1f} mm from the drop point, via topic: {via}")
        return 0 if result["data"]["status"] == "succeeded" and error <= 0.01 and via else 1
    finally:
        for p in reversed(procs):
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()


def _answers(uri):
    try:
        xmlrpc.client.ServerProxy(uri).getSystemState("/freeplay_test")
        return True
    except OSError:
        return False


if __name__ == "__main__":
    sys.exit(main())
