#!/usr/bin/python3
"""The JSON Schemas in schemas/ against what hapscene reads and writes (ctest json_schemas).

    /usr/bin/python3 tests/schemas/check_schemas.py SOURCE_DIR HAPSCENE

1. The schemas are valid draft 2020-12 schemas and equal what schemas/generate_schemas.py
   writes (so an edit goes through the generator).
2. Every shipped environment (1-D and 2-D), device profile and test spec is valid against
   its schema (and a "$schema" it carries names that schema, relative to the file), and so
   are fresh `hapscene validate --report` files of a 1-D and a 2-D scene.
3. Files that are wrong in the ways people get them wrong (a misspelt key, a unit of the
   wrong kind, a missing key, a 1-D form in a 2-D file) are refused by the schema, and the
   environments among them are refused by hapscene too (exit 2), so the schemas are not
   vacuous and agree with the loader.
Exit code 77 (skipped) when this python3 has no jsonschema (Debian: python3-jsonschema).
"""
import copy
import json
import pathlib
import subprocess
import sys
import tempfile

try:
    import jsonschema
except ImportError:
    print("json_schemas: skipped: no jsonschema module for " + sys.executable + " (apt-get install python3-jsonschema)")
    sys.exit(77)

SOURCE = pathlib.Path(sys.argv[1])
HAPSCENE = sys.argv[2]
failures = []


def fail(message):
    failures.append(message)
    print("FAIL " + message)


def load(path):
    return json.loads(pathlib.Path(path).read_text(encoding="utf-8"))


def validator(name):
    schema = load(SOURCE / "schemas" / name)
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema, format_checker=jsonschema.FormatChecker())


def expect_valid(v, instance, what):
    errors = sorted(v.iter_errors(instance), key=lambda e: list(e.absolute_path))
    if errors:
        best = jsonschema.exceptions.best_match(errors)
        fail(f"{what}: refused by its schema at /{'/'.join(map(str, best.absolute_path))}: {best.message[:300]}")


refused = []


def expect_invalid(v, instance, what):
    refused.append(what)
    if v.is_valid(instance):
        fail(f"{what}: accepted by its schema, but it is invalid")


# 1. Up to date, and valid schemas.
with tempfile.TemporaryDirectory() as scratch:
    subprocess.run([sys.executable, str(SOURCE / "schemas" / "generate_schemas.py"), scratch, "--hapscene", HAPSCENE],
                   check=True)
    for generated in sorted(pathlib.Path(scratch).glob("*.schema.json")):
        committed = SOURCE / "schemas" / generated.name
        if not committed.exists() or committed.read_bytes() != generated.read_bytes():
            fail(f"schemas/{generated.name} differs from what schemas/generate_schemas.py writes (run it)")
environment = validator("environment.schema.json")
profile = validator("device-profile.schema.json")
spec = validator("test-spec.schema.json")
report = validator("validate-report.schema.json")


def closed_everywhere(node):
    """The report schema with every object that lists its keys closed to others: a fresh
    report must have no key the schema does not describe."""
    if isinstance(node, dict):
        result = {k: closed_everywhere(v) for k, v in node.items()}
        if "properties" in result and result.get("type") == "object":
            result.setdefault("additionalProperties", False)
        return result
    if isinstance(node, list):
        return [closed_everywhere(v) for v in node]
    return node


strict_report = jsonschema.Draft202012Validator(closed_everywhere(load(SOURCE / "schemas" / "validate-report.schema.json")))

# 2. Every shipped file; a "$schema" it carries names its schema, relative to the file (so
# it resolves in the source tree and in the installed share/hapscene alike).
counts = {"environments": 0, "profiles": 0, "specs": 0, "reports": 0}


def check_shipped(path, v, schema_name, kind):
    instance = load(path)
    relative = path.relative_to(SOURCE)
    expect_valid(v, instance, str(relative))
    named = instance.get("$schema")
    if named is not None and (path.parent / named).resolve() != (SOURCE / "schemas" / schema_name).resolve():
        fail(f"{relative}: \"$schema\": \"{named}\" is not schemas/{schema_name} relative to the file")
    counts[kind] += 1


