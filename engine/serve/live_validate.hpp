#pragma once
// POST /api/validate: the harness on the live view's current values, on a job's thread at
// a lower priority than the run (off the loop); the verdict table and the report.
#include <atomic>
#include <string>

namespace httplib {
struct Response;
}

namespace hapscene {

// Validates `version` (the environment's text; `path` names it, relative paths from
// `base_dir`): 200 {"pass", "table", "report"}, 400 with the loader's words, 503 when
// `stopping` was set first. One at a time is the caller's to see to.
template <int N>
void validate_version(const std::string& version, const std::string& path, const std::string& base_dir,
                      const std::atomic<bool>& stopping, httplib::Response& res);

}  // namespace hapscene
