#include "engine/bench/build_info.hpp"

// Set by CMakeLists.txt for this file only; a build without them says so.
#ifndef HAPSCENE_BUILD_TYPE
#define HAPSCENE_BUILD_TYPE "unknown build type"
#endif
#ifndef HAPSCENE_BUILD_LTO
#define HAPSCENE_BUILD_LTO 0
#endif
#ifndef HAPSCENE_BUILD_COMPILER
#define HAPSCENE_BUILD_COMPILER "unknown compiler"
#endif

namespace hapscene {

std::string build_description() {
  std::string text = HAPSCENE_BUILD_TYPE;
  if (text.empty()) text = "no build type (no optimisation flags)";
  text += HAPSCENE_BUILD_LTO ? ", LTO on" : ", LTO off";
#ifdef NDEBUG
  text += ", assertions off";
#else
  text += ", assertions on";
#endif
  return text + ", " + HAPSCENE_BUILD_COMPILER;
}

}  // namespace hapscene
