"""Loads a synthetic PInSoRo dataset with python3 + yaml + csv (as docs/dataset.md shows) and checks it against the
run it came from: layout, experiment.yaml keys, bag description, md5 files, audio, the 449-column tables and their
label shares."""
import csv
import glob
import hashlib
import json
import os
import sys

import yaml

root, expected = sys.argv[1], int(sys.argv[2])
errors = []
# The coding scheme's labels per axis (PInSoRo tools/timeline.py).
AXES = {"task_engagement": ["goaloriented", "aimless", "adultseeking", "noplay"],
        "social_engagement": ["solitary", "onlooker", "parallel", "associative", "cooperative"],
        "social_attitude": ["prosocial", "adversarial", "assertive", "frustrated", "passive"]}
sessions = sorted(glob.glob(os.path.join(root, "data", "*", "experiment.yaml")))
if len(sessions) != expected:
    errors.append("%d sessions, want %d" % (len(sessions), expected))
records = {}
for line in open(os.path.join(root, "run", "episodes.jsonl")):
    r = json.loads(line)
    records[r["episode_id"]] = r
index = {row["session"]: row for row in csv.DictReader(open(os.path.join(root, "data", "sessions.csv")))}

for path in sessions:
    folder = os.path.dirname(path)
    name = os.path.basename(folder)
    if len(name) != 23 or name[4] != "-" or name[10] != "-" or not name[11:].isdigit():
        errors.append("folder name %s is not YYYY-MM-DD-HHMMSSffffff" % name)
    experiment = yaml.safe_load(open(path))
    for key in ("timestamp", "condition", "purple-participant", "markers", "notes", "extras"):
        if key not in experiment:
            errors.append("%s: no %s" % (path, key))
    condition = experiment["condition"]
    if (condition == "childchild") != ("yellow-participant" in experiment):
        errors.append("%s: yellow participant and condition disagree" % path)
    bag = yaml.safe_load(open(os.path.join(folder, "freeplay.bag.yaml")))
    topics = {t["topic"]: t for t in bag["topics"]}
    if "frequency" not in topics["/tf"]:
        errors.append("%s: no /tf frequency" % name)
    # The md5 files the dataset ships (free-play-sandbox.md §4.3), each naming its file's digest.
    for shipped in ["freeplay.bag", "freeplay.poses.json"] + [os.path.basename(t) for t in glob.glob(os.path.join(folder, "pinsoro-*.csv"))]:
        digest = hashlib.md5(open(os.path.join(folder, shipped), "rb").read()).hexdigest()
        md5 = os.path.join(folder, shipped + ".md5")
        if not os.path.exists(md5) or open(md5).read().split()[0] != digest:
            errors.append("%s: %s.md5 does not match" % (name, shipped))
    for camera in ("purple", "yellow"):
        for ext in ("mp3", "wav"):
            audio = os.path.join(folder, "audio", "freeplay_camera_%s_audio.%s" % (camera, ext))
            if not os.path.exists(audio) or os.path.getsize(audio) == 0:
                errors.append("%s: no %s" % (name, os.path.relpath(audio, folder)))
    annotations = glob.glob(os.path.join(folder, "freeplay.annotations.*.yaml"))
    if len(annotations) != 1 or "purple" not in yaml.safe_load(open(annotations[0])):
        errors.append("%s: no annotation file with purple" % name)
    episode = index[name]["episode_id"]
    tables = glob.glob(os.path.join(folder, "pinsoro-*.csv"))
    with open(tables[0]) as f:
        rows = list(csv.DictReader(f))
    header = open(tables[0]).readline().strip().split(",")
    if len(header) != 449 or header[0] != "timestamp" or header[-1] != "yellow_child_social_attitude":
        errors.append("%s: header has %d columns" % (name, len(header)))
    record = records[episode]
    seats = ["purple", "yellow"] if condition == "childchild" else ["purple"]
    for seat in seats:
        for axis in ("task_engagement", "social_engagement", "social_attitude"):
            column = "%s_child_%s" % (seat, axis)
            counts = {}
            for row in rows:
                counts[row[column]] = counts.get(row[column], 0) + 1
            shares = record["metrics"]["label_share"][seat]
            for label in set(counts) | set(AXES[axis]):
                table_share = counts.get(label, 0) / len(rows)
                run_share = shares.get(label, 0.0)
                if abs(table_share - run_share) > 3.0 / len(rows):
                    errors.append("%s %s %s: table %.4f vs run %.4f" % (name, seat, label, table_share, run_share))
    if condition == "childrobot" and any(row["yellow_child_task_engagement"] for row in rows):
        errors.append("%s: yellow labels in a child-robot session" % name)

print("\n".join(errors) if errors else "dataset loads; label shares equal the run's")
sys.exit(1 if errors else 0)
