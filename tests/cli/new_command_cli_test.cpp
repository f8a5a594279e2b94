// `hapscene new`: every template is a file that loads, validates and passes the spec
// `new spec` writes for it, as written; nothing is overwritten without --force, and no
// symbolic link is written through.
#include <doctest/doctest.h>

#include <filesystem>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

namespace hapscene::test {
namespace {

std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

}  // namespace

// Makes KIND at NAME in `folder`, then its spec, and runs the spec: `test` passing means
// the environment validates (the spec asks passes_validate) and the spec is well formed.
void check_kind_validates(const ScratchFolder& folder, const std::string& kind, const std::string& options,
                          const std::string& environment) {
  CAPTURE(kind);
  CAPTURE(options);
  const std::filesystem::path stem = folder.dir / std::filesystem::path(environment).stem();
  const CliOutcome made = run_cli("new " + kind + " " + quoted(stem) + " " + options);
  REQUIRE_MESSAGE(made.exit_code == 0, made.err);
  CHECK(made.out.find("next:  hapscene validate") != std::string::npos);
  const std::filesystem::path environment_file = folder.dir / environment;
  REQUIRE(std::filesystem::exists(environment_file));
  // Named for what was asked: the environment's name is the file's.
  if (environment_file.extension() == ".json") {
    CHECK(slurp_file(environment_file).find("\"name\": \"" + stem.filename().string() + "\"") != std::string::npos);
  }
  const CliOutcome spec = run_cli("new spec " + quoted(stem));
  REQUIRE_MESSAGE(spec.exit_code == 0, spec.err);
  const std::filesystem::path spec_file = stem.string() + ".test.json";
  CHECK(slurp_file(spec_file).find("\"environment\": \"" + environment + "\"") != std::string::npos);
  const CliOutcome tested = run_cli("test " + quoted(spec_file));
  CHECK_MESSAGE(tested.exit_code == 0, (tested.out + tested.err));
}

TEST_CASE("new: every 1-DOF kind writes a file that validates and passes the spec new writes for it") {
  const ScratchFolder folder("new_kinds_1d");
  check_kind_validates(folder, "spring", "", "a_spring.json");
  check_kind_validates(folder, "wall", "", "a_wall.json");
  check_kind_validates(folder, "damper", "", "a_damper.json");
  check_kind_validates(folder, "texture", "", "a_texture.json");
  check_kind_validates(folder, "script", "", "a_script.lua");
}

// Every 2-DOF kind written and validated through the commands: a sweep (the sanitizer runs
// leave it out; the templates' own cases stay in).
TEST_CASE("new: every 2-DOF kind validates on the Haplink and the 2DIY, its shape away from the handle's home" *
          doctest::test_suite("sweeps")) {
  const ScratchFolder folder("new_kinds_2d");
  check_kind_validates(folder, "box", "", "a_box.json");
  check_kind_validates(folder, "circle", "--device haply2diy_v3", "a_circle.json");
  check_kind_validates(folder, "planar-script", "--device haply2diy_v3", "a_field.json");
  // A profile file by path: the environment names it from its own folder.
  const CliOutcome by_path = run_cli("new box " + quoted(folder.dir / "sub" / "b") + " --device environments/devices/haplink.json");
  CHECK(by_path.exit_code == 2);  // no folder "sub": nothing is created there
  std::filesystem::create_directories(folder.dir / "sub");
  const CliOutcome made = run_cli("new box " + quoted(folder.dir / "sub" / "b") + " --device environments/devices/haplink.json");
  REQUIRE_MESSAGE(made.exit_code == 0, made.err);
  const CliOutcome validated = run_cli("validate -q " + quoted(folder.dir / "sub" / "b.json"));
  CHECK_MESSAGE(validated.exit_code == 0, (validated.out + validated.err));
}

TEST_CASE("new: an existing file is kept unless --force, and a symbolic link is never written through") {
  const ScratchFolder folder("new_overwrite");
  const std::filesystem::path kept = folder.write("mine.json", "{\"effects\": []}\n");
  const CliOutcome refused = run_cli("new wall " + quoted(folder.dir / "mine"));
  CHECK(refused.exit_code == 2);
  CHECK(refused.err.find("mine.json: exists already (--force overwrites it)") != std::string::npos);
  CHECK(slurp_file(kept) == "{\"effects\": []}\n");

  const CliOutcome forced = run_cli("new wall " + quoted(folder.dir / "mine") + " --force");
  CHECK(forced.exit_code == 0);
  CHECK(slurp_file(kept).find("\"type\": \"wall\"") != std::string::npos);

  // A link planted where the file goes: refused with or without --force; its target unchanged.
  const std::filesystem::path target = folder.write("target.txt", "precious\n");
  std::filesystem::create_symlink(target, folder.dir / "linked.json");
  for (const char* force : {"", " --force"}) {
    const CliOutcome linked = run_cli("new spring " + quoted(folder.dir / "linked") + force);
    CHECK(linked.exit_code == 2);
    CHECK(slurp_file(target) == "precious\n");
  }
  // A planar-script writes two files: when the second exists, neither is written.
  folder.write("pair.json", "{}\n");
  const CliOutcome pair = run_cli("new planar-script " + quoted(folder.dir / "pair"));
  CHECK(pair.exit_code == 2);
  CHECK_FALSE(std::filesystem::exists(folder.dir / "pair.lua"));
}

TEST_CASE("new: a wrong kind, name or option is invalid input that says what is expected") {
  const CliOutcome misspelt = run_cli("new wal x");
  CHECK(misspelt.exit_code == 2);
  CHECK(misspelt.err.find("unknown kind \"wal\" (did you mean \"wall\"?)") != std::string::npos);
  const CliOutcome missing = run_cli("new wall");
  CHECK(missing.exit_code == 2);
  CHECK(missing.err.find("expected KIND NAME") != std::string::npos);
  const CliOutcome one_axis_device = run_cli("new wall x --device haplink");
  CHECK(one_axis_device.exit_code == 2);
  CHECK(one_axis_device.err.find("--device: only for the 2-DOF kinds") != std::string::npos);
  const CliOutcome no_environment = run_cli("new spec /nonexistent/folder/nothing");
  CHECK(no_environment.exit_code == 2);
  CHECK(no_environment.err.find("no /nonexistent/folder/nothing.json or /nonexistent/folder/nothing.lua") !=
        std::string::npos);
  const CliOutcome not_planar = run_cli("new box x --device hapkit3");
  CHECK(not_planar.exit_code == 2);
}

}  // namespace hapscene::test
