# hapscene.simulate against `hapscene run --sim-time --log`: the same options give the
# same log, byte for byte; the summary is the one the CLI prints.
import os
import re
import signal
import threading
import time

import numpy as np
import pytest

import hapscene
from conftest import assert_bits_equal, csv_text, read_csv, run_cli

LOG_1D = ["t_s", "x_m", "v_m_per_s", "force_N", "output_N", "duty", "direction"]
TRUTH_1D = ["x_true_m", "v_true_m_per_s", "motor_force_N", "hand_force_N"]
LOG_2D = ["t_s", "x_m", "y_m", "vx_m_per_s", "vy_m_per_s", "force_x_N", "force_y_N", "output_x_N", "output_y_N",
          "duty_1", "direction_1", "duty_2", "direction_2"]


def cli_run(tmp_path, env, *options):
    log = tmp_path / "run.csv"
    cli = run_cli("run", env, "--sim-time", "--quiet", "--no-reload", "--log", log, *options)
    return cli, log.read_text()


def summary_line(stdout, label):
    for line in stdout.splitlines():
        if line.strip().startswith(label):
            return line
    raise AssertionError(f"no '{label}' line in:\n{stdout}")


def check_against_cli(got, cli, log_text, columns):
    header, expected = read_csv(log_text)
    assert header == columns
    assert list(got)[: len(columns)] == columns
    for name in columns:
        assert_bits_equal(got[name], expected[name], name)
    assert csv_text(got, columns) == log_text
    summary = got["summary"]
    assert summary["exit_code"] == cli.returncode
    ticks = re.search(r"ticks +(\d+) in ([0-9.]+) s", cli.stdout)
    assert summary["ticks"] == int(ticks.group(1)) == len(got["t_s"])
    assert f"{summary['device_time_s']:.3f}" == ticks.group(2)
    force = re.search(r"asked ([0-9.]+) N, commanded ([0-9.]+) N \(limit ([0-9.e+]+) N", cli.stdout)
    assert f"{summary['max_abs_requested_N']:.3f}" == force.group(1)
    assert f"{summary['max_abs_output_N']:.3f}" == force.group(2)
    assert f"{summary['force_limit_N']:g}" == force.group(3)
    clamped = re.search(r"time clamped +[0-9.]+ s \((\d+) ticks\); slew-limited (\d+), soft start (\d+), "
                        r"outside workspace (\d+) ticks", cli.stdout)
    assert [summary[k] for k in ("clamped_ticks", "slew_limited_ticks", "soft_start_ticks",
                                 "outside_workspace_ticks")] == [int(g) for g in clamped.groups()]
    first = summary_line(cli.stdout, "")
    assert first.startswith(f"{summary['scene']} ({summary['source']}) on {summary['device']}")
    assert f"hand {summary['hand']}" in first


@pytest.mark.parametrize("env,options,kwargs", [
    ("environments/wall.json", [], {}),
    ("environments/spring.json", ["--hand", "release", "--hold", "20mm", "--duration", "3s"],
     {"hand": "release", "hold": "20mm", "duration": "3s"}),
    ("environments/texture.json", ["--hand", "shake", "--noise", "2", "--seed", "7", "--start", "5 mm"],
     {"hand": "shake", "noise": 2, "seed": 7, "start": 0.005}),
    ("environments/damper.json", ["--hand-stiffness", "400", "--hand-damping", "1", "--duration", "0.5"],
     {"hand_stiffness": 400, "hand_damping": 1.0, "duration": 0.5}),
    ("scripts/mass_spring.lua", ["--hand", "release", "--release", "0.2s", "--duration", "1s"],
     {"hand": "release", "release": "0.2 s", "duration": 1}),
])
def test_simulate_1d_is_the_cli_log(tmp_path, env, options, kwargs):
    cli, log_text = cli_run(tmp_path, env, *options)
    got = hapscene.simulate(env, **kwargs)
    check_against_cli(got, cli, log_text, LOG_1D)
    assert list(got)[len(LOG_1D):] == TRUTH_1D + ["summary"]
    assert got["direction"].dtype == np.int8


def test_simulate_takes_a_loaded_scene_and_is_deterministic():
    scene = hapscene.load("environments/wall.json")
    a = hapscene.simulate(scene, duration=0.5)
    b = hapscene.simulate("environments/wall.json", duration=0.5)
    for name in LOG_1D + TRUTH_1D:
        assert_bits_equal(a[name], b[name], name)
    # The truth is the plant's: the host's measurement is within a sensor count of it.
    assert np.max(np.abs(a["x_m"] - a["x_true_m"])) < 1e-4
    assert np.any(a["hand_force_N"] != 0.0)


