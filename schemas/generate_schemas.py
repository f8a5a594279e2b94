#!/usr/bin/env python3
"""Writes hapscene's JSON Schemas (draft 2020-12) into this folder.

    python3 schemas/generate_schemas.py [OUTPUT_DIR] [--hapscene BINARY]

The schemas describe what the loaders accept (engine/load, engine/devices/profile.cpp,
engine/devices/planar/planar_profile.cpp, engine/harness/*test_spec*.cpp) and what
`hapscene validate --report` writes (engine/harness/report.cpp, planar_report.cpp). They are
written from this script so the quantity forms, the ranges and the shared parts stay alike
in every file; the ctest test `json_schemas` checks the committed files equal its output.
The built-in effects' schemas are not written here: the program writes them from the
effects' declarations (`hapscene schema effects`, engine/effects/effect_keys.hpp), and this
script places them (BINARY: build/hapscene by default).

A schema checks the shape of a file: the keys, their types, enumerations, whole numbers,
the unit of a quantity written as a string ("10 mm" where a length goes), and the range of
a quantity written as a plain number (SI). The loader checks more (a range written with a
unit, min below max, a polygon that crosses itself, what a script does), and says where.
"""
import json
import pathlib
import re
import subprocess
import sys

DRAFT = "https://json-schema.org/draft/2020-12/schema"
ID_BASE = "urn:hapscene:schema:"

# --- quantities ---------------------------------------------------------------------------
# The unit spellings of engine/base/units.cpp, by quantity. In a string, "*" may also be
# written as a middle dot or a space ("N s/m"), and spaces may stand around "/" and "*".
UNITS = {
    "length": ["m", "cm", "mm", "um", "µm"],
    "velocity": ["m/s", "cm/s", "mm/s"],
    "force": ["N", "mN"],
    "stiffness": ["N/m", "N/cm", "N/mm", "kN/m"],
    "damping": ["N*s/m", "Ns/m", "N*s/mm", "Ns/mm", "kg/s"],
    "time": ["s", "ms", "us", "µs"],
    "frequency": ["Hz", "kHz"],
    "mass": ["kg", "g"],
    "force_rate": ["N/s", "N/ms"],
    "angle": ["rad", "mrad", "deg"],
    "torque": ["N*m", "Nm", "mN*m", "mNm"],
    "inertia": ["kg*m^2", "g*cm^2", "kg*mm^2"],
    "rotational_damping": ["N*m*s/rad", "mN*m*s/rad"],
    "rotational_stiffness": ["N*m/rad", "mN*m/rad"],
    "plain": [],
}
SI_UNIT = {
    "length": "m", "velocity": "m/s", "force": "N", "stiffness": "N/m", "damping": "N*s/m",
    "time": "s", "frequency": "Hz", "mass": "kg", "force_rate": "N/s", "angle": "rad",
    "torque": "N*m", "inertia": "kg*m^2", "rotational_damping": "N*m*s/rad",
    "rotational_stiffness": "N*m/rad", "plain": "",
}
# std::from_chars's general form, with an optional leading '+'.
NUMBER = r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
SPACE = r"[ \t]*"


def unit_regex(unit):
    parts = re.split(r"([*/])", unit)
    out = ""
    for part in parts:
        if part == "*":
            out += r"(?:" + SPACE + r"[*·]" + SPACE + r"|[ \t]+)"
        elif part == "/":
            out += SPACE + "/" + SPACE
        else:
            out += re.escape(part).replace(r"\^", r"\^")
    return out


def quantity_pattern(kind):
    units = UNITS[kind]
    unit_part = ""
    if units:
        alternatives = "|".join(unit_regex(u) for u in sorted(units, key=len, reverse=True))
        unit_part = "(?:" + SPACE + "(?:" + alternatives + "))?"
    return "^" + SPACE + NUMBER + unit_part + SPACE + "$"


def quantity(kind, minimum=None, maximum=None, exclusive_min=False, description=None):
    """A number in SI (within [minimum, maximum] when given) or a string with a unit."""
    number = {"type": "number"}
    if minimum is not None:
        number["exclusiveMinimum" if exclusive_min else "minimum"] = minimum
    if maximum is not None:
        number["maximum"] = maximum
    unit = SI_UNIT[kind]
    schema = {"anyOf": [number, {"$ref": "#/$defs/" + kind + "_text"}]}
    what = kind.replace("_", " ")
    schema["description"] = description or (
        f"a {what}: a number in {unit} or a string with a unit" if unit else "a plain number (or a string holding one)")
    return schema


def quantity_defs(kinds):
    return {kind + "_text": {"type": "string", "pattern": quantity_pattern(kind),
                             "description": "a number with a unit of " + kind.replace("_", " ") +
                             (": " + ", ".join(UNITS[kind]) if UNITS[kind] else "")} for kind in kinds}


def whole(minimum, maximum, description=None):
    schema = {"type": "integer", "minimum": minimum, "maximum": maximum}
    if description:
        schema["description"] = description
    return schema


def vector(item, description):
    return {"type": "array", "prefixItems": [item, item], "minItems": 2, "maxItems": 2, "items": False,
            "description": description}


