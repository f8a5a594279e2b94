#pragma once
// The JSON Schema of every built-in effect, written from the effects' declarations
// (engine/effects/effect_keys.hpp): what `hapscene schema effects` prints and
// schemas/generate_schemas.py places in schemas/environment.schema.json, so the schema of
// an effect cannot drift from what the loader reads.
#include <string>

#include <nlohmann/json.hpp>

namespace hapscene {

// {"effect_1d_spring": {...}, "effect_2d_box": {...}, ...}: one closed object schema per
// built-in effect type of every N, in the order of each N's list. Quantities refer to
// "#/$defs/KIND_text" (KIND: length, stiffness, damping, plain) for their string form.
nlohmann::ordered_json effect_schemas();

// The same declarations as a Markdown page for people (docs/reference/effects.md, written
// by `hapscene schema effects --markdown`): per N, per effect, a table of its keys with
// their form, unit, range, default and whether the live view slides them.
std::string effect_reference_markdown();

}  // namespace hapscene
