// hapscene_fuzz_replay TARGET PATH...: runs every file under the PATHs (folders
// recursively, in sorted order) through one fuzz target, without libFuzzer. ctest uses it
// to replay the committed corpora (seeds and minimized crashers) in every build, so a
// fixed finding stays fixed under g++ too. A failing input aborts with its name printed.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#define HAPSCENE_FUZZ_TARGET(name) \
  extern "C" int hapscene_fuzz_##name(const std::uint8_t* data, std::size_t size);
#include "fuzz_targets.def"
#undef HAPSCENE_FUZZ_TARGET

namespace {

struct Target {
  const char* name;
  int (*run)(const std::uint8_t*, std::size_t);
};

constexpr Target kTargets[] = {
#define HAPSCENE_FUZZ_TARGET(name) {#name, hapscene_fuzz_##name},
#include "fuzz_targets.def"
#undef HAPSCENE_FUZZ_TARGET
};

std::vector<std::filesystem::path> files_under(const std::filesystem::path& path) {
  std::vector<std::filesystem::path> files;
  if (std::filesystem::is_directory(path)) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(path)) {
      if (entry.is_regular_file()) files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
  } else {
    files.push_back(path);
  }
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  const Target* target = nullptr;
  for (const Target& t : kTargets) {
    if (argc > 1 && std::strcmp(argv[1], t.name) == 0) target = &t;
  }
  if (argc < 3 || target == nullptr) {
    std::fprintf(stderr, "usage: hapscene_fuzz_replay TARGET FILE_OR_FOLDER...\ntargets:");
    for (const Target& t : kTargets) std::fprintf(stderr, " %s", t.name);
    std::fprintf(stderr, "\n");
    return 2;
  }
  std::size_t replayed = 0;
  for (int i = 2; i < argc; ++i) {
    if (!std::filesystem::exists(argv[i])) {
      std::fprintf(stderr, "%s: no such file or folder\n", argv[i]);
      return 2;
    }
    for (const std::filesystem::path& file : files_under(argv[i])) {
      std::ifstream in(file, std::ios::binary);
      const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      // Printed first, so an abort names its input.
      std::fprintf(stderr, "%s %s\n", target->name, file.string().c_str());
      target->run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++replayed;
    }
  }
  std::printf("%s: %zu inputs replayed\n", target->name, replayed);
  return 0;
}
