#!/usr/bin/python3
"""Live ROS 1 graph checks of `freeplay serve` and `freeplay robot` against a real rosmaster.

Usage: live_graph_test.py FREEPLAY SCENARIO CASE   (CASE: topics | client | robot | rate | signals | restart | cameras | errors)

Each case starts its own rosmaster on a free loopback port, the freeplay processes it needs, and a rospy client of
ours (independent of the C++ code, with the freeplay_sandbox_msgs Python classes genpy generated at build time);
every wait is bounded and every child process is stopped at the end. Exit status 77 (ctest: skipped) only when the
master cannot start.
"""
import math
import os
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
import xmlrpc.client

FREEPLAY, SCENARIO, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
SKIP = 77
SHORT_PROTOCOL = ["--set", "protocol.greeting_s=1", "--set", "protocol.tutorial_s=1",
                  "--set", "protocol.freeplay_cap_s=90", "--set", "protocol.debriefing_s=1"]
ITEMS = ["zebra", "elephant", "giraffe", "hippo", "lion", "crocodile", "caravan", "ball", "boy", "girl"]


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Graph:
    """A rosmaster and the processes of one case; stops them all on exit."""

    def __init__(self):
        self.dir = tempfile.mkdtemp(prefix="freeplay-ros-")
        self.port = free_port()
        self.uri = f"http://127.0.0.1:{self.port}/"
        os.environ.update({"ROS_MASTER_URI": self.uri, "ROS_IP": "127.0.0.1", "ROS_HOME": self.dir,
                           "ROS_LOG_DIR": self.dir})
        os.environ.pop("ROS_HOSTNAME", None)
        self.procs = []

    def __enter__(self):
        try:
            self.spawn("rosmaster", ["/usr/bin/rosmaster", "--core", "-p", str(self.port)])
        except OSError as e:
            print(f"SKIP: rosmaster cannot start ({e}); install python3-rosmaster (scripts/setup.sh)")
            sys.exit(SKIP)
        master = xmlrpc.client.ServerProxy(self.uri)
        deadline = time.monotonic() + 15
        while True:
            try:
                master.getSystemState("/freeplay_test")
                break
            except OSError:
                if time.monotonic() > deadline or self.procs[0][1].poll() is not None:
                    print(f"SKIP: rosmaster did not answer on {self.uri}:\n{self.log('rosmaster')}")
                    self.stop()
                    sys.exit(SKIP)
                time.sleep(0.2)
        return self

    def __exit__(self, *exc):
        self.stop()

    def spawn(self, name, argv):
        out = open(os.path.join(self.dir, name + ".log"), "w")
        proc = subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT, start_new_session=True)
        self.procs.append((name, proc))
        return proc

    def log(self, name):
        with open(os.path.join(self.dir, name + ".log")) as f:
            return f.read()

    def stop(self):
        for name, proc in reversed(self.procs):
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGINT)
                try:
                    proc.wait(timeout=8)
                except subprocess.TimeoutExpired:
                    os.killpg(proc.pid, signal.SIGKILL)
                    proc.wait(timeout=5)
        self.procs = []

    def serve(self, *extra):
        return self.spawn("serve", [FREEPLAY, "serve", SCENARIO, *SHORT_PROTOCOL, *extra])


def check(condition, message):
    if not condition:
        raise AssertionError(message)


def rospy_client():
    import rospy  # imported after ROS_MASTER_URI is set
    rospy.init_node("freeplay_test_client", anonymous=True, disable_signals=True)
    return rospy


def item_positions(rospy, timeout=10.0):
    """The latest (x, y, yaw) of every frame in `sandtray` on /tf (waits until all ten items arrived: each item has
    its own broadcaster, so a subscriber collects several messages)."""
    from tf2_msgs.msg import TFMessage
    seen = {}
    lock = threading.Lock()

    def on_tf(msg):
        with lock:
            for t in msg.transforms:
                if t.header.frame_id in ("sandtray", "/sandtray"):
                    q = t.transform.rotation
                    seen[t.child_frame_id] = (t.transform.translation.x, t.transform.translation.y,
                                              math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z)))

    subscriber = rospy.Subscriber("/tf", TFMessage, on_tf)
    deadline = time.monotonic() + timeout
    try:
        while True:
            with lock:
                if all(i in seen for i in ITEMS):
                    return dict(seen)
                check(time.monotonic() < deadline, f"not every item on /tf within {timeout} s (seen: {sorted(seen)})")
            time.sleep(0.05)
    finally:
        subscriber.unregister()


