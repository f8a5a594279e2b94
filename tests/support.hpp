#pragma once
// Helpers shared by the tests: scenes from inline JSON, and the error message of a call.
#include <functional>
#include <string>

#include <doctest/doctest.h>

#include "engine/base/errors.hpp"
#include "engine/load/environment.hpp"

namespace hapscene::test {

// A scene from inline JSON, named "test.json" in messages.
inline Scene scene_from(const std::string& json_text) {
  return load_environment_text(json_text, "test.json", HAPSCENE_SOURCE_DIR "/environments");
}

// The same, with the harness's thresholds (the "validate" block) beside the scene.
inline Environment environment_from(const std::string& json_text) {
  return compile_environment(json_text, "test.json", HAPSCENE_SOURCE_DIR "/environments");
}

// The message of the InputError `call` throws, or "(no error)".
inline std::string input_error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

// The message loading `json_text` fails with.
inline std::string load_error(const std::string& json_text) {
  return input_error_of([&] { scene_from(json_text); });
}

inline std::string source_path(const std::string& relative) {
  return std::string(HAPSCENE_SOURCE_DIR) + "/" + relative;
}

}  // namespace hapscene::test
