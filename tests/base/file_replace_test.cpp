// Every whole file hapscene writes (the live view's save, reports, figures, profiles)
// goes through replace_file: a new file of its own name in the same folder, created
// exclusively and never through a link, renamed over the path. A link planted anywhere
// near is left alone, the file keeps its permissions, nothing is left behind.
#include <doctest/doctest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>

#include "engine/base/file_replace.hpp"
#include "engine/cli/output_file.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

using namespace hapscene;

namespace {

int entries_in(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

mode_t mode_of(const std::string& path) {
  struct stat s {};
  REQUIRE(::lstat(path.c_str(), &s) == 0);
  return s.st_mode;
}

}  // namespace

TEST_CASE("replace_file: a file is replaced whole and keeps its permission bits, whatever the umask") {
  test::ScratchFolder scratch("replace_mode");
  const std::string path = scratch.write("env.json", "old").string();
  REQUIRE(::chmod(path.c_str(), 0604) == 0);
  const mode_t umask_before = ::umask(0077);
  const FileWriteOutcome outcome = replace_file(path, "new text", SpecialPath::refuse);
  ::umask(umask_before);
  CHECK(outcome.ok());
  CHECK(test::slurp_file(path) == "new text");
  CHECK((mode_of(path) & 07777) == 0604);
  CHECK(entries_in(scratch.dir) == 1);
}

TEST_CASE("replace_file: a link at the path is replaced, not followed, and links planted next to it are never written through") {
  test::ScratchFolder scratch("replace_link");
  const std::string victim = scratch.write("victim.txt", "precious").string();
  const std::string path = (scratch.dir / "report.json").string();
  std::filesystem::create_symlink(victim, path);
  for (const char* name : {"report.json.hapscene-save", ".report.json.tmp", "report.json.tmp"}) {
    std::filesystem::create_symlink(victim, scratch.dir / name);
  }
  CHECK(replace_file(path, "{}", SpecialPath::write_through).ok());
  CHECK(test::slurp_file(victim) == "precious");
  CHECK(S_ISREG(mode_of(path)));
  CHECK(test::slurp_file(path) == "{}");
  CHECK(entries_in(scratch.dir) == 5);
}

TEST_CASE("replace_file: a pipe is refused for an environment, a device is written through for an output") {
  test::ScratchFolder scratch("replace_special");
  const std::string pipe = scratch.fifo("env.json");
  const FileWriteOutcome refused = replace_file(pipe, "x", SpecialPath::refuse);
  CHECK(refused.failed == FileWriteStep::open);
  CHECK(refused.error_number == EINVAL);
  CHECK(S_ISFIFO(mode_of(pipe)));
  CHECK(replace_file("/dev/null", "x", SpecialPath::write_through).ok());
  CHECK(S_ISCHR(mode_of("/dev/null")));
  // A folder that is not there: nothing is created, the open step is named.
  const FileWriteOutcome missing = replace_file((scratch.dir / "no" / "x.json").string(), "x", SpecialPath::write_through);
  CHECK(missing.failed == FileWriteStep::open);
  CHECK(missing.error_number == ENOENT);
  CHECK(entries_in(scratch.dir) == 1);
}

TEST_CASE("output files: write_output_file replaces the file, and a new one gets the umask's permissions") {
  test::ScratchFolder scratch("replace_output");
  const std::string path = (scratch.dir / "figure.svg").string();
  const mode_t umask_before = ::umask(0022);
  write_output_file(path, "<svg/>");
  ::umask(umask_before);
  CHECK(test::slurp_file(path) == "<svg/>");
  CHECK((mode_of(path) & 07777) == 0644);
  CHECK_THROWS_AS(write_output_file((scratch.dir / "no" / "x.svg").string(), "x"), InputError);
}