def check_md5sums():
    from freeplay_sandbox_msgs.msg import PlaygroundNavigationAction, PlaygroundNavigationGoal
    from freeplay_sandbox_msgs.srv import PlaygroundPlan
    check(PlaygroundNavigationAction._md5sum == "963b23f6d5b652b667fa543b37887490", "PlaygroundNavigationAction md5")
    check(PlaygroundNavigationGoal._md5sum == "2ed089e571e800686ee1fc2035ee705c", "PlaygroundNavigationGoal md5")
    check(PlaygroundPlan._md5sum == "961b128a52b8c2470af3bee566e33af5", "PlaygroundPlan md5")


def case_topics(g):
    """`rostopic list -v` and `rostopic hz` show the real topics and types; latched topics reach late subscribers."""
    check_md5sums()
    g.serve()
    rospy = rospy_client()
    frames = item_positions(rospy, timeout=30)
    for frame in ["camera_purple_link", "camera_yellow_link", "env_camera_link"]:
        deadline = time.monotonic() + 5
        while frame not in frames:
            check(time.monotonic() < deadline, f"no TF frame {frame}")
            frames.update(item_positions(rospy))
    listing = subprocess.run(["/usr/bin/rostopic", "list", "-v"], capture_output=True, text=True, timeout=30).stdout
    expected = {
        "/tf": "tf2_msgs/TFMessage", "/footprints": "visualization_msgs/MarkerArray",
        "/zones": "visualization_msgs/MarkerArray", "/sandtray/background/image": "sensor_msgs/Image",
        "/sandtray/background/image/compressed": "sensor_msgs/CompressedImage",
        "/sandtray/background/camera_info": "sensor_msgs/CameraInfo",
        "/sandtray/interaction_events": "std_msgs/String", "/sandtray/signals/start_freeplay": "std_msgs/Empty",
        "/sandtray/signals/robot_localising": "std_msgs/Empty", "/poses": "geometry_msgs/PoseStamped",
        "/map": "nav_msgs/OccupancyGrid", "/joint_states": "sensor_msgs/JointState",
        "/visualization_markers": "visualization_msgs/Marker", "/speech": "std_msgs/String",
    }
    for topic, kind in expected.items():
        check(f" {topic} [{kind}]" in listing, f"rostopic list -v lacks {topic} [{kind}]:\n{listing}")
    hz = subprocess.run(["timeout", "-s", "INT", "6", "/usr/bin/rostopic", "hz", "/joint_states"],
                        capture_output=True, text=True, timeout=30).stdout
    check("average rate" in hz, f"rostopic hz /joint_states saw no messages:\n{hz}")
    print("rostopic hz /joint_states:", hz.strip().splitlines()[-4:])
    from visualization_msgs.msg import MarkerArray, Marker
    from sensor_msgs.msg import CameraInfo
    footprints = rospy.wait_for_message("/footprints", MarkerArray, timeout=10)  # latched: a late subscriber gets it
    check(sorted(m.header.frame_id for m in footprints.markers) == sorted("/" + i for i in ITEMS),
          "footprints: one marker per item in the item's frame")
    zones = rospy.wait_for_message("/zones", MarkerArray, timeout=10)
    check(zones.markers[0].action == Marker.DELETEALL and len(zones.markers) > 1, "zones: DELETEALL then polygons")
    check(all(m.ns.startswith("sandbox_zone_") for m in zones.markers[1:]), "zones: ns sandbox_zone_<colour>")
    info = rospy.wait_for_message("/sandtray/background/camera_info", CameraInfo, timeout=10)
    check(abs(info.K[0] * 0.6 - info.width) < 1e-6, "camera_info K[0] = 1 / pixel2meter")
    bag = os.path.join(g.dir, "live.bag")  # rosbag record on the live graph, read back by rosbag info
    subprocess.run(["timeout", "-s", "INT", "4", "/usr/bin/rosbag", "record", "-O", bag, "/tf", "/footprints",
                    "/zones", "/joint_states"], capture_output=True, timeout=30)
    info_text = subprocess.run(["/usr/bin/rosbag", "info", bag], capture_output=True, text=True, timeout=30).stdout
    for topic, kind in [("/tf", "tf2_msgs/TFMessage"), ("/footprints", "visualization_msgs/MarkerArray"),
                        ("/zones", "visualization_msgs/MarkerArray"), ("/joint_states", "sensor_msgs/JointState")]:
        check(topic in info_text and kind in info_text, f"rosbag record/info lacks {topic} [{kind}]:\n{info_text}")
    check(g.procs[1][1].poll() is None, "serve still runs")


