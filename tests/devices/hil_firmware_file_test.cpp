// `--device hil:PATH` with a file that is not a valid ATmega328P firmware: a clear input
// error, never a crash of hapscene. The firmware this build produced is mutated the ways
// that made simavr crash or abort: truncated, random bytes, another machine, huge
// sections and segments, overlapping segments, and random byte flips in its headers.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/devices/open_device.hpp"
#include "tests/cli/cli_support.hpp"

#if HAPSCENE_HAVE_HIL
#include "engine/devices/hil/firmware_image.hpp"
#include "engine/devices/hil/simulated_board.hpp"

using namespace hapscene;

namespace {

std::vector<std::uint8_t> firmware_bytes() {
  std::ifstream in(default_firmware_elf(), std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string write_temp(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("hapscene_fw_" + std::to_string(getpid()) + "_" + name + ".elf");
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path.string();
}

std::uint32_t get32(const std::vector<std::uint8_t>& b, std::size_t at) {
  return b[at] | (b[at + 1] << 8) | (b[at + 2] << 16) | (static_cast<std::uint32_t>(b[at + 3]) << 24);
}
void put32(std::vector<std::uint8_t>* b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b->at(at + i) = static_cast<std::uint8_t>(v >> (8 * i));
}
void put16(std::vector<std::uint8_t>* b, std::size_t at, std::uint16_t v) {
  b->at(at) = static_cast<std::uint8_t>(v);
  b->at(at + 1) = static_cast<std::uint8_t>(v >> 8);
}

// The section header of `name`, by offset in the file.
std::size_t section_header(const std::vector<std::uint8_t>& b, const std::string& name) {
  const std::uint32_t shoff = get32(b, 32);
  const auto shnum = static_cast<std::uint16_t>(b[48] | (b[49] << 8));
  const auto shstrndx = static_cast<std::uint16_t>(b[50] | (b[51] << 8));
  const std::uint32_t names = get32(b, shoff + shstrndx * 40u + 16);
  for (std::uint16_t i = 0; i < shnum; ++i) {
    const std::size_t at = shoff + i * 40u;
    if (std::strcmp(reinterpret_cast<const char*>(b.data() + names + get32(b, at)), name.c_str()) == 0) return at;
  }
  FAIL("no section " << name);
  return 0;
}

// Loads `bytes` as the board's firmware: "ok", or the InputError's message. Anything
// else (a crash) ends the test binary, which is the failure this test is about.
std::string load(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  const std::string path = write_temp(bytes, name);
  std::string outcome = "ok";
  try {
    SimulatedBoard board(path);
    board.run_until(16'000'000 / 100);
  } catch (const InputError& error) {
    outcome = error.what();
  }
  std::filesystem::remove(path);
  return outcome;
}

}  // namespace

TEST_CASE("hil firmware file: the firmware this build produced passes the checks") {
  const auto bytes = firmware_bytes();
  REQUIRE(bytes.size() > 1000);
  CHECK_NOTHROW(check_avr_firmware(default_firmware_elf()));
  CHECK(load(bytes, "good") == "ok");
}

TEST_CASE("hil firmware file: each kind of damage is an input error naming the file and the problem") {
  const auto good = firmware_bytes();
  struct Case {
    const char* name;
    std::vector<std::uint8_t> bytes;
    const char* expect;
  };
  std::vector<Case> cases;
  cases.push_back({"empty", {}, "too short"});
  for (const std::size_t length : {std::size_t{10}, std::size_t{51}, std::size_t{52}, std::size_t{200},
                                   good.size() / 2, good.size() - 1}) {
    cases.push_back({"truncated", std::vector<std::uint8_t>(good.begin(), good.begin() + static_cast<long>(length)), ""});
  }
  {
    std::mt19937 random(7);
    std::vector<std::uint8_t> noise(good.size());
    for (auto& byte : noise) byte = static_cast<std::uint8_t>(random());
    cases.push_back({"random bytes", noise, "no ELF signature"});
  }
  {
    auto b = good;
    put16(&b, 18, 40);  // ARM
    cases.push_back({"another machine", b, "machine 40, not AVR"});
  }
  {
    auto b = good;
    b[4] = 2;  // 64-bit
    cases.push_back({"64-bit class", b, "32-bit little-endian"});
  }
  {
    auto b = good;
    put32(&b, section_header(b, ".text") + 20, 0xFFFFFFF0u);
    cases.push_back({"huge .text", b, "section .text"});
  }
  {
    auto b = good;
    put32(&b, section_header(b, ".text") + 20, 40000);  // inside the file? no: beyond 32 KB anyway
    cases.push_back({"text beyond flash", b, ""});
  }
  {
    // Compressed (SHF_COMPRESSED): libelf would hand simavr other bytes than the header
    // describes, and simavr read out of bounds (a crash depending on the address layout).
    auto b = good;
    put32(&b, section_header(b, ".symtab") + 8, 0xE800u);
    cases.push_back({"compressed .symtab", b, "compressed or unknown"});
  }
  {
    auto b = good;
    put32(&b, section_header(b, ".bss") + 20, 0x10000);
    cases.push_back({"huge .bss", b, "2 KB of RAM"});
  }
  {
    auto b = good;
    put32(&b, get32(b, 28) + 16, 0x7FFFFFFF);  // first segment's file size
    cases.push_back({"huge segment", b, "load segment 0"});
  }
  {
    auto b = good;
    put32(&b, get32(b, 28) + 32 + 12, 0x100);  // second segment (.data image) loads into .text's flash
    cases.push_back({"overlapping segments", b, "overlap"});
  }
  {
    auto b = good;
    put32(&b, 32, 0xFFFFFF00u);  // section headers beyond the file
    cases.push_back({"section table outside", b, "section header table"});
  }
  {
    auto b = good;
    put16(&b, 50, 200);  // name table index beyond the sections
    cases.push_back({"bad name table index", b, "name table index"});
  }
  {
    auto b = good;
    put32(&b, 24, 0x9001);  // odd entry point beyond flash
    cases.push_back({"entry point", b, "entry point"});
  }
  {
    auto b = good;
    const std::size_t symtab = section_header(b, ".symtab");
    put32(&b, get32(b, symtab + 16) + 16, 0x00FFFFFF);  // symbol 1's name far outside its table
    cases.push_back({"symbol name", b, "name index"});
  }
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const std::string outcome = load(c.bytes, c.name);
    CHECK(outcome.find("not a valid ATmega328P firmware") != std::string::npos);
    CHECK(outcome.find(c.expect) != std::string::npos);
    CHECK(outcome.find("hapscene_fw_") != std::string::npos);  // names the file
  }
}

TEST_CASE("hil firmware file: random damage to the headers never crashes hapscene") {
  const auto good = firmware_bytes();
  // Header bytes: the ELF header, the program headers, and the section header table.
  const std::size_t shoff = get32(good, 32);
  std::vector<std::size_t> header_bytes;
  for (std::size_t i = 0; i < 52 + 3 * 32; ++i) header_bytes.push_back(i);
  for (std::size_t i = shoff; i < good.size(); ++i) header_bytes.push_back(i);
  std::mt19937 random(2024);
  int refused = 0, loaded = 0;
  for (int trial = 0; trial < 150; ++trial) {
    auto b = good;
    const int flips = 1 + static_cast<int>(random() % 6);
    for (int f = 0; f < flips; ++f) {
      b[header_bytes[random() % header_bytes.size()]] = static_cast<std::uint8_t>(random());
    }
    const std::string outcome = load(b, "random" + std::to_string(trial));
    (outcome == "ok" ? loaded : refused) += 1;
  }
  MESSAGE(refused << " damaged files refused, " << loaded << " loaded (damage outside what simavr uses)");
  CHECK(refused + loaded == 150);
  CHECK(refused > 0);
}

TEST_CASE("hil firmware file: the command line exits 2 with the reason") {
  auto b = firmware_bytes();
  put16(&b, 18, 40);
  const std::string path = write_temp(b, "cli");
  const test::CliOutcome outcome = test::run_cli("run environments/wall.json --sim-time --duration 0.1s --device hil:" + path);
  std::filesystem::remove(path);
  CHECK(outcome.exit_code == 2);
  CHECK(outcome.err.find("machine 40, not AVR") != std::string::npos);
}

#else
TEST_CASE("hil firmware file: needs simavr and the AVR toolchain" * doctest::skip()) {}
#endif
