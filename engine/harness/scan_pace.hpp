#pragma once
// The scripts' pace in the harness's open-loop scans (OpenLoop): how much CPU time their
// calls may take there. pace.hpp has the loop's own pace checks and the failure they
// share (ScriptsTooSlow, pace_failure).
#include <cstdint>

#include "engine/scene/scene.hpp"

namespace hapscene {

struct CheckResult;

// Calls per measuring window (here and in pace.hpp's checks).
inline constexpr std::uint64_t kPaceWindowCalls = 200;

// The share of the tick period a script call may take, on average, in the harness's
// open-loop scans (ScanPace). The loop gives a script the whole period per call, but a
// check calls it far more often than its runs do: validate's field scan and a test spec's
// scans make 10^4 calls in 1-D and up to 2 x 10^5 in 2-D (8436 grid points at 19
// velocities and times), 200 s at the loop's pace at 1 kHz. At a tenth of the period
// those scans take at most 20 s, about what the check's closed-loop runs take a script
// at the loop's full pace; ordinary scripts (1-10 us a call) stay ten times under it.
inline constexpr double kScanPaceShare = 0.1;

// The CPU time of the scripts' calls in an open-loop scan, per window of kPaceWindowCalls
// calls (creating instances is not a call: ScriptCreationBudget bounds that): charge()
// is false once a window's calls took more than kScanPaceShare of a period each on
// average, or more than a whole window allows at any time, so the evaluation stops
// after about one window of a slow script instead of taking minutes.
class ScanPace {
 public:
  explicit ScanPace(double period_s) : allowed_per_call_s_(period_s * kScanPaceShare) {}

  // Charges `calls` calls that took `cpu_s` of CPU time.
  bool charge(double cpu_s, std::uint64_t calls) noexcept;
  // The failed "pace" check (only after charge() was false).
  template <int N>
  CheckResult check(const SceneOf<N>& scene) const;

 private:
  double allowed_per_call_s_;
  double window_s_{};
  std::uint64_t window_calls_{};
  std::uint64_t calls_{};  // all calls charged
  bool too_slow_{};
};

}  // namespace hapscene