def wait_result(client, timeout):
    check(client.wait_for_result(__import__("rospy").Duration(timeout)), f"no action result within {timeout} s")
    return client.get_state(), client.get_goal_status_text()


def case_client(g):
    """A rospy actionlib client moves an item; bad goals are aborted with a clear text; malformed poses dropped."""
    check_md5sums()
    g.serve("--robot", "external")
    rospy = rospy_client()
    import actionlib
    from actionlib_msgs.msg import GoalStatus
    from freeplay_sandbox_msgs.msg import PlaygroundNavigationAction, PlaygroundNavigationGoal
    from freeplay_sandbox_msgs.srv import PlaygroundPlan
    from geometry_msgs.msg import Point, PoseStamped
    client = actionlib.SimpleActionClient("move_sandbox_items", PlaygroundNavigationAction)
    check(client.wait_for_server(rospy.Duration(30)), "no move_sandbox_items server within 30 s")
    start = item_positions(rospy)["ball"]
    target = (min(max(start[0] + (0.06 if start[0] < 0.3 else -0.06), 0.05), 0.55),
              min(max(start[1] + (0.04 if start[1] < -0.17 else -0.04), -0.3), -0.03))
    rospy.wait_for_service("plan_motion", timeout=10)
    plan = rospy.ServiceProxy("plan_motion", PlaygroundPlan)
    # map_and_plan's goal is in the moved item's frame: the screen centre, seen from the ball.
    dx, dy, yaw = 0.3 - start[0], -0.17 - start[1], start[2]
    goal_pose = PoseStamped()
    goal_pose.header.frame_id = "/ball"
    goal_pose.pose.position.x = math.cos(yaw) * dx + math.sin(yaw) * dy
    goal_pose.pose.position.y = -math.sin(yaw) * dx + math.cos(yaw) * dy
    path = plan(goal_pose).path
    check(len(path.poses) > 3 and path.header.frame_id == "/sandtray",
          f"plan_motion returns a path in /sandtray: {len(path.poses)} poses, frame {path.header.frame_id!r}")
    check(abs(path.poses[1].header.stamp.to_sec() - 0.1) < 1e-6, "path poses stamped 0, 0.1, 0.2 … s")
    last = path.poses[-1].pose.position
    check(math.hypot(last.x - 0.3, last.y + 0.17) < 0.01, f"the path ends at the goal ({last.x}, {last.y})")
    client.send_goal(PlaygroundNavigationGoal(item="ball", goal=Point(target[0], target[1], 0)))
    state, text = wait_result(client, 60)
    check(state == GoalStatus.SUCCEEDED, f"move ball: state {state}, text '{text}'")
    time.sleep(2.0)  # the game releases the item 1 s after the last pose
    end = item_positions(rospy)["ball"]
    error = math.hypot(end[0] - target[0], end[1] - target[1])
    print(f"ball moved from {start[:2]} to {end[:2]} (target {target}, error {error * 1000:.1f} mm)")
    check(error < 0.03, f"the ball arrived within 3 cm of the target (error {error * 1000:.1f} mm)")
    for goal, needle in [(PlaygroundNavigationGoal(item="unicorn", goal=Point(0.3, -0.1, 0)), "unknown item 'unicorn'"),
                         (PlaygroundNavigationGoal(item="ball", goal=Point(0.9, -0.1, 0)), "off the screen"),
                         (PlaygroundNavigationGoal(item="ball", goal=Point(float("nan"), -0.1, 0)), "not a finite")]:
        client.send_goal(goal)
        state, text = wait_result(client, 20)
        check(state == GoalStatus.ABORTED and needle in text, f"bad goal {goal}: state {state}, text '{text}'")
    poses = rospy.Publisher("/poses", PoseStamped, queue_size=10)
    deadline = time.monotonic() + 10
    while poses.get_num_connections() == 0:  # serve subscribes /poses
        check(time.monotonic() < deadline, "serve did not connect to our /poses publisher")
        time.sleep(0.1)
    bad = PoseStamped()
    bad.header.frame_id = "sandtray"
    bad.pose.position.x = float("nan")
    for _ in range(3):
        poses.publish(bad)
        time.sleep(0.2)
    time.sleep(1.0)
    check("dropped a malformed pose" in g.log("serve"), "serve logs the malformed /poses message")
    from geometry_msgs.msg import PointStamped  # gaze targets turn the simulated Nao's head
    from sensor_msgs.msg import JointState
    look = rospy.Publisher("freeplay/robot/look_at", PointStamped, queue_size=1)
    deadline = time.monotonic() + 10
    while look.get_num_connections() == 0:
        check(time.monotonic() < deadline, "serve did not connect to our freeplay/robot/look_at publisher")
        time.sleep(0.1)

    def head_yaw_looking_at(x, y):
        target = PointStamped()
        target.header.frame_id = "sandtray"
        target.point.x, target.point.y = x, y
        look.publish(target)
        time.sleep(1.0)
        joints = rospy.wait_for_message("/joint_states", JointState, timeout=10)
        return joints.position[list(joints.name).index("HeadYaw")]
    left, right = head_yaw_looking_at(0.05, -0.17), head_yaw_looking_at(0.55, -0.17)
    print(f"HeadYaw looking at the left end {left:.3f} rad, at the right end {right:.3f} rad")
    check(abs(left - right) > 0.1, f"look_at turns the head (HeadYaw {left} vs {right})")
    item_positions(rospy)  # the simulation runs on
    check(g.procs[1][1].poll() is None, "serve still runs after bad goals and malformed poses")


