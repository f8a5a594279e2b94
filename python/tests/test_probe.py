# Scene.probe against `hapscene probe`: the same points give the same CSV, byte for byte.
import numpy as np
import pytest

import hapscene
from conftest import assert_bits_equal, csv_text, read_csv, run_cli

CASES_1D = [
    ("environments/wall.json", "-10mm:30mm:0.5mm", None),
    ("environments/texture.json", "0:0.03:0.0005", "0.1"),
    ("environments/wall_corridor.json", "-60mm:60mm:1mm", "-0.05"),
    ("scripts/bumps.lua", "-0.03:0.03:0.001", None),
    ("environments/spring.json", "-1:1:0.125", None),  # beyond the workspace: output 0
]


@pytest.mark.parametrize("env,x_range,v", CASES_1D)
def test_probe_1d_is_the_cli_probe(env, x_range, v):
    args = ["probe", env, "--x", x_range] + (["--v", v] if v else [])
    cli = run_cli(*args, check_code=0)
    header, expected = read_csv(cli.stdout)
    assert header == ["x_m", "v_m_per_s", "force_N", "output_N"]
    scene = hapscene.load(env)
    got = scene.probe(expected["x_m"], v=float(v) if v else 0.0)
    assert list(got) == header
    for name in header:
        assert got[name].dtype == np.float64
        assert_bits_equal(got[name], expected[name], name)
    assert csv_text(got, header) == cli.stdout


def test_probe_keeps_the_shape_and_takes_units():
    scene = hapscene.load("environments/wall.json")
    grid = np.linspace(0.0, 0.02, 12).reshape(3, 4)
    got = scene.probe(grid, v="10 mm/s")
    assert got["force_N"].shape == (3, 4)
    assert got["v_m_per_s"][0, 0] == 0.01
    assert scene.probe(0.02)["force_N"] == pytest.approx(-5.0)


@pytest.mark.parametrize("env", ["environments/planar/haplink_box_inside.json",
                                 "environments/planar/haplink_vortex.json"])
def test_probe_2d_is_the_cli_probe(env):
    cli = run_cli("probe", env, "--x", "-0.04:0.04:0.005", "--y", "0.06:0.14:0.005", "--v", "0.01,-0.02",
                  check_code=0)
    header, expected = read_csv(cli.stdout)
    scene = hapscene.load(env)
    got = scene.probe(expected["x_m"], expected["y_m"], vx=0.01, vy=-0.02)
    assert list(got) == header
    for name in header:
        assert_bits_equal(got[name], expected[name], name)
    assert csv_text(got, header) == cli.stdout


def test_probe_grid_from_meshgrid():
    scene = hapscene.load("environments/planar/haplink_box_inside.json")
    x, y = np.meshgrid(np.linspace(-0.02, 0.02, 5), np.linspace(0.08, 0.12, 4))
    got = scene.probe(x, y)
    assert got["force_x_N"].shape == (4, 5)


def test_probe_errors_name_the_value():
    scene = hapscene.load("environments/wall.json")
    with pytest.raises(hapscene.InputError, match=r"Scene.probe: x\[1\]: must be in \[-1000, 1000\] m, got 2000"):
        scene.probe([0.0, 2000.0])
    with pytest.raises(hapscene.InputError, match=r"Scene.probe: v: must be in"):
        scene.probe([0.0], v=1e9)
    with pytest.raises(hapscene.InputError, match=r"only for a 2-DOF"):
        scene.probe([0.0], [0.0])
    with pytest.raises(hapscene.InputError, match=r"more than 1000000 points"):
        scene.probe(np.zeros(1_000_001))
    planar = hapscene.load("environments/planar/haplink_box_inside.json")
    with pytest.raises(hapscene.InputError, match=r"y is required"):
        planar.probe([0.0])


def test_script_faults_are_warnings(tmp_path):
    env = tmp_path / "faulty.lua"
    env.write_text("function force(s) if s.x > 0.01 then error('too far') end return 0 end\n")
    cli = run_cli("probe", env, "--x", "0:0.02:0.005", check_code=1)
    _, expected = read_csv(cli.stdout)
    scene = hapscene.load(env)
    with pytest.warns(hapscene.ScriptFaultWarning) as warned:
        got = scene.probe(expected["x_m"])
    assert_bits_equal(got["force_N"], expected["force_N"], "force_N")
    assert [str(w.message) for w in warned] == cli.stderr.splitlines()
    # Where the script faulted: NaN (the CSV's empty fields), never the 0 N it answered.
    faulted = expected["x_m"] > 0.01
    assert faulted.any() and np.isnan(got["force_N"][faulted]).all() and np.isnan(got["output_N"][faulted]).all()
    assert not np.isnan(got["force_N"][~faulted]).any()


def test_a_flood_of_distinct_faults_is_bounded_as_the_cli_bounds_it(tmp_path):
    env = tmp_path / "distinct.lua"
    env.write_text("function force(s)\n  if s.x > 0.001 then error(\"at \" .. math.floor(s.x * 1000 + 0.3) .. \" mm\") end\n"
                   "  return 0\nend\n")
    cli = run_cli("probe", env, "--x", "-10mm:40mm:0.25mm", check_code=1)
    _, expected = read_csv(cli.stdout)
    with pytest.warns(hapscene.ScriptFaultWarning) as warned:
        hapscene.load(env).probe(expected["x_m"])
    lines = [str(w.message) for w in warned]
    assert lines == cli.stderr.splitlines()
    assert len(lines) == 21 and lines[-1].startswith("... and script faults with other messages (only the 20 first")