def interval(item, description):
    return {"type": "array", "prefixItems": [item, item], "minItems": 2, "maxItems": 2, "items": False,
            "description": description}


def closed(properties, required=(), description=None, **extra):
    schema = {"type": "object", "properties": properties, "additionalProperties": False}
    if required:
        schema["required"] = list(required)
    if description:
        schema["description"] = description
    schema.update(extra)
    return schema


def text(description):
    return {"type": "string", "description": description}


BOOLEAN = {"type": "boolean"}
SCHEMA_KEY = {"type": "string", "description": "the URI of this file's JSON Schema (for editors; ignored by hapscene)"}

# --- ranges (engine/base/physical_ranges.hpp and the loaders) -----------------------------
POSITION = dict(minimum=-1000, maximum=1000)
LENGTH = dict(minimum=0, maximum=1000)
POSITIVE_LENGTH = dict(minimum=0, maximum=1000, exclusive_min=True)
STIFFNESS = dict(minimum=0, maximum=1e7)
POSITIVE_STIFFNESS = dict(minimum=0, maximum=1e7, exclusive_min=True)
DAMPING = dict(minimum=0, maximum=1e4)
FORCE = dict(minimum=0, maximum=1000)
POSITIVE_FORCE = dict(minimum=0, maximum=1000, exclusive_min=True)
POSITIVE_SLEW = dict(minimum=0, maximum=1e8, exclusive_min=True)
DURATION = dict(minimum=0, maximum=60)
POSITIVE_DURATION = dict(minimum=0, maximum=60, exclusive_min=True)


def root(name, title, description, defs_kinds, body, extra_defs=None):
    defs = quantity_defs(defs_kinds)
    defs.update(extra_defs or {})
    schema = {"$schema": DRAFT, "$id": ID_BASE + name, "title": title, "description": description}
    schema.update(body)
    schema["$defs"] = defs
    return schema


# --- environments --------------------------------------------------------------------------

def script_effect(axes):
    limits = closed({
        "instructions_per_call": whole(100, 100_000_000),
        "memory_bytes": whole(64 << 10, 1 << 30),
        "allocation_bytes_per_call": whole(1 << 10, 1 << 30),
        "wall_time_per_call": quantity("time", **DURATION),
        "instructions_at_load": whole(100, 1_000_000_000),
        "string_bytes": whole(256, 16 << 20),
        "load_time": quantity("time", minimum=0, maximum=600, exclusive_min=True),
        "log_rate": quantity("frequency", minimum=0, maximum=1e5),
        "log_burst": whole(0, 64),
    }, description="the script's limits (docs/reference/lua.md, \"Limits\")")
    return closed({
        "type": {"const": "script"},
        "enabled": BOOLEAN,
        "file": text("the Lua file, relative to this environment"),
        "source": text("the Lua source, inline"),
        "params": {"type": "object", "description": "overrides of the script's params table"},
        "limits": limits,
    }, required=["type"], oneOf=[{"required": ["file"]}, {"required": ["source"]}],
        description=f"a Lua script effect ({axes}-D): exactly one of \"file\" and \"source\"")