def case_rate(g):
    """`--rate 20` publishes /clock for use_sim_time, and it advances."""
    g.serve("--rate", "20", "--set", "protocol.freeplay_cap_s=600")
    rospy = rospy_client()
    from rosgraph_msgs.msg import Clock
    first = rospy.wait_for_message("/clock", Clock, timeout=30).clock.to_sec()
    time.sleep(0.5)
    later = rospy.wait_for_message("/clock", Clock, timeout=10).clock.to_sec()
    check(later > first, f"/clock advances ({first} → {later})")
    item_positions(rospy)


def case_robot(g):
    """`freeplay serve --robot external` + `freeplay robot --policy asocial`: the robot moves items by fake touches,
    and the served episode's metrics count the robot's moves as an in-process episode does."""
    serve = g.serve("--robot", "external", "--set", "protocol.freeplay_cap_s=25")
    rospy = rospy_client()
    from std_msgs.msg import String
    releases = []
    rospy.Subscriber("sandtray/interaction_events", String, lambda m: releases.append(m.data))
    start = item_positions(rospy, timeout=30)
    robot = g.spawn("robot", [FREEPLAY, "robot", "--policy", "asocial", "--duration", "20", "--seed", "3"])
    # Malformed input for the robot node: a non-finite item transform (logged and dropped, never applied).
    from tf2_msgs.msg import TFMessage
    from geometry_msgs.msg import TransformStamped
    bad_tf = rospy.Publisher("/tf", TFMessage, queue_size=10)
    wait_connected(bad_tf, "/tf (bad transforms)", timeout=30)
    wrong = TransformStamped()
    wrong.header.frame_id = "sandtray"
    wrong.child_frame_id = "ball"
    wrong.transform.translation.x = float("nan")
    wrong.transform.rotation.w = 1.0
    for _ in range(5):
        bad_tf.publish(TFMessage(transforms=[wrong]))
        time.sleep(0.1)
    try:
        robot.wait(timeout=80)
    except subprocess.TimeoutExpired:
        raise AssertionError("freeplay robot did not stop after --duration 20")
    check(robot.returncode == 0, f"freeplay robot failed:\n{g.log('robot')}")
    stats = [line for line in g.log("robot").splitlines() if line.startswith("{")]
    print("robot:", stats)
    check(stats and '"moves_succeeded":0' not in stats[-1], f"the robot completed a move: {stats}")
    released = [r[len("releasing_"):] for r in releases if r.startswith("releasing_")]
    check(released, f"the game released an item the robot dragged (events: {releases})")
    end = item_positions(rospy)
    moved = [i for i in set(released) if math.dist(start[i][:2], end[i][:2]) > 0.02]
    print("released by the robot:", released, "moved > 2 cm:", moved)
    check(moved, "an item the robot dragged moved on /tf")
    check("/tf: dropped a non-finite transform sandtray → ball" in g.log("robot"),
          "the robot node logs and drops the non-finite transform")
    try:
        serve.wait(timeout=60)
    except subprocess.TimeoutExpired:
        raise AssertionError("freeplay serve did not end after its 25 s of free play")
    check(serve.returncode == 0, f"freeplay serve failed:\n{g.log('serve')}")
    import json
    summary = json.loads([line for line in g.log("serve").splitlines() if line.startswith("{")][-1])
    metrics = summary["metrics"]
    print("serve metrics: robot_item_moves_per_min", metrics["robot_item_moves_per_min"],
          "child_item_moves_per_min", metrics["child_item_moves_per_min"], "timing", summary["timing"])
    check(not summary["aborted"] and metrics["robot_item_moves_per_min"] > 0, "the episode counted the robot's moves")


