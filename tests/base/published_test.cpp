// A value one thread publishes and another reads without locks (the simulated board's truth
// for the loop's observers): every value read is one that a store left whole, and reads
// never go back in time.
#include <doctest/doctest.h>

#include <atomic>
#include <cstdint>
#include <thread>

#include "engine/base/published.hpp"

using namespace hapscene;

namespace {

// Five fields a store fills alike, so a torn value shows as fields that differ.
struct Fields {
  std::uint64_t a, b, c, d, e;
};

Fields fields_of(std::uint64_t n) { return Fields{n, n, n, n, n}; }

}  // namespace

TEST_CASE("published: the value read is the latest whole one") {
  Published<Fields> value(fields_of(7));
  CHECK(value.load().e == 7);
  value.store(fields_of(8));
  value.store(fields_of(9));
  const Fields read = value.load();
  CHECK(read.a == 9);
  CHECK(read.e == 9);
}

TEST_CASE("published: a reader beside a writer sees only whole values, never older ones" *
          doctest::test_suite("threaded")) {
  Published<Fields> value(fields_of(0));
  std::atomic<bool> done{false};
  constexpr std::uint64_t kStores = 200'000;
  std::thread writer([&] {
    for (std::uint64_t n = 1; n <= kStores; ++n) value.store(fields_of(n));
    done.store(true, std::memory_order_release);
  });
  std::uint64_t torn = 0;
  std::uint64_t backwards = 0;
  std::uint64_t last = 0;
  std::uint64_t reads = 0;
  while (!done.load(std::memory_order_acquire) || reads == 0) {
    const Fields read = value.load();
    if (read.a != read.b || read.a != read.c || read.a != read.d || read.a != read.e) ++torn;
    if (read.a < last) ++backwards;
    last = read.a;
    ++reads;
  }
  writer.join();
  CHECK(torn == 0);
  CHECK(backwards == 0);
  CHECK(value.load().a == kStores);
}