def builtin_effects(hapscene):
    """The built-in effects' schemas, as the program writes them from their declarations:
    {"effect_1d_spring": {...}, "effect_2d_box": {...}, ...}."""
    out = subprocess.run([str(hapscene), "schema", "effects"], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def effects_of(builtins, axes):
    """The effect forms of one N: the built-ins, in the program's order, then "script"."""
    prefix = f"effect_{axes}d_"
    effects = {name[len(prefix):]: schema for name, schema in builtins.items() if name.startswith(prefix)}
    effects["script"] = script_effect(axes)
    return effects


def point(description="[x, y] in m (or strings with a unit)", **component):
    return vector(quantity("length", **(component or POSITION)), description)


def direction(description):
    return vector(quantity("plain", minimum=-1e6, maximum=1e6), description + " (not the zero vector)")


def effect_list(effects, axes):
    """An effect: a disabled one ("enabled": false) is only checked for its type, as the
    loader reads nothing more of it; an enabled one is one of the effect forms."""
    names = list(effects)
    return {
        "type": "array", "maxItems": 256,
        "items": {
            "type": "object", "required": ["type"],
            "properties": {"type": {"enum": names}},
            "if": {"properties": {"enabled": {"const": False}}, "required": ["enabled"]},
            "then": {},
            # One branch per type (rather than a oneOf), so a mistake is reported within its
            # effect's keys.
            "else": {"allOf": [{"if": {"properties": {"type": {"const": n}}},
                                "then": {"$ref": f"#/$defs/effect_{axes}d_{n}"}} for n in names]},
        },
        "description": f"the {axes}-D effects; their forces add up (at most 256)",
    }


def validate_block(axes):
    common = {
        "max_force": quantity("force", **POSITIVE_FORCE),
        "max_time_at_limit": quantity("plain", minimum=0, maximum=1, description="a fraction in [0, 1]"),
        "max_slew": quantity("force_rate", **POSITIVE_SLEW),
        "max_passivity_ratio": quantity("plain", minimum=0, maximum=1e6, exclusive_min=True),
        "max_residual_amplitude": quantity("length", **POSITIVE_LENGTH),
        "max_amplitude_growth": quantity("plain", minimum=0, maximum=1e6, exclusive_min=True),
        "max_penetration": quantity("length", **POSITIVE_LENGTH),
        "max_force_jitter": quantity("force", **POSITIVE_FORCE),
        "max_tick_compute": quantity("time", **POSITIVE_DURATION),
        "max_script_faults": whole(0, 1_000_000_000),
        "press_force": quantity("force", **POSITIVE_FORCE),
    }
    if axes == 1:
        common.update({"max_slip_ticks": whole(0, 1_000_000_000),
                       "stiff_threshold": quantity("stiffness", **POSITIVE_STIFFNESS),
                       "release_from": quantity("length", **POSITION)})
    else:
        common.update({"max_pop_through": whole(0, 1_000_000_000),
                       "max_singularity_ticks": whole(0, 1_000_000_000),
                       "release_from": quantity("length", **POSITIVE_LENGTH)})
    return closed(common, description="thresholds of hapscene validate (docs/reference/validate.md)")


def environment_form(axes, effects):
    safety = {
        "max_force": quantity("force", **POSITIVE_FORCE, description="at most the device's"),
        "slew_limit": quantity("force_rate", **POSITIVE_SLEW, description="at most the device's"),
        "soft_start": quantity("time", **DURATION, description="at least the device's"),
    }
    if axes == 1:
        safety["workspace"] = interval(quantity("length", **POSITION), "[low, high] within the device's")
    else:
        safety["workspace"] = closed({"min": point(), "max": point()}, required=["min", "max"],
                                     description="a box within the device's workspace")
    return closed({
        "$schema": SCHEMA_KEY,
        "name": text("for people (default: the file name)"),
        "description": text("for people"),
        "rate_hz": quantity("frequency", minimum=10, maximum=100000),
        "device": text("a device profile name (\"hapkit3\", \"haplink\") or a path relative to this file"),
        "safety": closed(safety, description="limits only safer than the device's"),
        "velocity": closed({"estimator": {"enum": ["hapkit2019", "hapkit2013", "difference", "lowpass"]},
                            "cutoff": quantity("frequency", minimum=0, maximum=1e6, exclusive_min=True)}),
        "effects": effect_list(effects, axes),
        "validate": validate_block(axes),
    }, required=["effects"], description=f"a {axes}-DOF environment")


def environment_schema(capstan_names, planar_names, builtins):
    effects = {axes: effects_of(builtins, axes) for axes in (1, 2)}
    defs = {"environment_1d": environment_form(1, effects[1]), "environment_2d": environment_form(2, effects[2])}
    for axes in (1, 2):
        for name, effect in effects[axes].items():
            defs[f"effect_{axes}d_{name}"] = effect
    body = {
        "type": "object",
        # Which form follows from "device": a shipped planar profile is 2-D, a shipped
        # capstan profile (or none: "hapkit3") is 1-D, a path may be either.
        "if": {"properties": {"device": {"enum": planar_names}}, "required": ["device"]},
        "then": {"$ref": "#/$defs/environment_2d"},
        "else": {
            "if": {"anyOf": [{"not": {"required": ["device"]}},
                             {"properties": {"device": {"enum": capstan_names}}, "required": ["device"]}]},
            "then": {"$ref": "#/$defs/environment_1d"},
            "else": {"anyOf": [{"$ref": "#/$defs/environment_1d"}, {"$ref": "#/$defs/environment_2d"}]},
        },
    }
    return root("environment", "hapscene environment",
                "An environment file (docs/reference/environments.md): 1-D for a "
                "capstan device profile, 2-D for a planar one.", list(UNITS), body, defs)


# --- device profiles ---------------------------------------------------------------------

def capstan_profile():
    mr_keys = {"min_counts", "span_counts", "flip_threshold_counts"}
    sensor = closed({
        "type": {"enum": ["mr", "encoder"]},
        "counts_to_deg_slope": quantity("plain", minimum=-10, maximum=10,
                                        description="deg per count, |slope| in [1e-6, 10]"),
        "counts_to_deg_offset": quantity("plain", minimum=-3600, maximum=3600),
        "min_counts": whole(0, 65535), "span_counts": whole(2, 65535), "flip_threshold_counts": whole(1, 65534),
    }, required=["counts_to_deg_slope", "counts_to_deg_offset"],
        allOf=[{"if": {"properties": {"type": {"const": "encoder"}}, "required": ["type"]},
                "then": {"not": {"anyOf": [{"required": [k]} for k in sorted(mr_keys)]}},
                "else": {"required": sorted(mr_keys)}}])
    radius = quantity("length", minimum=1e-4, maximum=1)
    drive = closed({
        "handle_radius": radius, "pulley_radius": radius, "sector_radius": radius,
        "duty_law": {"enum": ["sqrt", "linear"]},
        "motor_constant": quantity("plain", minimum=1e-6, maximum=100),
        "duty_max": quantity("plain", minimum=0, maximum=1, exclusive_min=True),
        "direction_sign": {"enum": [1, -1]},
        "pwm_levels": whole(1, 65535),
    }, required=["handle_radius", "pulley_radius", "sector_radius", "motor_constant", "duty_max",
                 "direction_sign", "pwm_levels"])
    limits = closed({
        "max_force": quantity("force", **POSITIVE_FORCE),
        "slew_limit": quantity("force_rate", **POSITIVE_SLEW),
        "workspace": interval(quantity("length", **POSITION), "[low, high]"),
        "soft_start": quantity("time", **DURATION),
        "soft_start_threshold": quantity("force", **FORCE),
        "slip_force": quantity("force", **POSITIVE_FORCE),
        "slip_step": quantity("force", **POSITIVE_FORCE),
    }, required=["max_force", "slew_limit", "workspace", "soft_start", "soft_start_threshold"])
    plant = closed({
        "mass": quantity("mass", minimum=1e-4, maximum=100),
        "viscous": quantity("damping", **DAMPING),
        "coulomb": quantity("force", **FORCE),
        "end_stops": interval(quantity("length", **POSITION), "[low, high]"),
        "end_stop_stiffness": quantity("stiffness", **POSITIVE_STIFFNESS),
        "sensor_noise_counts": quantity("plain", minimum=0, maximum=1000),
    }, required=["mass", "viscous", "coulomb", "end_stops", "end_stop_stiffness", "sensor_noise_counts"])
    return closed({
        "$schema": SCHEMA_KEY, "kind": {"const": "capstan"}, "name": text("the profile's name"),
        "description": text("for people"), "sensor": sensor, "drive": drive, "limits": limits, "plant": plant,
    }, required=["name", "sensor", "drive", "limits", "plant"], description="a 1-DOF (capstan) device profile")


def planar_profile():
    link = quantity("length", minimum=1e-4, maximum=1)
    angle = quantity("angle", minimum=-62.83185307179586, maximum=62.83185307179586)
    sign = {"enum": [1, -1]}
    kinematics = {
        "type": "object", "required": ["family"],
        "oneOf": [
            closed({"family": {"const": "serial_2r"}, "base": point(), "link_a": link, "link_b": link,
                    "offset_a": angle, "offset_b": angle}, required=["family", "link_a", "link_b"]),
            closed({"family": {"const": "five_bar"}, "base_1": point(), "base_2": point(),
                    "proximal_1": link, "proximal_2": link, "distal_1": link, "distal_2": link,
                    "assembly": {"enum": ["left", "right"]}},
                   required=["family", "base_1", "base_2", "proximal_1", "proximal_2", "distal_1", "distal_2"]),
        ],
    }
    counts_per_revolution = whole(1, 1 << 24)
    sensor = {
        "type": "object", "required": ["type"],
        "oneOf": [
            closed({"type": {"const": "mr"},
                    "counts_to_deg_slope": quantity("plain", minimum=-10, maximum=10),
                    "counts_to_deg_offset": quantity("plain", minimum=-3600, maximum=3600),
                    "min_counts": whole(0, 65535), "span_counts": whole(2, 65535),
                    "flip_threshold_counts": whole(1, 65534)},
                   required=["type", "counts_to_deg_slope", "counts_to_deg_offset", "min_counts", "span_counts",
                             "flip_threshold_counts"]),
            closed({"type": {"const": "encoder"}, "counts_per_revolution": counts_per_revolution,
                    "direction_sign": sign, "offset": angle}, required=["type", "counts_per_revolution"]),
            closed({"type": {"const": "angle"}, "counts_per_revolution": counts_per_revolution,
                    "board_offset": angle, "board_direction": {"enum": ["cw", "ccw"]}, "offset": angle},
                   required=["type", "counts_per_revolution", "board_offset", "board_direction"]),
        ],
    }
    duty = {"duty_max": quantity("plain", minimum=0, maximum=1, exclusive_min=True), "pwm_levels": whole(1, 65535)}
    drive = {
        "type": "object", "required": ["law"],
        "oneOf": [
            closed({"law": {"const": "torque"},
                    "torque_max": quantity("torque", minimum=0, maximum=100, exclusive_min=True),
                    "board_direction": {"enum": ["cw", "ccw"]}, "direction_sign": sign},
                   required=["law", "torque_max", "board_direction"]),
            closed({"law": {"const": "sqrt"}, "motor_constant": quantity("torque", minimum=1e-6, maximum=100),
                    **duty, "direction_sign": sign}, required=["law", "motor_constant", "duty_max", "pwm_levels"]),
            closed({"law": {"const": "linear"},
                    "duty_per_N_m": quantity("plain", minimum=0, maximum=1e6, exclusive_min=True),
                    **duty, "direction_sign": sign}, required=["law", "duty_per_N_m", "duty_max", "pwm_levels"]),
        ],
    }
    joint = closed({"sensor": sensor, "pulley_radius": link, "sector_radius": link, "drive": drive,
                    "board_port": whole(1, 4)}, required=["sensor", "drive"],
                   dependentRequired={"pulley_radius": ["sector_radius"], "sector_radius": ["pulley_radius"]},
                   description="a joint: its sensor, an optional capstan (both radii), its drive")
    workspace = {
        "type": "object",
        "oneOf": [
            closed({"box": closed({"min": point(), "max": point()}, required=["min", "max"])}, required=["box"]),
            closed({"polygon": {"type": "array", "items": point(), "minItems": 3, "maxItems": 1024}},
                   required=["polygon"]),
        ],
    }
    limits = closed({
        "max_force": quantity("force", **POSITIVE_FORCE),
        "slew_limit": quantity("force_rate", **POSITIVE_SLEW),
        "soft_start": quantity("time", **DURATION),
        "soft_start_threshold": quantity("force", **FORCE),
        "condition_limit": quantity("plain", minimum=1, maximum=1e6, exclusive_min=True),
        "workspace": workspace,
    }, required=["max_force", "slew_limit", "soft_start", "soft_start_threshold", "condition_limit", "workspace"])
    link_mass = closed({"mass": quantity("mass", minimum=0, maximum=100),
                        "inertia": quantity("inertia", minimum=0, maximum=100),
                        "center_of_mass": quantity("length", minimum=-1, maximum=1)},
                       required=["mass", "inertia", "center_of_mass"])
    plant = closed({
        "links": {"type": "array", "items": link_mass, "minItems": 2, "maxItems": 4,
                  "description": "two links (serial_2r) or four (five_bar: proximal 1, proximal 2, distal 1, distal 2)"},
        "handle_mass": quantity("mass", minimum=0, maximum=100),
        "rotor_inertia": vector(quantity("inertia", minimum=0, maximum=100), "per joint"),
        "viscous": vector(quantity("rotational_damping", minimum=0, maximum=100), "per joint"),
        "coulomb": vector(quantity("torque", minimum=0, maximum=100), "per joint"),
        "end_stops": vector(interval(angle, "[min, max]"), "per joint: [[min, max], [min, max]]"),
        "end_stop_stiffness": quantity("rotational_stiffness", minimum=0, maximum=1e6, exclusive_min=True),
        "sensor_noise_counts": quantity("plain", minimum=0, maximum=1000),
    }, required=["links", "handle_mass", "rotor_inertia", "viscous", "coulomb", "end_stops", "end_stop_stiffness",
                 "sensor_noise_counts"])
    return closed({
        "$schema": SCHEMA_KEY, "kind": {"const": "planar"}, "name": text("the profile's name"),
        "description": text("for people"), "note": text("for people"),
        "frame": closed({"origin": text("where (0, 0) is"), "x": text("the +x direction"),
                         "y": text("the +y direction")}, required=["origin", "x", "y"]),
        "kinematics": kinematics,
        "joints": {"type": "array", "items": joint, "minItems": 2, "maxItems": 2},
        "coupling": quantity("plain", minimum=-10, maximum=10),
        "board_serials": {"type": "array", "items": {"type": "string", "minLength": 1}, "minItems": 2, "maxItems": 2,
                          "description": "two Hapkit boards: the USB serial numbers of joint 1's and joint 2's "
                                         "boards (hapscene devices lists them), so swapped cables are caught"},
        "home": point(),
        "limits": limits,
        "plant": plant,
    }, required=["kind", "name", "frame", "kinematics", "joints", "home", "limits", "plant"],
        description="a 2-DOF (planar) device profile (docs/reference/devices-2d.md)")


def without_required(schema):
    """The schema with no key required anywhere: a profile that extends another (an RFC 7386
    merge patch over its parent) gives only the keys it overrides, at any depth."""
    if isinstance(schema, dict):
        # Only an object's own list of keys it must have; a bare {"required": [...]} is a
        # condition (if/then, not, oneOf) whose meaning must stay.
        drop = "properties" in schema
        return {key: without_required(value) for key, value in schema.items() if not (drop and key == "required")}
    if isinstance(schema, list):
        return [without_required(item) for item in schema]
    return schema


def with_extends(profile):
    profile["properties"]["extends"] = text("the profile this one extends: a shipped name or a path relative "
                                            "to this file; the keys here override the parent's")
    return profile


def profile_schema():
    capstan, planar = with_extends(capstan_profile()), with_extends(planar_profile())
    whole = {
        "if": {"properties": {"kind": {"const": "planar"}}, "required": ["kind"]},
        "then": {"$ref": "#/$defs/planar"},
        "else": {"$ref": "#/$defs/capstan"},
    }
    body = {
        "type": "object",
        "if": {"required": ["extends"]},
        "then": {"anyOf": [{"$ref": "#/$defs/capstan_override"}, {"$ref": "#/$defs/planar_override"}]},
        "else": whole,
    }
    return root("device-profile", "hapscene device profile",
                "A device profile (docs/reference/devices.md; planar: docs/reference/devices-2d.md).",
                list(UNITS), body, {"capstan": capstan, "planar": planar,
                                    "capstan_override": without_required(capstan),
                                    "planar_override": without_required(planar)})


# --- test specs ----------------------------------------------------------------------------
CHECKS_1D = ["max_force", "time_at_limit", "slew", "slip", "passivity", "limit_cycle", "growth", "penetration",
             "jitter", "script", "tick_compute"]
CHECKS_2D = ["max_force", "time_at_limit", "slew", "passivity", "limit_cycle", "growth", "penetration",
             "pop_through", "singularity", "jitter", "script", "tick_compute"]
SCENARIOS_1D = ["sweep", "press", "release", "hold", "shake", "free"]
SCENARIOS_2D = ["sweep", "press", "swipe", "release", "hold", "shake", "free"]


def spec_form(axes):
    hand = {
        "hand_stiffness": quantity("stiffness", minimum=0, maximum=1e6, exclusive_min=True),
        "hand_damping": quantity("damping", minimum=0, maximum=1e4),
        "hand_mass": quantity("mass", minimum=0, maximum=10),
        "seed": whole(0, 1 << 53),
    }
    free_start = quantity("length", minimum=-1, maximum=1)
    probe_position = quantity("length", **POSITION)
    probe_velocity = quantity("velocity", minimum=-1000, maximum=1000)
    if axes == 1:
        options = closed({**hand, "noise": quantity("plain", minimum=0, maximum=1000), "start": free_start})
        force = closed({"x": probe_position, "v": probe_velocity, "force": quantity("force"),
                        "tolerance": quantity("force", minimum=0)}, required=["x", "force"])
        zero_outside = interval(quantity("length"), "[a, b]: no force outside it")
    else:
        options = closed({**hand, "start": vector(free_start, "[x, y]")})
        force = closed({"at": vector(probe_position, "[x, y]"), "v": vector(probe_velocity, "[vx, vy]"),
                        "force": vector(quantity("force", minimum=-1e9, maximum=1e9), "[fx, fy]"),
                        "tolerance": quantity("force", minimum=0)}, required=["at", "force"])
        region = quantity("length", minimum=-1000, maximum=1000)
        zero_outside = closed({"min": vector(region, "[x, y]"), "max": vector(region, "[x, y]")},
                              required=["min", "max"], description="a box: no force outside it")
    scenario = closed({
        "scenario": {"enum": SCENARIOS_2D if axes == 2 else SCENARIOS_1D},
        "min_half_cycles": whole(0, 100000), "max_half_cycles": whole(0, 100000),
        "frequency": interval(quantity("frequency"), "[low, high]"),
        "max_force": quantity("force", minimum=0, exclusive_min=True),
        "pass": BOOLEAN,
        "fail": {"type": "array", "items": {"enum": CHECKS_2D if axes == 2 else CHECKS_1D},
                 "description": "checks that must fail"},
    }, required=["scenario"])
    return closed({
        "$schema": SCHEMA_KEY,
        "environment": text("the environment, relative to this spec (default: this file's name with .json)"),
        "description": text("for people"),
        "options": options,
        "forces": {"type": "array", "items": force},
        "zero_outside": zero_outside,
        "never_exceeds": quantity("force", minimum=0, exclusive_min=True),
        "passes_validate": BOOLEAN,
        "scenarios": {"type": "array", "items": scenario},
    }, description=f"a test spec for a {axes}-DOF environment")


def spec_schema():
    body = {"type": "object", "anyOf": [{"$ref": "#/$defs/spec_1d"}, {"$ref": "#/$defs/spec_2d"}]}
    return root("test-spec", "hapscene test spec",
                "A test spec, NAME.test.json (docs/reference/test-specs.md): the 1-D form for a "
                "1-DOF environment (\"x\", [a, b]), the 2-D form for a planar one (\"at\": [x, y], boxes).",
                list(UNITS), body, {"spec_1d": spec_form(1), "spec_2d": spec_form(2)})


# --- the validate report -------------------------------------------------------------------
# Numbers that may not be finite (a ratio over no energy, an unbounded threshold) are written
# as null by the JSON writer.
NUM = {"type": ["number", "null"]}
COUNT = {"type": "integer", "minimum": 0}
STRINGS = {"type": "array", "items": {"type": "string"}}
PAIR = {"type": "array", "items": NUM, "minItems": 2, "maxItems": 2}


def all_required(properties, description=None, **extra):
    return closed(properties, required=list(properties), description=description, **extra)


def report_schema():
    check = all_required({"name": {"type": "string"}, "value": NUM, "threshold": NUM, "unit": {"type": "string"},
                          "pass": BOOLEAN, "verdict": {"enum": ["pass", "FAIL", "not judged"]},
                          "detail": {"type": "string"}}, description="one check and its verdict")
    checks = {"type": "array", "items": {"$ref": "#/$defs/check"}}
    fault = all_required({"message": {"type": "string"}, "where": {"type": "string"}})
    passivity = all_required({"motor_work_J": NUM, "stored_J": NUM, "created_J": NUM, "dissipated_J": NUM,
                              "net_J": NUM, "ratio": NUM, "grows": BOOLEAN})
    compute = all_required({"p50": NUM, "p99": NUM, "max": NUM}, description="the tick's compute time, s")
    safety = {"nonfinite_faults": COUNT, "outside_workspace_ticks": COUNT, "soft_start_ticks": COUNT,
              "clamped_ticks": COUNT, "slew_limited_ticks": COUNT}

    def options(start):
        return all_required({"hand_stiffness_N_per_m": NUM, "hand_damping_N_s_per_m": NUM, "hand_mass_kg": NUM,
                             "noise_counts": NUM, "seed": COUNT, "free_start_m": start},
                            description="the virtual hand's options (noise_counts null: the profile's)")

    def scenario(metrics_ref, extra=None):
        # Every scenario has every key: one that does not apply (not run) has "metrics": null
        # and no checks.
        common = {"name": {"type": "string"}, "description": {"type": "string"}, "applicable": BOOLEAN,
                  "duration_s": NUM, **(extra or {}), "pass": BOOLEAN,
                  "metrics": {"anyOf": [{"$ref": metrics_ref}, {"type": "null"}]}, "checks": checks}
        return closed(common, required=list(common),
                      **{"if": {"properties": {"applicable": {"const": False}}},
                         "then": {"properties": {"metrics": {"type": "null"}, "checks": {"maxItems": 0}}}})

    metrics_1d = all_required({
        "ticks": COUNT, "max_requested_N": NUM, "max_output_N": NUM, "max_output_x_m": NUM,
        "max_output_t_s": NUM, "time_at_limit_s": NUM, "time_at_limit_fraction": NUM, "max_slew_N_per_s": NUM,
        "force_jitter_N": NUM, "slip_force_ticks": COUNT, "slip_step_ticks": COUNT, "max_step_1ms_N": NUM,
        "slip_first_x_m": NUM, "slip_first_t_s": NUM, "jitter_peak_N": NUM, "jitter_peak_x_m": NUM,
        "jitter_peak_t_s": NUM, "passivity": passivity,
        "oscillation": {"anyOf": [{"type": "null"}, all_required({
            "from_s": NUM, "half_cycles": COUNT, "frequency_Hz": NUM, "initial_amplitude_m": NUM,
            "residual_amplitude_m": NUM, "growth": NUM, "rest_m": NUM})]},
        "max_penetration_m": NUM, "max_penetration_x_m": NUM, "script_errors": COUNT,
        "script_budget_overruns": COUNT, "script_faults": {"type": "array", "items": fault},
        "tick_compute_s": compute, "safety": all_required(safety)})
    metrics_2d = all_required({
        "ticks": COUNT, "max_requested_N": NUM, "max_output_N": NUM, "max_output_x_m": PAIR,
        "max_output_t_s": NUM, "time_at_limit_s": NUM, "time_at_limit_fraction": NUM, "max_slew_N_per_s": NUM,
        "force_jitter_N": NUM, "jitter_peak_N": NUM, "jitter_peak_x_m": PAIR, "jitter_peak_t_s": NUM,
        "passivity": passivity,
        "oscillation": {"anyOf": [{"type": "null"}, all_required({
            "from_s": NUM, "half_cycles": COUNT, "frequency_Hz": NUM, "initial_amplitude_m": NUM,
            "residual_amplitude_m": NUM, "growth": NUM, "rest_m": PAIR, "major_axis": PAIR})]},
        "max_penetration_m": NUM, "max_penetration_x_m": PAIR, "max_penetration_t_s": NUM,
        "max_penetration_shape": {"type": ["integer", "null"], "minimum": 0},
        "pop_throughs": COUNT, "first_pop_x_m": {"anyOf": [PAIR, {"type": "null"}]}, "first_pop_t_s": NUM,
        "first_pop_shape": {"type": ["integer", "null"], "minimum": 0},
        "pose_hold_ticks": COUNT, "pose_hold_force_ticks": COUNT, "max_condition": NUM,
        "max_condition_x_m": PAIR, "max_condition_t_s": NUM, "script_errors": COUNT,
        "script_budget_overruns": COUNT, "script_faults": {"type": "array", "items": fault},
        "tick_compute_s": compute,
        "safety": all_required({**safety, "pose_hold_ticks": COUNT, "motor_saturated_ticks": COUNT})})

    scene_1d = all_required({
        "name": {"type": "string"}, "source": {"type": "string"}, "rate_hz": NUM, "passivity_bound_N_per_m": NUM,
        "passivity_bound": {"type": "string"}, "stiffest_region_N_per_m": NUM,
        "stiff_regions": {"type": "array", "items": all_required(
            {"low_m": NUM, "high_m": NUM, "low_is_edge": BOOLEAN, "high_is_edge": BOOLEAN,
             "stiffness_N_per_m": NUM})},
        "static_field": BOOLEAN, "field_note": {"type": "string"}, "field_script_faults": STRINGS,
        "load_warnings": STRINGS})
    pose = all_required({"x_m": PAIR, "viscous_N_per_m": NUM, "coulomb_N_per_m": NUM, "bound_N_per_m": NUM,
                         "bound": {"type": "string"}, "condition": NUM})
    scene_2d = all_required({
        "name": {"type": "string"}, "source": {"type": "string"}, "rate_hz": NUM, "axes": {"const": 2},
        "shapes": COUNT, "passivity_bound_N_per_m": NUM, "passivity_bound": {"type": ["string", "null"]},
        "stiffest_region_N_per_m": NUM,
        "stiffness_bound": all_required({"grid": COUNT, "held_poses": COUNT,
                                         "lowest": {"anyOf": [{"$ref": "#/$defs/pose"}, {"type": "null"}]},
                                         "highest": {"anyOf": [{"$ref": "#/$defs/pose"}, {"type": "null"}]},
                                         "poses": {"type": "array", "items": {"$ref": "#/$defs/pose"}}}),
        "load_warnings": STRINGS})
    report_1d = all_required({
        "schema": {"const": "hapscene-validate/2"}, "scene": scene_1d, "options": options(NUM), "pass": BOOLEAN,
        "scene_checks": checks,
        "scenarios": {"type": "array", "items": scenario("#/$defs/metrics_1d")},
    }, description="the report of a 1-DOF scene")
    report_2d = all_required({
        "schema": {"const": "hapscene-validate/2"}, "axes": {"const": 2}, "scene": scene_2d,
        "options": options({"anyOf": [PAIR, {"type": "null"}]}), "pass": BOOLEAN, "scene_checks": checks,
        "scenarios": {"type": "array", "items": scenario("#/$defs/metrics_2d", {"start_m": PAIR})},
    }, description="the report of a 2-DOF scene (\"axes\": 2)")
    body = {"type": "object",
            "if": {"properties": {"axes": {"const": 2}}, "required": ["axes"]},
            "then": {"$ref": "#/$defs/report_2d"}, "else": {"$ref": "#/$defs/report_1d"}}
    schema = root("validate-report", "hapscene validate report (hapscene-validate/2)",
                  "What `hapscene validate --report FILE` writes (docs/reference/validate-report.md): a 1-D report, or a 2-D "
                  "one marked \"axes\": 2. Fields are only ever added to hapscene-validate/2 (/1 wrote a failed check's verdict "
                  "\"fail\" and left a scenario that did not apply without \"metrics\" and \"checks\"), so objects here "
                  "allow keys they do not list; the test json_schemas checks that they list every key hapscene "
                  "writes today.", [], body,
                  {"check": check, "pose": pose, "metrics_1d": metrics_1d, "metrics_2d": metrics_2d,
                   "report_1d": report_1d, "report_2d": report_2d})
    return open_for_additions(schema)


def test_results_schema():
    expectation = all_required({"what": {"type": "string", "description": "the JSON pointer of the expectation in the spec"},
                                "pass": BOOLEAN,
                                "message": {"type": "string", "description": "what was expected and what was found"}})
    spec = all_required({
        "spec": {"type": "string", "description": "the spec file, as given or found"},
        "environment": {"type": ["string", "null"], "description": "the environment it tests (null: the spec did not load)"},
        "verdict": {"enum": ["pass", "fail", "invalid"],
                    "description": "invalid: the spec or its environment is invalid input (exit 2)"},
        "error": {"type": ["string", "null"], "description": "the error printed for the spec, when there was one"},
        "seconds": {"type": "number", "minimum": 0, "description": "the wall time the spec took"},
        "expectations": {"type": "array", "items": {"$ref": "#/$defs/expectation"}},
    }, description="one spec as run")
    summary = all_required({"specs": COUNT, "passed": COUNT, "failed": COUNT, "invalid": COUNT, "expectations": COUNT})
    body = all_required({"format": {"const": "hapscene-test/1"}, "summary": summary,
                         "specs": {"type": "array", "items": {"$ref": "#/$defs/spec"}}})
    schema = root("test-results", "hapscene test results (hapscene-test/1)",
                  "What `hapscene test --json FILE` writes (docs/reference/test-specs.md): every spec's verdict and "
                  "expectations, in the order run. Fields are only ever added to hapscene-test/1, so objects here allow "
                  "keys they do not list; the test json_schemas checks that they list every key hapscene writes today.",
                  [], body, {"expectation": expectation, "spec": spec})
    return open_for_additions(schema)


def open_for_additions(node):
    """Drops every "additionalProperties": false (a report of a later hapscene may add keys)."""
    if isinstance(node, dict):
        return {k: open_for_additions(v) for k, v in node.items()
                if not (k == "additionalProperties" and v is False)}
    if isinstance(node, list):
        return [open_for_additions(v) for v in node]
    return node


# --- output --------------------------------------------------------------------------------

def shipped_profile_names(source_dir):
    capstan, planar = [], []
    for path in sorted((source_dir / "environments" / "devices").glob("*.json")):
        kind = json.loads(path.read_text(encoding="utf-8")).get("kind", "capstan")
        (planar if kind == "planar" else capstan).append(path.stem)
    return capstan, planar


def schemas(source_dir, hapscene):
    capstan, planar = shipped_profile_names(source_dir)
    return {
        "environment.schema.json": environment_schema(capstan, planar, builtin_effects(hapscene)),
        "device-profile.schema.json": profile_schema(),
        "test-spec.schema.json": spec_schema(),
        "validate-report.schema.json": report_schema(),
        "test-results.schema.json": test_results_schema(),
    }


def main():
    here = pathlib.Path(__file__).resolve().parent
    args = sys.argv[1:]
    hapscene = here.parent / "build" / "hapscene"
    if "--hapscene" in args:
        at = args.index("--hapscene")
        hapscene = pathlib.Path(args[at + 1])
        del args[at:at + 2]
    out_dir = pathlib.Path(args[0]) if args else here
    out_dir.mkdir(parents=True, exist_ok=True)
    for name, schema in schemas(here.parent, hapscene).items():
        (out_dir / name).write_text(json.dumps(schema, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")


if __name__ == "__main__":
    main()