def wait_connected(publisher, what, timeout=10.0):
    deadline = time.monotonic() + timeout
    while publisher.get_num_connections() == 0:
        check(time.monotonic() < deadline, f"nobody subscribed our {what} within {timeout} s")
        time.sleep(0.1)


def case_signals(g):
    """Incoming sandtray/signals/* drive the served protocol (start_freeplay ends a 600 s greeting at once,
    items_to_stash moves the items, blank_interface ends free play) and are not echoed; a malformed gaze target is
    logged and dropped, never applied."""
    serve = g.serve("--set", "protocol.greeting_s=600", "--set", "protocol.freeplay_cap_s=600")
    rospy = rospy_client()
    from std_msgs.msg import Empty
    from geometry_msgs.msg import PointStamped
    echoes = []
    me = rospy.get_name()
    rospy.Subscriber("sandtray/signals/start_freeplay", Empty,
                     lambda m: echoes.append(m._connection_header["callerid"]))
    before = item_positions(rospy, timeout=30)
    publishers = {name: rospy.Publisher("sandtray/signals/" + name, Empty, queue_size=1, latch=False)
                  for name in ["start_freeplay", "items_to_stash", "blank_interface"]}
    for name, publisher in publishers.items():
        wait_connected(publisher, "sandtray/signals/" + name)
    time.sleep(0.5)
    publishers["start_freeplay"].publish(Empty())
    time.sleep(1.5)
    look = rospy.Publisher("freeplay/robot/look_at", PointStamped, queue_size=1)
    wait_connected(look, "freeplay/robot/look_at")
    bad = PointStamped()
    bad.header.frame_id = "odom"  # not the sandtray frame
    bad.point.x = 0.3
    look.publish(bad)
    publishers["items_to_stash"].publish(Empty())
    time.sleep(1.5)
    after = item_positions(rospy)
    moved = [i for i in ITEMS if math.dist(before[i][:2], after[i][:2]) > 0.02]
    print("items moved by items_to_stash:", moved)
    check(len(moved) >= 5, f"items_to_stash moved the items on /tf (moved: {moved})")
    publishers["blank_interface"].publish(Empty())
    try:
        serve.wait(timeout=30)
    except subprocess.TimeoutExpired:
        raise AssertionError("blank_interface did not end free play")
    check(serve.returncode == 0, f"freeplay serve failed:\n{g.log('serve')}")
    import json
    summary = json.loads([line for line in g.log("serve").splitlines() if line.startswith("{")][-1])
    print("serve summary:", {k: summary[k] for k in ["ended_by", "duration_s", "simulated_s"]})
    check(summary["ended_by"] == "signal", f"free play ended by the signal: {summary['ended_by']}")
    check(summary["simulated_s"] < 60, f"start_freeplay cut the 600 s greeting short: {summary['simulated_s']} s")
    others = [c for c in echoes if c != me]
    check(not others, f"serve echoed start_freeplay (from {others})")
    log = g.log("serve")
    check("received sandtray/signals/start_freeplay: applied" in log, "serve logs the applied signal")
    check("look_at: dropped a malformed target (frame 'odom'" in log, "serve logs and drops the malformed target")


