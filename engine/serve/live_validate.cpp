#include "engine/serve/live_validate.hpp"

#include <httplib.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <optional>

#include <nlohmann/json.hpp>

#include "engine/harness/validate_kind.hpp"
#include "engine/load/environment.hpp"
#include "engine/serve/live_job.hpp"
#include "engine/serve/live_requests.hpp"

namespace hapscene {

using json = nlohmann::json;

template <int N>
void validate_version(const std::string& version, const std::string& path, const std::string& base_dir,
                      const std::atomic<bool>& stopping, httplib::Response& res) {
  try {
    std::optional<json> out = run_job<json>(
        [version, file = path, dir = base_dir] {
          setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
          const EnvironmentOf<N> environment = compile_environment_of<N>(version, file, dir);
          const ValidationReportOf<N> report = validate_environment(environment, {}, HarnessOptions{});
          return json{{"pass", report.pass}, {"table", format_report_table(report)}, {"report", report_to_json(report)}};
        },
        stopping);
    if (!out) {
      error_response(res, 503, "the run is ending");
      return;
    }
    res.set_content(out->dump(), "application/json");
  } catch (const std::exception& error) {
    error_response(res, 400, error.what());
  }
}

#define HAPSCENE_VALIDATE_VERSION(N)                                                                        \
  template void validate_version<N>(const std::string&, const std::string&, const std::string&, \
                                    const std::atomic<bool>&, httplib::Response&);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_VALIDATE_VERSION)
#undef HAPSCENE_VALIDATE_VERSION

}  // namespace hapscene
