#include "engine/serve/live_job.hpp"

#include "engine/serve/live_view.hpp"

namespace hapscene {
namespace {

std::atomic<std::uint64_t> g_abandoned_jobs{0};

}  // namespace

void count_abandoned_live_view_job() noexcept { ++g_abandoned_jobs; }

std::uint64_t abandoned_live_view_jobs() noexcept { return g_abandoned_jobs.load(); }

}  // namespace hapscene