for path in sorted((SOURCE / "environments").rglob("*.json")):
    if path.name.endswith(".test.json"):
        check_shipped(path, spec, "test-spec.schema.json", "specs")
    elif path.parent.name == "devices":
        check_shipped(path, profile, "device-profile.schema.json", "profiles")
    else:
        check_shipped(path, environment, "environment.schema.json", "environments")
for path in sorted((SOURCE / "scripts").rglob("*.test.json")):
    check_shipped(path, spec, "test-spec.schema.json", "specs")

# A "$schema" key is part of every form.
wall = load(SOURCE / "environments" / "wall.json")
box = load(SOURCE / "environments" / "planar" / "haplink_box_inside.json")
for name, instance in [("wall.json", wall), ("haplink_box_inside.json", box)]:
    expect_valid(environment, {"$schema": "../schemas/environment.schema.json", **instance}, name + " with $schema")
expect_valid(profile, {"$schema": "x", **load(SOURCE / "environments" / "devices" / "hapkit3.json")},
             "hapkit3.json with $schema")
expect_valid(spec, {"$schema": "x", **load(SOURCE / "environments" / "wall.test.json")}, "wall.test.json with $schema")

# Fresh reports of a 1-D and a 2-D scene.
with tempfile.TemporaryDirectory() as scratch:
    for scene in ["environments/wall.json", "environments/planar/haplink_box_inside.json"]:
        out = pathlib.Path(scratch) / (pathlib.Path(scene).stem + ".report.json")
        run = subprocess.run([HAPSCENE, "validate", scene, "--quiet", "--report", str(out)], cwd=SOURCE,
                             capture_output=True, text=True)
        if run.returncode not in (0, 1) or not out.exists():
            fail(f"hapscene validate {scene} --report: exit {run.returncode}: {run.stderr.strip()}")
            continue
        expect_valid(report, load(out), f"validate report of {scene}")
        expect_valid(strict_report, load(out), f"validate report of {scene}, every key described")
        counts["reports"] += 1

# Fresh test results (--json) of a passing spec, a failing one and one that does not load,
# and the same run's JUnit XML, read by Python's XML parser.
results = validator("test-results.schema.json")
strict_results = jsonschema.Draft202012Validator(closed_everywhere(load(SOURCE / "schemas" / "test-results.schema.json")))
with tempfile.TemporaryDirectory() as scratch:
    folder = pathlib.Path(scratch)
    failing = folder / "failing.test.json"
    failing.write_text(json.dumps({"environment": str((SOURCE / "environments" / "spring.json").resolve()),
                                   "forces": [{"x": "10 mm", "force": "9 N"}]}), encoding="utf-8")
    broken = folder / "broken.test.json"
    broken.write_text("{\"environment\": ", encoding="utf-8")
    out, xml_out = folder / "results.json", folder / "results.xml"
    run = subprocess.run([HAPSCENE, "test", "environments/spring.test.json", str(failing), str(broken),
                          "--json", str(out), "--junit", str(xml_out)], cwd=SOURCE, capture_output=True, text=True)
    if run.returncode != 2 or not out.exists() or not xml_out.exists():
        fail(f"hapscene test --json --junit: exit {run.returncode}, expected 2 and both files: {run.stderr.strip()}")
    else:
        expect_valid(results, load(out), "test results")
        expect_valid(strict_results, load(out), "test results, every key described")
        verdicts = [s["verdict"] for s in load(out)["specs"]]
        if verdicts != ["pass", "fail", "invalid"]:
            fail(f"test results: verdicts {verdicts}, expected pass, fail, invalid")
        import xml.etree.ElementTree as ElementTree
        suites = ElementTree.parse(xml_out).getroot()
        if suites.tag != "testsuites" or len(suites) != 3:
            fail(f"test results JUnit: {suites.tag} with {len(suites)} suites, expected testsuites with 3")
        elif (suites[0].get("failures"), suites[1].get("failures"), suites[2].get("errors")) != ("0", "1", "1"):
            fail("test results JUnit: the failures and errors per suite are not 0, 1 and an error")
        counts["reports"] += 1