def test_simulate_hil_is_the_cli_log(tmp_path):
    cli, log_text = cli_run(tmp_path, "environments/wall.json", "--device", "hil", "--duration", "0.5")
    if cli.returncode == 2 and "no firmware-in-the-loop" in cli.stderr:
        with pytest.raises(hapscene.InputError, match="no firmware-in-the-loop"):
            hapscene.simulate("environments/wall.json", device="hil", duration=0.5)
        pytest.skip("this build has no firmware-in-the-loop")
    got = hapscene.simulate("environments/wall.json", device="hil", duration=0.5)
    check_against_cli(got, cli, log_text, LOG_1D)
    assert got["summary"]["device"] == "hil:hapkit3"
    assert got["summary"]["device_report"] != ""


@pytest.mark.parametrize("env,options,kwargs", [
    ("environments/planar/haplink_box_inside.json", ["--duration", "0.5s", "--hand", "circle"],
     {"duration": "0.5s", "hand": "circle"}),
    ("environments/planar/haplink_maze.json", ["--duration", "0.4", "--hand", "line"],
     {"duration": 0.4, "hand": "line"}),
    ("environments/planar/haplink_vortex.json", ["--duration", "0.3", "--hand", "hold", "--hold", "0.01,0.1"],
     {"duration": 0.3, "hand": "hold", "hold": (0.01, 0.1)}),
])
def test_simulate_2d_is_the_cli_log(tmp_path, env, options, kwargs):
    cli, log_text = cli_run(tmp_path, env, *options)
    got = hapscene.simulate(env, **kwargs)
    check_against_cli(got, cli, log_text, LOG_2D)
    assert "x_true_m" in got and "hand_force_y_N" in got
    linkage = re.search(r"plant +(\d+) linkage faults", cli.stdout)
    assert got["summary"]["plant_linkage_faults"] == int(linkage.group(1))


@pytest.mark.parametrize("device,returned", [("", "1e308"), ('"device": "haplink", ', "1e308, 1e308")])
def test_a_non_finite_force_fails_the_run_as_in_the_cli(tmp_path, device, returned):
    # Two scripts whose finite forces sum past the largest double: the safety stage zeroes
    # every tick, and the run fails (exit code 1) in Python as in the CLI, whatever its axes.
    (tmp_path / "huge.lua").write_text(f"function force(s) return {returned} end\n")
    env = tmp_path / "overflow.json"
    env.write_text('{' + device + '"effects": [{"type": "script", "file": "huge.lua"}, '
                   '{"type": "script", "file": "huge.lua"}]}')
    cli = run_cli("run", env, "--sim-time", "--quiet", "--no-reload", "--duration", "50ms")
    summary = hapscene.simulate(str(env), duration="50ms")["summary"]
    assert cli.returncode == 1
    assert summary["nonfinite_faults"] == 50
    assert summary["faulted"] is True and summary["exit_code"] == 1


def test_simulate_errors_are_the_cli_ranges():
    with pytest.raises(hapscene.InputError, match=r"^hapscene.simulate: duration: must be in \(0, 86400\] s, got 0 s$"):
        hapscene.simulate("environments/wall.json", duration=0)
    with pytest.raises(hapscene.InputError, match=r'hand: unknown motion "wave"'):
        hapscene.simulate("environments/wall.json", hand="wave")
    with pytest.raises(hapscene.InputError, match=r"hold: .*unknown unit|hold: "):
        hapscene.simulate("environments/wall.json", hold="3 parsecs")
    with pytest.raises(hapscene.InputError, match=r'device: "serial:/dev/null"'):
        hapscene.simulate("environments/wall.json", device="serial:/dev/null")
    with pytest.raises(hapscene.InputError, match=r"noise: not yet for a 2-DOF"):
        hapscene.simulate("environments/planar/haplink_box_inside.json", noise=1)
    with pytest.raises(hapscene.InputError, match=r"at most 4194304 are kept"):
        hapscene.simulate("environments/wall.json", duration=7200)


def test_the_gil_is_released_while_the_engine_runs():
    # The main thread keeps taking timestamps while another thread is inside simulate();
    # with the GIL held for the call, none could fall in the middle of it.
    window = {}
    done = threading.Event()

    def work():
        window["start"] = time.perf_counter()
        hapscene.simulate("environments/wall.json", duration=60)
        window["end"] = time.perf_counter()
        done.set()

    stamps = []
    thread = threading.Thread(target=work)
    thread.start()
    while not done.is_set():
        stamps.append(time.perf_counter())
        time.sleep(0)
    thread.join()
    start, end = window["start"], window["end"]
    assert end - start > 0.02, "the run is too short to tell"
    middle = [t for t in stamps if start + 0.25 * (end - start) < t < start + 0.75 * (end - start)]
    assert len(middle) > 10


def test_ctrl_c_stops_a_long_run():
    # SIGINT during a run of 3000 s of device time (half a minute of work): the run stops
    # at its next tick and simulate raises KeyboardInterrupt, as Python code would.
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.perf_counter()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        hapscene.simulate("environments/wall.json", duration=3000)
    timer.join()
    assert time.perf_counter() - started < 10.0
    # The module still works afterwards.
    assert len(hapscene.simulate("environments/wall.json", duration=0.1)["t_s"]) == 100
