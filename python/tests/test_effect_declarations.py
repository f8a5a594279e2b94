# hapscene.effect_types(): the engine's declaration of every built-in effect, and Python's
# view of a loaded effect agreeing with it (the C++ side of the same check:
# tests/effects/effect_declarations_test.cpp). A new effect type is covered here without a
# line of this file changing.
import hapscene


def example_value(key, axes, index):
    """A written value for the key at `index`: inside its range, different for each key."""
    v = 0.01 * (index + 1)
    form = key["form"]
    if form == "number":
        return v
    if form == "vector":
        return v if axes == 1 else [v] * axes
    if form == "direction":
        return [1.0] + [0.0] * (axes - 1)
    if form == "choice":
        return key["choices"][0]
    if form == "flag":
        return True
    if form == "points":
        return [[0, 0], [0.01, 0], [0, 0.01]]
    if form == "friction":
        return {"static": 0.5, "dynamic": 0.25}
    raise AssertionError(f"a form this test does not know: {form}")


def loaded_effect(declaration):
    effect = {"type": declaration["type"]}
    for index, key in enumerate(declaration["keys"]):
        effect[key["name"]] = example_value(key, declaration["axes"], index)
    device = "hapkit3" if declaration["axes"] == 1 else "haplink"
    return hapscene.loads({"device": device, "effects": [effect]}).effects[0], effect


def test_every_type_of_every_axis_count_is_declared():
    types = {(d["axes"], d["type"]) for d in hapscene.effect_types()}
    for builtin in ("spring", "wall", "damper", "texture", "magnet"):
        assert (1, builtin) in types
    for builtin in ("spring", "wall", "box", "circle", "polygon", "damper", "texture", "magnet"):
        assert (2, builtin) in types


def test_a_loaded_effect_shows_every_declared_value_under_its_field():
    for declaration in hapscene.effect_types():
        shown, written = loaded_effect(declaration)
        fields = {key["field"] for key in declaration["keys"] if key["field"] is not None}
        assert set(shown) == {"type"} | fields, declaration["type"]
        for index, key in enumerate(declaration["keys"]):
            value = shown.get(key["field"]) if key["field"] else None
            if key["form"] in ("number", "vector"):
                expected = 0.01 * (index + 1)
                values = value if isinstance(value, tuple) else (value,)
                assert len(values) == (declaration["axes"] if key["form"] == "vector" else 1)
                assert all(abs(v - expected) < 1e-15 for v in values), (declaration["type"], key["name"])
            elif key["form"] in ("choice", "flag"):
                assert value is True, (declaration["type"], key["name"])


def test_defaults_and_ranges_are_the_loaders():
    for declaration in hapscene.effect_types():
        for key in declaration["keys"]:
            if key["form"] not in ("number", "vector"):
                continue
            assert key["min"] <= key["max"]
            if key["required"]:
                assert "default" not in key and "default_from" not in key
            else:
                assert ("default" in key) != ("default_from" in key)
                # Left out, the loaded value is the declared default (or the other key's).
                _, written = loaded_effect(declaration)
                del written[key["name"]]
                device = "hapkit3" if declaration["axes"] == 1 else "haplink"
                shown = hapscene.loads({"device": device, "effects": [written]}).effects[0]
                value = shown[key["field"]]
                values = value if isinstance(value, tuple) else (value,)
                if "default" in key:
                    assert all(v == key["default"] for v in values)
                else:
                    source = next(k for k in declaration["keys"] if k["name"] == key["default_from"])
                    assert all(v == shown[source["field"]] for v in values)
