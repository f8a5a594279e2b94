// log()/print(): never blocks the tick; messages carry their place and run time, are
// rate limited on run time, and the drops are counted and reported.
#include <atomic>
#include <thread>

#include "tests/lua/script_test_support.hpp"

namespace hapscene {
namespace {

using test::at;
using test::run_inline;

std::vector<std::string> drained(ScriptInstance* script) {
  std::vector<std::string> lines;
  script->drain_log(&lines);
  return lines;
}

TEST_CASE("log: messages carry the script line and the run time") {
  auto script = run_inline(
      "log('loaded')\n"
      "function force(s)\n"
      "  print('x =', s.x, true, nil)\n"
      "  return 0\n"
      "end");
  script->force_N(at(0.5, 0.0, 0.25));
  CHECK(drained(script.get()) ==
        std::vector<std::string>{"t.lua:1: loaded (t = 0.000 s)",
                                 "t.lua:3: x =\t0.5\ttrue\tnil (t = 0.250 s)"});
  CHECK(drained(script.get()).empty());
}

TEST_CASE("log: a message per tick is rate limited, and the drops are counted") {
  auto script = run_inline("function force(s) log('tick', s.t) return 0 end");
  for (int i = 0; i < 1000; ++i) script->force_N(at(0.0, 0.0, i * 0.001));
  const auto lines = drained(script.get());
  // A burst of 20, then 10 per second over the 1 s of run time: 29 or 30 messages.
  REQUIRE(lines.size() >= 30);
  CHECK(lines.size() <= 31);
  CHECK(lines.back() == "t.lua: " + std::to_string(1000 - (lines.size() - 1)) +
                            " log messages dropped (at most 10 per second, bursts of 20)");
}

TEST_CASE("log: the queue is bounded, a full queue drops instead of blocking") {
  ScriptLimits limits;
  limits.log_messages_per_s = 1e9;
  limits.log_burst = 1000;
  auto script = run_inline("function force(s) log('m') return 0 end", limits);
  for (int i = 0; i < 100; ++i) script->force_N(at(0.0, 0.0, i * 1.0));
  const auto lines = drained(script.get());
  REQUIRE(lines.size() == 65);
  CHECK(lines.back() == "t.lua: 36 log messages dropped (at most 1e+09 per second, bursts of 64)");
}

TEST_CASE("log: long messages are cut to the slot size") {
  auto script = run_inline("function force(s) log(string.rep('a', 1000)) return 0 end");
  script->force_N(at(0.0));
  const auto lines = drained(script.get());
  REQUIRE(lines.size() == 1);
  CHECK(lines[0].size() == 240 + std::string(" (t = 0.000 s)").size());
  CHECK(lines[0].substr(0, 10) == "t.lua:1: a");
  CHECK(lines[0].substr(237, 3) == "...");
}

TEST_CASE("log: a __tostring that fails does not publish a broken message") {
  auto script = run_inline(
      "local bad = setmetatable({}, { __tostring = function() error('no text') end })\n"
      "function force(s)\n"
      "  if s.x > 0 then log('value', bad) end\n"
      "  return 0\n"
      "end");
  script->force_N(at(0.01));
  CHECK(script->disabled());
  CHECK(script->fault_message() == "t.lua:1: no text");
  CHECK(drained(script.get()).empty());
}

TEST_CASE("log: another thread may drain while the loop logs" * doctest::test_suite("threaded")) {
  ScriptLimits limits;
  limits.log_messages_per_s = 1e9;
  limits.log_burst = 64;
  auto script = run_inline("function force(s) log(s.t) return 0 end", limits);
  std::vector<std::string> lines;
  std::atomic<bool> done{false};
  std::thread reader([&] {
    while (!done.load()) script->drain_log(&lines);
    script->drain_log(&lines);
  });
  for (int i = 0; i < 20'000; ++i) script->force_N(at(0.0, 0.0, i * 1e-3));
  done.store(true);
  reader.join();
  // Every message either arrived whole or was counted as dropped.
  std::size_t messages = 0;
  std::size_t dropped = 0;
  std::size_t malformed = 0;
  for (const std::string& line : lines) {
    if (line.find("dropped") != std::string::npos) {
      dropped += std::stoul(line.substr(std::string("t.lua: ").size()));
    } else {
      malformed += line.rfind("t.lua:1: ", 0) == 0 && line.back() == ')' ? 0 : 1;
      ++messages;
    }
  }
  CHECK(malformed == 0);
  CHECK(messages + dropped == 20'000);
}

}  // namespace
}  // namespace hapscene
