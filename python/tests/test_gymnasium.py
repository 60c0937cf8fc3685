"""freeplay.Env with and without gymnasium. Debian 12 has no gymnasium, so the gymnasium path is tested against a
minimal stand-in package (below) that has only the names freeplay uses: it shows that freeplay builds its spaces
and registers itself, not that the real gymnasium accepts them."""

import json
import os
import subprocess
import sys
import textwrap

import freeplay
from conftest import SHORT

STUB_INIT = '''
from . import spaces
registry = {}


def register(id, entry_point, **kwargs):
    registry[id] = {"entry_point": entry_point, **kwargs}


def make(id, **kwargs):
    module, name = registry[id]["entry_point"].split(":")
    return getattr(__import__(module, fromlist=[name]), name)(**kwargs)
'''

STUB_SPACES = '''
class Space:
    def __init__(self, *args, **kwargs):
        self.args, self.kwargs = args, kwargs


class Box(Space):
    pass


class Discrete(Space):
    pass


class MultiBinary(Space):
    pass


class Text(Space):
    pass


class Sequence(Space):
    pass


class Dict(Space):
    def __getitem__(self, key):
        return self.args[0][key]
'''

CHECK = '''
import json, sys
import gymnasium, freeplay
scenario, overrides = sys.argv[1], json.loads(sys.argv[2])
env = gymnasium.make("freeplay/Sandtray-v0", scenario=scenario, overrides=overrides)
obs, info = env.reset(seed=2)
vec = freeplay.VecEnv(1, scenario, overrides)
print(json.dumps({
    "registered": gymnasium.registry["freeplay/Sandtray-v0"],
    "env": type(env).__name__,
    "observation": type(env.observation_space).__name__,
    "items": type(env.observation_space["items"]).__name__,
    "position": env.observation_space["self"]["arm_reach_centre"].kwargs["shape"],
    "action": type(env.action_space).__name__,
    "vec_single": type(vec.single_action_space).__name__,
    "vec_observation": type(vec.single_observation_space).__name__,
    "vec_pose": vec.single_observation_space["item_pose"].kwargs["shape"],
    "layout": sorted(env.observation_layout),
    "t": obs.t,
}))
'''


def test_without_gymnasium_the_spaces_are_plain_descriptions(scenario):
    try:
        import gymnasium  # noqa: F401
    except ImportError:
        pass
    else:
        import pytest
        pytest.skip("gymnasium is installed here: this test is for the machines without it (Debian 12)")
    env = freeplay.Env(scenario, SHORT)
    assert env.observation_space is not None and isinstance(env.observation_space, dict)
    assert env.observation_space == freeplay.observation_space() == env.observation_layout
    assert isinstance(env.action_space, dict) and "MoveItem" in env.action_space


def test_with_gymnasium_the_spaces_are_gymnasium_spaces_and_the_env_is_registered(scenario, tmp_path):
    package = tmp_path / "gymnasium"
    package.mkdir()
    (package / "__init__.py").write_text(textwrap.dedent(STUB_INIT))
    (package / "spaces.py").write_text(textwrap.dedent(STUB_SPACES))
    environment = dict(os.environ)
    environment["PYTHONPATH"] = os.pathsep.join([str(tmp_path), *filter(None, [os.environ.get("PYTHONPATH")])])
    done = subprocess.run([sys.executable, "-c", CHECK, str(scenario), json.dumps(SHORT)], env=environment,
                          capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout)
    assert seen["registered"] == {"entry_point": "freeplay.env:Env", "disable_env_checker": True}
    assert seen["env"] == "Env"
    assert (seen["observation"], seen["items"], seen["action"], seen["vec_single"]) == (
        "Dict", "Sequence", "Sequence", "Sequence")
    assert seen["position"] == [2]
    assert seen["vec_observation"] == "Dict" and seen["vec_pose"][1] == 3
    assert {"t", "items", "self"} <= set(seen["layout"])
    assert seen["t"] >= 0.0
