#pragma once
// The environment's optional "validate" block: thresholds for `hapscene validate`.
#include "engine/base/object_reader.hpp"
#include "engine/load/validate_thresholds.hpp"

namespace hapscene {

// Reads every key of the block over the defaults in `thresholds`. Throws InputError
// naming the key ("/validate/max_force: must be > 0, got -1 N").
void parse_validate_block(ObjectReader& reader, ValidateThresholds* thresholds);

}  // namespace hapscene
