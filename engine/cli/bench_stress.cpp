// placeholder, replaced below
#include "engine/cli/bench_modes.hpp"
namespace hapscene {
int bench_stress(Arguments& arguments) { arguments.fail("--stress: not implemented yet"); }
int bench_soak(Arguments& arguments) { arguments.fail("--soak: not implemented yet"); }
}  // namespace hapscene
