#pragma once
// Commands that take several files (validate, test) give each file its own verdict: a
// file that cannot be loaded prints its error, as main() would, and the others still run.
// The exit code is the worst of the files' codes: 2 when any file was invalid input, else
// 1 when any check failed (or anything else went wrong), else 0.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/standard_output.hpp"

namespace hapscene {

// The exit code of a command over several files from two of their codes.
inline int worst_exit_code(int a, int b) {
  const auto rank = [](int code) { return code == kExitInvalidInput ? 2 : code == kExitOk ? 0 : 1; };
  return rank(a) >= rank(b) ? a : b;
}

// Runs `work` (which returns the file's exit code); an error it throws is printed on
// stderr (after what stdout has so far, so the lines stay in order) and becomes the code.
// `error_text`, when given, receives the error's printable text.
template <class Work>
int run_for_file(Work&& work, std::string* error_text = nullptr) {
  try {
    return work();
  } catch (const InputError& error) {
    flush_out();
    const std::string text = printable(error.what());
    std::fprintf(stderr, "error: %s\n", text.c_str());
    if (error_text != nullptr) *error_text = text;
    return kExitInvalidInput;
  } catch (const std::exception& error) {
    flush_out();
    const std::string text = printable(error.what());
    std::fprintf(stderr, "hapscene: %s\n", text.c_str());
    if (error_text != nullptr) *error_text = text;
    return kExitFailure;
  }
}

}  // namespace hapscene
