# hapscene.validate against `hapscene validate --report`: the same JSON; hapscene.test
# against `hapscene test`.
import json

import pytest

import hapscene
from conftest import run_cli


def without_timing(report):
    """The report without what measures this machine's CPU time (the tick compute time
    and its check's value), which differs from run to run; everything else is simulated."""
    report = json.loads(json.dumps(report))
    for scenario in report["scenarios"]:
        metrics = scenario.get("metrics") or {}
        assert set(metrics.pop("tick_compute_s", {"p50": 0, "p99": 0, "max": 0})) == {"p50", "p99", "max"}
        for check in scenario.get("checks", []):
            if check["name"] == "tick_compute":
                check["value"] = check["detail"] = None
    return report


@pytest.mark.parametrize("env,options,kwargs", [
    ("environments/wall.json", [], {}),
    ("environments/texture.json", ["--scenario", "sweep,shake", "--noise", "1", "--seed", "3"],
     {"scenarios": ["sweep", "shake"], "noise": 1, "seed": 3}),
    ("environments/spring.json", ["--hand-stiffness", "300", "--hand-mass", "30 g", "--start", "3mm",
                                  "--scenario", "free,release"],
     {"hand_stiffness": 300, "hand_mass": "30 g", "start": "3mm", "scenarios": "free,release"}),
    ("scripts/bumps.lua", ["--scenario", "sweep"], {"scenarios": "sweep"}),
    ("environments/planar/haplink_box_inside.json", ["--scenario", "press,swipe"], {"scenarios": ["press", "swipe"]}),
    ("environments/planar/haplink_circle_outside.json", ["--scenario", "free", "--start", "0.01,0.1"],
     {"scenarios": "free", "start": (0.01, 0.1)}),
])
def test_validate_is_the_cli_report(tmp_path, env, options, kwargs):
    report_path = tmp_path / "report.json"
    cli = run_cli("validate", env, "--quiet", "--report", report_path, *options)
    assert cli.returncode in (0, 1), cli.stderr
    expected = json.loads(report_path.read_text())
    got = hapscene.validate(env, **kwargs)
    assert without_timing(got) == without_timing(expected)
    assert got["pass"] == (cli.returncode == 0)
    # A loaded Scene gives the same report.
    assert without_timing(hapscene.validate(hapscene.load(env), **kwargs)) == without_timing(expected)


def test_validate_error_from_the_engine_is_the_cli_message():
    cli = run_cli("validate", "environments/spring.json", "--scenario", "free", "--start", "6mm", check_code=2)
    with pytest.raises(hapscene.InputError) as caught:
        hapscene.validate("environments/spring.json", scenarios="free", start="6mm")
    assert cli.stderr == f"error: {caught.value}\n"


def test_validate_errors_read_by_the_kind_are_the_cli_messages():
    # One reading of the scenarios, the start and the noise for every number of axes
    # (engine/harness/validate_kind.hpp): Python says what the CLI says, prefixed.
    planar = "environments/planar/haplink_box_inside.json"
    for args, kwargs, cli_prefix, py_prefix in [
        (["--scenario", "swep"], {"scenarios": "swep"}, "--scenario: ", "scenarios: "),
        (["--scenario", "hold,hold"], {"scenarios": "hold,hold"}, "--scenario: ", "scenarios: "),
        (["--noise", "1"], {"noise": 1}, "--", ""),
    ]:
        cli = run_cli("validate", planar, *args, check_code=2)
        with pytest.raises(hapscene.InputError) as caught:
            hapscene.validate(planar, **kwargs)
        said = str(caught.value)
        assert said.startswith("hapscene.validate: " + py_prefix), said
        problem = said[len("hapscene.validate: " + py_prefix):]
        assert cli.stderr == f"error: hapscene validate: {cli_prefix}{problem}\n"
    with pytest.raises(hapscene.InputError, match=r'unknown scenario "swep" for a 2-DOF environment \(one of sweep, press, swipe'):
        hapscene.validate(planar, scenarios="swep")


def test_validate_errors():
    with pytest.raises(hapscene.InputError, match=r'unknown scenario "swep" \(one of .*did you mean "sweep"\?\)'):
        hapscene.validate("environments/wall.json", scenarios="swep")
    with pytest.raises(hapscene.InputError, match=r'"sweep" is listed twice'):
        hapscene.validate("environments/wall.json", scenarios=["sweep", "sweep"])
    with pytest.raises(hapscene.InputError, match=r"hapscene.validate: hand_mass: must be in"):
        hapscene.validate("environments/wall.json", hand_mass=-1)


def test_test_is_the_cli_test(tmp_path):
    bad = tmp_path / "bad.test.json"
    bad.write_text('{"environment": "nowhere.json"}')
    specs = ["environments/wall.test.json", "scripts", str(bad)]
    cli = run_cli("test", *specs)
    assert cli.returncode == 2
    results = hapscene.test(specs)
    lines = [line for line in cli.stdout.splitlines() if line.startswith(("PASS", "FAIL"))]
    assert len(results) == len(lines)
    for result, line in zip(results, lines):
        assert line.startswith(("PASS " if result["pass"] else "FAIL ") + result["spec"])
        if result["error"] is None:
            assert line.endswith(f"({len(result['outcomes'])} expectations)")
        else:
            assert f"error: {result['error']}" in cli.stderr
    assert results[0]["spec"] == "environments/wall.test.json" and results[0]["pass"]
    assert results[-1]["error"] is not None
