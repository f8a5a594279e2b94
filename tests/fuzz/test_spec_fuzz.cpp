// Fuzz target: an environment test spec (*.test.json) through the spec reader. The spec is
// written to an empty scratch folder, so the environment it names is not there: a spec the
// reader accepts fails at its environment, which keeps every input fast (no probes or
// simulated runs) and exercises the whole of the spec's parsing and checking.
#include "engine/base/errors.hpp"
#include "engine/harness/test_spec.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hapscene;
  const std::string path = fuzz::write_scratch_file("fuzz.test.json", fuzz::as_text(data, size));
  try {
    run_test_spec(path);
  } catch (const InputError&) {
  }
  return 0;
}