def case_cameras(g):
    """The scenario's cameras are rendered and published live under their drivers' topics: the Nao's head camera
    (naoqi_driver front) and an SR300 (camera_purple), JPEG with their CameraInfo."""
    cameras = ("cameras=[{name: CameraTop, rate_hz: 5, width: 160, height: 120}, "
               "{name: camera_purple, rate_hz: 2, width: 192, height: 108}]")
    g.serve("--set", cameras)
    rospy = rospy_client()
    from sensor_msgs.msg import CameraInfo, CompressedImage
    for image_topic, info_topic, size in [
            ("/naoqi_driver/camera/front/image_raw/compressed", "/naoqi_driver/camera/front/camera_info", (160, 120)),
            ("/camera_purple/rgb/image_raw/compressed", "/camera_purple/rgb/camera_info", (192, 108))]:
        image = rospy.wait_for_message(image_topic, CompressedImage, timeout=60)
        info = rospy.wait_for_message(info_topic, CameraInfo, timeout=10)
        check(image.format.endswith("jpeg compressed bgr8") and bytes(image.data[:2]) == b"\xff\xd8",
              f"{image_topic}: a JPEG ({image.format})")
        check((info.width, info.height) == size and info.K[0] > 0, f"{info_topic}: {info.width}x{info.height}")
        print(f"{image_topic}: {len(image.data)} bytes, frame {image.header.frame_id}, K[0] {info.K[0]:.1f}")


def registrations(g):
    """(publishers, subscribers, services) of the master as {name: [nodes]}."""
    state = xmlrpc.client.ServerProxy(g.uri).getSystemState("/freeplay_test")[2]
    return [dict((name, set(nodes)) for name, nodes in part) for part in state]


def wait_master(g, timeout=15.0):
    deadline = time.monotonic() + timeout
    while True:
        try:
            return registrations(g)
        except OSError:
            check(time.monotonic() < deadline, f"the restarted master did not answer on {g.uri}")
            time.sleep(0.2)


