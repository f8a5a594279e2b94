#pragma once
// The environment's optional "validate" block: thresholds for `hapscene validate`.
#include "engine/base/object_reader.hpp"
#include "engine/load/validate_thresholds.hpp"

namespace hapscene {

// Reads every key of the block over the defaults in `thresholds`. Throws InputError
// naming the key ("/validate/max_force: must be > 0, got -1 N").
void parse_validate_block(ObjectReader& reader, ValidateThresholds* thresholds);

// The block of a 2-DOF (planar) environment: the keys that mean something in 2-D, in the
// same units as in 1-D, plus "max_pop_through" and "max_singularity_ticks" (counts); the
// 1-DOF-only keys ("max_slip_ticks", "stiff_threshold") are refused, each naming why.
void parse_planar_validate_block(ObjectReader& reader, ValidateThresholds* thresholds);

}  // namespace hapscene