# 3. Wrong files, refused by the schema; the environments among them by hapscene too.
def edited(instance, change):
    result = copy.deepcopy(instance)
    change(result)
    return result


def set_key(path, value):
    def change(instance):
        node = instance
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
    return change


def drop_key(path):
    def change(instance):
        node = instance
        for key in path[:-1]:
            node = node[key]
        del node[path[-1]]
    return change


bad_environments = [
    ("a misspelt effect key", edited(wall, set_key(["effects", 0, "stifness"], 500))),
    ("a length where a stiffness goes", edited(wall, set_key(["effects", 0, "stiffness"], "50 mm"))),
    ("an unknown effect type", edited(wall, set_key(["effects", 0, "type"], "wal"))),
    ("a wall without its solid side", edited(wall, drop_key(["effects", 0, "solid"]))),
    ("a negative stiffness", edited(wall, set_key(["effects", 0, "stiffness"], -5))),
    ("a rate below 10 Hz", edited(wall, set_key(["rate_hz"], 5))),
    ("an unknown top-level key", edited(wall, set_key(["colour"], "red"))),
    ("a $schema that is not a string", edited(wall, set_key(["$schema"], 3))),
    ("no effects", edited(wall, drop_key(["effects"]))),
    ("a script with both file and source",
     {"effects": [{"type": "script", "file": str(SOURCE / "scripts" / "spring.lua"),
                  "source": "function force(s) return 0 end"}]}),
    ("a 1-D wall in a 2-D scene", edited(box, set_key(["effects", 0], wall["effects"][0]))),
    ("a 2-D box in a 1-D scene", edited(wall, set_key(["effects", 0], box["effects"][0]))),
    ("a 1-D safety workspace in a 2-D scene", edited(box, set_key(["safety"], {"workspace": ["-1 mm", "1 mm"]}))),
    ("a 1-D-only validate key in a 2-D scene", edited(box, set_key(["validate"], {"max_slip_ticks": 3}))),
]
with tempfile.TemporaryDirectory() as scratch:
    for number, (what, instance) in enumerate(bad_environments):
        expect_invalid(environment, instance, "environment with " + what)
        # hapscene refuses it too.
        path = pathlib.Path(scratch) / f"bad{number}.json"
        path.write_text(json.dumps(instance), encoding="utf-8")
        planar = instance.get("device") == "haplink"
        probe = [HAPSCENE, "probe", str(path), "--x", "0:0:1mm"] + (["--y", "120mm:120mm:1mm"] if planar else [])
        run = subprocess.run(probe, capture_output=True, text=True)
        if run.returncode != 2:
            fail(f"environment with {what}: hapscene probe exit {run.returncode}, expected 2 ({run.stderr.strip()})")

hapkit3 = load(SOURCE / "environments" / "devices" / "hapkit3.json")
haplink = load(SOURCE / "environments" / "devices" / "haplink.json")
bad_profiles = [
    ("a misspelt drive key", edited(hapkit3, set_key(["drive", "pwm_level"], 255))),
    ("a direction sign of 0", edited(hapkit3, set_key(["drive", "direction_sign"], 0))),
    ("an encoder with MR keys", edited(hapkit3, set_key(["sensor", "type"], "encoder"))),
    ("no plant", edited(hapkit3, drop_key(["plant"]))),
    ("a planar profile with three joints", edited(haplink, lambda p: p["joints"].append(p["joints"][0]))),
    ("a planar joint with one capstan radius", edited(haplink, drop_key(["joints", 0, "sector_radius"]))),
    ("a workspace with a box and a polygon",
     edited(haplink, set_key(["limits", "workspace", "polygon"], [[0, 0], [1, 0], [0, 1]]))),
    ("an override of a wrong unit in a profile that extends another",
     {"extends": "hapkit3", "sensor": {"counts_to_deg_offset": "6 mm"}}),
    ("a misspelt key in a profile that extends another", {"extends": "hapkit3", "drive": {"pwm_level": 255}}),
]
for what, instance in bad_profiles:
    expect_invalid(profile, instance, "profile with " + what)