def case_restart(g):
    """A master that restarts and nodes that die crash neither side: serve and robot run on while the master is
    away, register again when it is back (the robot moves items through the new master), and each survives the
    other's death."""
    serve = g.serve("--robot", "external", "--set", "protocol.freeplay_cap_s=600")
    robot = g.spawn("robot", [FREEPLAY, "robot", "--policy", "asocial", "--seed", "3"])

    def registered(state):
        pubs, subs, services = state
        return ("/sandtray" in pubs.get("/tf", ()) and "/freeplay_robot" in subs.get("/tf", ())
                and "/freeplay_robot" in pubs.get("/poses", ()) and "/sandtray" in subs.get("/poses", ())
                and "/sandtray" in services.get("/plan_motion", ()))
    deadline = time.monotonic() + 30
    while not registered(registrations(g)):
        check(time.monotonic() < deadline, f"serve and robot did not register: {registrations(g)}")
        time.sleep(0.3)
    time.sleep(3)
    master = g.procs[0][1]
    os.killpg(master.pid, signal.SIGKILL)  # the master dies
    master.wait(timeout=5)
    time.sleep(3)
    check(serve.poll() is None and robot.poll() is None, "serve and robot run on without the master")
    g.spawn("rosmaster_again", ["/usr/bin/rosmaster", "--core", "-p", str(g.port)])
    wait_master(g)
    deadline = time.monotonic() + 15
    while not registered(registrations(g)):
        check(time.monotonic() < deadline, f"serve and robot did not register again: {registrations(g)}")
        time.sleep(0.3)
    print("registered again with the restarted master")
    rospy = rospy_client()  # registers with the new master
    from std_msgs.msg import String
    releases = []
    rospy.Subscriber("sandtray/interaction_events", String, lambda m: releases.append(m.data))
    deadline = time.monotonic() + 60
    while not any(r.startswith("releasing_") for r in releases):
        check(time.monotonic() < deadline, f"no item released by the robot after the restart (events {releases})")
        check(serve.poll() is None and robot.poll() is None, "serve and robot still run")
        time.sleep(0.2)
    print("after the restart, the game released:", [r for r in releases if r.startswith("releasing_")])
    os.killpg(robot.pid, signal.SIGKILL)  # the robot node dies
    robot.wait(timeout=5)
    time.sleep(2)
    check(serve.poll() is None, "serve runs on after the robot node died")
    item_positions(rospy)
    robot = g.spawn("robot_again", [FREEPLAY, "robot", "--policy", "asocial", "--seed", "4"])
    time.sleep(3)
    os.killpg(serve.pid, signal.SIGKILL)  # the sandtray dies
    serve.wait(timeout=5)
    time.sleep(2)
    check(robot.poll() is None, "robot runs on after the sandtray died")
    for line in ["lost the ROS master", "is back: registering again"]:
        check(line in g.log("serve") and line in g.log("robot"), f"serve and robot log '{line}'")


def case_errors():
    """Bad input exits 2 with the allowed values; no master exits 1 with a clear message (no master started)."""
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:1")
    child_child = os.path.join(os.path.dirname(SCENARIO), "child-child.yaml")
    runs = [([FREEPLAY, "serve", child_child, "--robot", "external"], 2, "needs a child-robot scenario"),
            ([FREEPLAY, "robot", "--policy", "nosuch"], 2, "unknown policy 'nosuch' (allowed: asocial"),
            ([FREEPLAY, "serve", SCENARIO, "--master-timeout", "1"], 1, "no ROS master at http://127.0.0.1:1"),
            ([FREEPLAY, "robot", "--master-timeout", "1"], 1, "no ROS master at http://127.0.0.1:1")]
    for argv, status, needle in runs:
        run = subprocess.run(argv, capture_output=True, text=True, timeout=60, env=env)
        check(run.returncode == status and needle in run.stderr,
              f"{argv[1:]}: exit {run.returncode} (want {status}), stderr {run.stderr!r} (want {needle!r})")


def main():
    if CASE == "errors":
        case_errors()
        print("errors: ok")
        return
    cases = {"topics": case_topics, "client": case_client, "robot": case_robot, "rate": case_rate,
             "signals": case_signals, "restart": case_restart, "cameras": case_cameras}
    with Graph() as g:
        try:
            cases[CASE](g)
        except Exception:
            g.stop()
            for name in ["serve", "robot"]:
                path = os.path.join(g.dir, name + ".log")
                if os.path.exists(path):
                    print(f"---- {name} log (last 40 lines) ----")
                    print("\n".join(g.log(name).splitlines()[-40:]))
            raise
    print(f"{CASE}: ok")


if __name__ == "__main__":
    main()
