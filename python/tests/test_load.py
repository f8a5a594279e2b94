# hapscene.load and hapscene.Scene: what a loaded environment says about itself, and
# invalid input raising hapscene.InputError with the command line's message.
import json

import pytest

import hapscene
from conftest import run_cli


def test_scene_describes_the_environment():
    scene = hapscene.load("environments/wall.json")
    assert scene.name == "wall"
    assert scene.rate == 1000.0
    assert scene.axes == 1
    assert scene.device == "hapkit3"
    assert scene.path == "environments/wall.json"
    assert scene.effects == [{"type": "wall", "stiffness_N_per_m": 500.0, "position_m": 0.01, "solid_above": True}]
    assert scene.parameters == {"effects[0].stiffness_N_per_m": 500.0, "effects[0].position_m": 0.01}
    assert "wall" in repr(scene)


def test_script_parameters_and_planar_effects():
    bumps = hapscene.load("scripts/bumps.lua")
    assert bumps.effects[0]["type"] == "script"
    assert bumps.effects[0]["name"] == "scripts/bumps.lua"
    assert any(key.startswith("effects[0].params.") for key in bumps.parameters)
    planar = hapscene.load("environments/planar/haplink_box_inside.json")
    assert planar.axes == 2
    assert planar.effects[0]["type"] == "box"
    assert len(planar.effects[0]["min_m"]) == 2


@pytest.mark.parametrize("text", [
    '{"effects": [{"type": "wall", "position": "10 mm", "stiffness": "1e99 N/m"}]}',
    '{"effects": [{"type": "sprung", "stiffness": 100}]}',
    '{"effects": [}',
    '{"rate_hz": 5, "effects": []}',
])
def test_input_error_carries_the_cli_message(tmp_path, text):
    bad = tmp_path / "bad.json"
    bad.write_text(text)
    cli = run_cli("probe", bad, "--x", "0:0.01:0.01", check_code=2)
    with pytest.raises(hapscene.InputError) as caught:
        hapscene.load(bad)
    assert isinstance(caught.value, ValueError)
    assert cli.stderr == f"error: {caught.value}\n"


def test_missing_file():
    with pytest.raises(hapscene.InputError) as caught:
        hapscene.load("environments/no_such_file.json")
    cli = run_cli("probe", "environments/no_such_file.json", "--x", "0:0.01:0.01", check_code=2)
    assert cli.stderr == f"error: {caught.value}\n"


def test_help_and_version():
    assert "duration" in hapscene.simulate.__doc__
    assert "passivity" in hapscene.validate.__doc__
    assert hapscene.__version__ == run_cli("version", check_code=0).stdout.split()[1]


def test_parameters_are_read_only():
    # A Scene is immutable: assigning a parameter raises instead of changing a copy.
    scene = hapscene.load("environments/wall.json")
    with pytest.raises(TypeError):
        scene.parameters["effects[0].stiffness_N_per_m"] = 900.0
    assert scene.parameters["effects[0].stiffness_N_per_m"] == 500.0


def test_loads_takes_a_dict_or_text_and_sweeps_without_files():
    with open("environments/wall.json") as f:
        document = json.load(f)
    forces = []
    for stiffness in (200, 400, 800):
        document["effects"][0]["stiffness"] = "%d N/m" % stiffness
        scene = hapscene.loads(document)
        assert scene.parameters["effects[0].stiffness_N_per_m"] == stiffness
        forces.append(float(scene.probe(0.02)["force_N"]))
    assert forces == pytest.approx([-2.0, -4.0, -8.0])  # 10 mm into the wall at 10 mm
    text = hapscene.loads(json.dumps(document), name="swept wall")
    assert text.path == "swept wall" and text.effects == scene.effects
    # Scripts and planar devices from base_dir, as a file in that folder would find them.
    planar = hapscene.loads('{"device": "haplink", "effects": [{"type": "script", "file": "planar/box.lua"}]}',
                            base_dir="scripts")
    assert planar.axes == 2 and planar.effects[0]["type"] == "script"


@pytest.mark.parametrize("source,message", [
    ({"effects": [{"type": "wall", "position": "10 mm", "stiffness": "1e99 N/m"}]},
     "<string>: /effects/0/stiffness: must be in"),
    ('{"effects": [}', "<string>:"),
    ({"effects": [{"type": "spring", "stiffness": float("nan")}]}, "<string>: not JSON: Out of range float values"),
    (42, "hapscene.loads: expected a JSON string or a dict, got int"),
])
def test_loads_errors_are_located(source, message):
    with pytest.raises(hapscene.InputError) as raised:
        hapscene.loads(source)
    assert message in str(raised.value)
