#pragma once
// How `hapscene test` runs its specs: one after another in this process, or several at
// once (--jobs), each in a process of its own, so that a class's hundreds of specs use every
// core and one that crashes, or runs past --spec-timeout, gets its verdict without
// stopping the others. Either way the results come back in the specs' order, with what each
// wrote on stderr (load warnings, its error line), so the output is the same bytes.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "engine/harness/test_report.hpp"

namespace hapscene {

// One spec's run: its record (texts printable), its exit code (0 pass, 1 fail, 2 invalid
// input) and, for a spec run in a process of its own, what it wrote on stderr.
struct SpecRun {
  SpecRecord record;
  int exit_code{};
  std::string stderr_text;
};

// Runs one spec here; its load warnings and error line go to stderr as they happen.
SpecRun run_spec_here(const std::string& spec);

// Runs `specs`, `jobs` at a time, each in a child process stopped after `timeout_s` (0: no
// limit), and calls `done(i, run)` for spec i as soon as it and every spec before it are
// done (so in the specs' order). A child that ends without its result (a signal, a crash)
// or runs past the limit is a failed spec (exit 1) whose error says so.
void run_specs_in_processes(const std::vector<std::string>& specs, int jobs, double timeout_s,
                            const std::function<void(std::size_t, SpecRun&)>& done);

}  // namespace hapscene
