"""Experiments from Python: load and validate scenarios and suites, run them, read their run folders."""

import csv
import gzip
import json
import os

from . import _freeplay


def overrides_list(overrides=(), **set_values):
    """``--set``-style overrides as ``KEY.PATH=VALUE`` strings, from strings, a dict or keyword arguments
    (``robot__policy="idle"`` stands for ``robot.policy=idle``); non-string values are written as YAML."""
    items = []
    if isinstance(overrides, dict):
        overrides = list(overrides.items())
    elif isinstance(overrides, str):
        overrides = [overrides]
    for entry in list(overrides) + [(k.replace("__", "."), v) for k, v in set_values.items()]:
        if isinstance(entry, str):
            items.append(entry)
        else:
            key, value = entry
            items.append(f"{key}={value if isinstance(value, str) else json.dumps(value)}")
    return items


def load(file, overrides=(), **set_values):
    """Loads and validates a scenario or suite file with overrides, as ``freeplay run|suite`` would.

    Returns a dict: name, description, file, is_suite, total_episodes and variants (each: id, name, condition,
    episodes, seed, policy, config_hash and the validated scenario with its defaults). Raises
    :class:`freeplay.InputError` (file, line, column, key, allowed) on bad input.
    """
    return _freeplay._load(os.fspath(file), overrides_list(overrides, **set_values))


def validate(file, overrides=(), **set_values):
    """Validates a scenario or suite file with overrides; raises :class:`freeplay.InputError` when it is bad."""
    load(file, overrides, **set_values)


def run(file, *, episodes=None, seed=None, jobs=1, overrides=(), out=None, events="auto", quiet=True, shard=None,
        **set_values):
    """Runs a scenario or suite like ``freeplay run|suite`` (the same engine, the same run folder) and returns a
    :class:`Run`.

    ``episodes`` and ``seed`` override every scenario's; ``jobs`` episodes run in parallel on C++ threads (the GIL
    is released; Python policies take it only while they decide); ``out`` is the run folder (default: a new
    ``runs/<UTC time>-<name>``; an existing one is resumed); ``events`` is auto, all, gz or none; ``shard`` is
    "I/N". Ctrl-C keeps the finished episodes and raises KeyboardInterrupt.
    """
    out = _freeplay._run(os.fspath(file), overrides_list(overrides, **set_values), episodes, seed, jobs,
                         os.fspath(out) if out is not None else "", events, quiet, shard or "")
    return Run(out)


class Run:
    """A run folder: the per-episode records, the summary and the event logs, as Python data."""

    def __init__(self, directory):
        """Reads the run folder ``directory`` (as written by ``freeplay run|suite`` or :func:`run`)."""
        self.dir = os.fspath(directory)

    def __repr__(self):
        return f"Run({self.dir!r})"

    @property
    def records(self):
        """The finished episodes: one dict per line of episodes.jsonl, in variant and episode order."""
        path = os.path.join(self.dir, "episodes.jsonl")
        if not os.path.exists(path):
            return []
        with open(path, encoding="utf-8") as f:
            return [json.loads(line) for line in f if line.strip()]

    @property
    def summary(self):
        """summary.csv as a list of dicts (variant, condition, policy, metric, n, mean, sd, median, ci_low,
        ci_high; numbers as floats)."""
        path = os.path.join(self.dir, "summary.csv")
        with open(path, encoding="utf-8", newline="") as f:
            rows = list(csv.DictReader(f))
        for row in rows:
            for key in ("n", "mean", "sd", "median", "ci_low", "ci_high"):
                if row.get(key) not in (None, ""):
                    row[key] = float(row[key])
        return rows

    @property
    def summary_markdown(self):
        """summary.md as text."""
        with open(os.path.join(self.dir, "summary.md"), encoding="utf-8") as f:
            return f.read()

    @property
    def info(self):
        """run.json: what was run and whether it finished."""
        with open(os.path.join(self.dir, "run.json"), encoding="utf-8") as f:
            return json.load(f)

    def events(self, episode_id):
        """The event log of episode ``episode_id`` (e.g. "pinsoro-cr-0003") as a list of dicts."""
        return [json.loads(line) for line in self.events_text(episode_id).splitlines() if line.strip()]

    def events_text(self, episode_id):
        """The event log of an episode as JSON Lines text (events/<id>.jsonl or .jsonl.gz)."""
        path = os.path.join(self.dir, "events", f"{episode_id}.jsonl")
        if os.path.exists(path):
            with open(path, encoding="utf-8") as f:
                return f.read()
        with gzip.open(path + ".gz", "rt", encoding="utf-8") as f:
            return f.read()

    def records_frame(self):
        """The records as a pandas DataFrame (nested fields flattened with dots); needs python3-pandas."""
        import pandas
        return pandas.json_normalize(self.records)

    def summary_frame(self):
        """summary.csv as a pandas DataFrame; needs python3-pandas."""
        import pandas
        return pandas.read_csv(os.path.join(self.dir, "summary.csv"))


def compare(run_a, run_b=None, *, variants=(), metrics=(), program=None, extra_args=()):
    """Compares two run folders (or two variants of one) with ``freeplay compare --json``: the command line's own
    engine and numbers (paired bootstrap CIs, Holm-adjusted p-values). Returns its JSON as Python data.

    ``variants``: up to two variant ids (``--variant``); ``metrics``: names or globs (``--metric``); ``program``:
    the ``freeplay`` executable (default: $FREEPLAY_PROGRAM, else build/freeplay beside this package, else
    ``freeplay`` on PATH).
    """
    import shutil
    import subprocess
    if program is None:
        beside = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "freeplay")
        program = os.environ.get("FREEPLAY_PROGRAM") or (beside if os.path.exists(beside) else shutil.which("freeplay"))
    if not program:
        raise FileNotFoundError("no freeplay program: build it (scripts/build.sh) or pass program=")
    args = [os.fspath(program), "compare", os.fspath(run_a)] + ([os.fspath(run_b)] if run_b is not None else [])
    for v in variants:
        args += ["--variant", v]
    for m in metrics:
        args += ["--metric", m]
    done = subprocess.run(args + ["--json", *extra_args], capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"freeplay compare failed ({done.returncode}): {done.stderr.strip()}")
    return json.loads(done.stdout)