# What `hapscene calibrate` writes: a profile that extends the shipped one and overrides a
# few keys, at any depth (1-D and planar).
expect_valid(profile, {"extends": "hapkit3", "name": "hapkit3-calibrated", "sensor": {"counts_to_deg_offset": 6.0027},
                       "drive": {"direction_sign": -1}, "limits": {"workspace": [-0.047, 0.037]}},
             "a calibrated profile that extends hapkit3")
expect_valid(profile, {"extends": "hapkit_pantograph", "kind": "planar", "home": ["50 mm", "130 mm"]},
             "a planar profile that extends hapkit_pantograph")

wall_spec = load(SOURCE / "environments" / "wall.test.json")
box_spec = load(SOURCE / "environments" / "planar" / "haplink_box_inside.test.json")
bad_specs = [
    ("a misspelt key", edited(wall_spec, set_key(["never_exceed"], "5 N"))),
    ("an unknown scenario", {"scenarios": [{"scenario": "swep"}]}),
    ("an unknown check", {"scenarios": [{"scenario": "press", "fail": ["passivty"]}]}),
    ("a 2-D point in a 1-D force", {"forces": [{"x": ["1 mm", "2 mm"], "force": "0 N"}]}),
    ("1-D and 2-D forms mixed", {"forces": [{"x": "1 mm", "force": "0 N"}],
                                 "zero_outside": {"min": [0, 0], "max": [1, 1]}}),
    ("a force without a place", {"forces": [{"force": "1 N"}]}),
    ("a 2-D spec with noise", edited(box_spec, set_key(["options"], {"noise": 2}))),
]
for what, instance in bad_specs:
    expect_invalid(spec, instance, "spec with " + what)

with tempfile.TemporaryDirectory() as scratch:
    out = pathlib.Path(scratch) / "wall.report.json"
    subprocess.run([HAPSCENE, "validate", "environments/wall.json", "--quiet", "--report", str(out)], cwd=SOURCE,
                   capture_output=True)
    fresh = load(out) if out.exists() else {}
if fresh:
    bad_reports = [
        ("another schema name", edited(fresh, set_key(["schema"], "hapscene-validate/1"))),
        ("an unknown verdict", edited(fresh, set_key(["scenarios", 0, "checks", 0, "verdict"], "maybe"))),
        ("schema 1's lower-case verdict", edited(fresh, set_key(["scenarios", 0, "checks", 0, "verdict"], "fail"))),
        ("a scenario without its checks", edited(fresh, drop_key(["scenarios", 0, "checks"]))),
        ("a missing pass", edited(fresh, drop_key(["pass"]))),
        ("2-D marks on a 1-D report", edited(fresh, set_key(["axes"], 2))),
    ]
    for what, instance in bad_reports:
        expect_invalid(report, instance, "report with " + what)
    # A key added by a later hapscene is allowed by the shipped schema, not by the strict one.
    added = edited(fresh, set_key(["scene", "added_later"], 1))
    expect_valid(report, added, "report with a key added later")
    expect_invalid(strict_report, added, "report with an undescribed key (strict)")

print(f"json_schemas: {counts['environments']} environments, {counts['profiles']} profiles, {counts['specs']} specs, "
      f"{counts['reports']} reports checked; {len(refused)} invalid files tried ({len(bad_environments)} also on "
      f"hapscene)" + ("" if not failures else f"; {len(failures)} FAILED"))
sys.exit(1 if failures else 0)
