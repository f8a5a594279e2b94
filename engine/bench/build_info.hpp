#pragma once
// What build the bench runs in, for its output: timings depend on it.
#include <string>

namespace hapscene {

// "Release, LTO on, GNU 12.2.0" (the CMake build type, link-time optimisation, compiler).
std::string build_description();

}  // namespace hapscene
