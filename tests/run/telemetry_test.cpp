// The telemetry ring under a concurrent producer and consumer, and the CSV log of a
// simulated run against the ticks traced beside it.
#include <doctest/doctest.h>

#include <atomic>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

#include "engine/base/errors.hpp"
#include "engine/devices/simulated_hapkit.hpp"
#include "engine/run/observer_list.hpp"
#include "engine/run/telemetry_log.hpp"
#include "engine/run/telemetry_ring.hpp"
#include "tests/support.hpp"

// This file's own names, apart from its unity batch's neighbours (tests/CMakeLists.txt).
namespace HAPSCENE_TEST_FILE {

using namespace hapscene;

TEST_CASE("telemetry ring: capacity, order, full and empty") {
  SpscRing<int> ring(5);
  CHECK(ring.capacity() == 8);
  int value = 0;
  CHECK_FALSE(ring.try_pop(&value));
  for (int i = 0; i < 8; ++i) CHECK(ring.try_push(i));
  CHECK_FALSE(ring.try_push(99));  // full: refused, nothing overwritten
  for (int i = 0; i < 8; ++i) {
    REQUIRE(ring.try_pop(&value));
    CHECK(value == i);
  }
  CHECK_FALSE(ring.try_pop(&value));
}

TEST_CASE("telemetry ring: a concurrent producer and consumer lose and reorder nothing" * doctest::test_suite("threaded")) {
  constexpr std::uint64_t kCount = 300'000;
  SpscRing<std::uint64_t> ring(1024);
  std::atomic<bool> mismatch{false};
  std::uint64_t received = 0;
  std::thread consumer([&] {
    std::uint64_t value = 0;
    while (received < kCount) {
      if (ring.try_pop(&value)) {
        if (value != received) mismatch = true;
        ++received;
      } else {
        std::this_thread::yield();  // the machine may have fewer cores than threads
      }
    }
  });
  // The producer retries when full (a test of the ring; the log drops instead).
  std::uint64_t refused = 0;
  for (std::uint64_t i = 0; i < kCount; ++i) {
    while (!ring.try_push(i)) {
      ++refused;
      std::this_thread::yield();
    }
  }
  consumer.join();
  CHECK(received == kCount);
  CHECK_FALSE(mismatch.load());
  MESSAGE("pushes refused while the ring was full: " << refused);
}

TEST_CASE("telemetry log: a full ring drops and counts, never blocks" * doctest::test_suite("threaded")) {
  const auto path = std::filesystem::temp_directory_path() / "hapscene_drop_test.csv";
  TelemetryLog log(path.string(), 4);
  TickState state;
  // Far more samples than the ring holds, pushed faster than any writer drains them.
  for (int i = 0; i < 100000; ++i) {
    state.t_s = i * 1e-3;
    log.on_tick(state);
  }
  log.finish();
  CHECK(log.dropped() > 0);
  CHECK(log.written() + log.dropped() == 100000);
  std::ifstream in(path);
  std::string line;
  std::uint64_t lines = 0;
  while (std::getline(in, line)) ++lines;
  CHECK(lines == log.written() + 1);  // plus the header
  std::filesystem::remove(path);
}

namespace {

// What the loop saw, tick by tick, for comparison with the CSV.
class Trace final : public TickObserver {
 public:
  explicit Trace(std::size_t ticks) { samples.reserve(ticks); }
  void on_tick(const TickState& s) noexcept override {
    samples.push_back({s.t_s, s.x_m, s.v_m_per_s, s.effects_force_N, s.output_N, s.command.duty,
                       s.command.direction_high});
  }
  std::vector<TelemetrySample> samples;
};

double parse_double(const std::string& text) {
  double value = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), value);
  return value;
}

}  // namespace

TEST_CASE("telemetry log: the CSV of a simulated run equals the traced ticks exactly" * doctest::test_suite("threaded")) {
  const Scene scene = load_environment_file(test::source_path("environments/wall_corridor.json"));
  SimulationConfig config;
  SimulatedHapkit device(scene.device, config);
  const auto path = std::filesystem::temp_directory_path() / "hapscene_log_test.csv";
  TelemetryLog log(path.string(), 4096);
  Trace trace(1001);
  ObserverList observers;
  observers.add(&log);
  observers.add(&trace);
  RunOptions options{.duration_s = 1.0, .pacing = Pacing::simulated_time};
  run_scene(scene, device, options, &observers);
  log.finish();
  CHECK(log.dropped() == 0);

  std::ifstream in(path);
  std::string line;
  REQUIRE(std::getline(in, line));
  CHECK(line == "t_s,x_m,v_m_per_s,force_N,output_N,duty,direction");
  std::size_t row = 0;
  while (std::getline(in, line)) {
    REQUIRE(row < trace.samples.size());
    const TelemetrySample& s = trace.samples[row];
    CHECK(line + "\n" == telemetry_csv_line(s));
    // Every number reads back as exactly the traced double.
    std::stringstream fields(line);
    std::string field;
    std::vector<double> values;
    while (std::getline(fields, field, ',')) values.push_back(parse_double(field));
    REQUIRE(values.size() == 7);
    CHECK(values[0] == s.t_s);
    CHECK(values[1] == s.x_m);
    CHECK(values[2] == s.v_m_per_s);
    CHECK(values[3] == s.force_N);
    CHECK(values[4] == s.output_N);
    CHECK(values[5] == s.command.duty);
    CHECK(values[6] == (s.command.direction_high ? 1.0 : 0.0));
    ++row;
  }
  CHECK(row == 1000);
  std::filesystem::remove(path);
}

// The header lines are a public interface (docs/reference/telemetry.md, scripts that read the
// logs): the names written over N give exactly the documented lines.
TEST_CASE("telemetry log: the header lines of one and of two axes") {
  CHECK(csv_header_line(telemetry_columns<1>()) == "t_s,x_m,v_m_per_s,force_N,output_N,duty,direction");
  CHECK(csv_header_line(telemetry_columns<2>()) ==
        "t_s,x_m,y_m,vx_m_per_s,vy_m_per_s,force_x_N,force_y_N,output_x_N,output_y_N,duty_1,direction_1,duty_2,direction_2");
}

TEST_CASE("telemetry log: never written through a link planted at its path, nor into a pipe" *
          doctest::test_suite("threaded")) {
  const auto dir = std::filesystem::temp_directory_path() / ("hapscene_log_link_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto victim = dir / "victim.txt";
  std::ofstream(victim) << "precious\n";
  std::filesystem::create_symlink(victim, dir / "run.csv");
  try {
    TelemetryLog log((dir / "run.csv").string());
    FAIL("the log opened through a link");
  } catch (const InputError& error) {
    CHECK(std::string(error.what()) == (dir / "run.csv").string() + ": is a symbolic link; the log is not written through one");
  }
  std::ifstream in(victim);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text == "precious\n");
  // A named pipe with no reader: refused at once, not waited on.
  REQUIRE(::mkfifo((dir / "pipe.csv").c_str(), 0600) == 0);
  CHECK_THROWS_WITH_AS(TelemetryLog((dir / "pipe.csv").string()),
                       ((dir / "pipe.csv").string() + ": not a regular file; the log is written to files only").c_str(),
                       InputError);
  // A regular file is emptied and written.
  std::ofstream(dir / "old.csv") << "old rows\n";
  {
    TelemetryLog log((dir / "old.csv").string());
    log.finish();
  }
  std::ifstream old(dir / "old.csv");
  std::string header;
  std::getline(old, header);
  CHECK(header.starts_with("t_s,"));
  std::filesystem::remove_all(dir);
}

}  // namespace HAPSCENE_TEST_FILE
