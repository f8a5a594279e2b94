#include "engine/harness/script_budget.hpp"

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"

namespace hapscene {

void ScriptCreationBudget::require(std::size_t count) const {
  if (create_cpu_s_ < 0.0 || count == 0) return;
  const double needed_s = spent_cpu_s_ + static_cast<double>(count) * create_cpu_s_;
  if (needed_s <= kOpenLoopCreateBudget_s) return;
  throw InputError(printf_string(
      "%s: creating a fresh instance takes %.3g s of CPU time (its top-level code runs every time); "
      "this open-loop evaluation of %zu point%s needs %zu more after the %zu made, about %.3g s in all, over the "
      "%g s budget: fewer points (probe --x), or a cheaper top level",
      who_.c_str(), create_cpu_s_, points_, points_ == 1 ? "" : "s", count, created_, needed_s,
      kOpenLoopCreateBudget_s));
}

void ScriptCreationBudget::charge(double used_s) {
  // The estimate for planned creations: the cheapest so far (the first is often slowed
  // by cold caches); what is really spent is charged in full.
  if (create_cpu_s_ < 0.0 || used_s < create_cpu_s_) create_cpu_s_ = used_s;
  spent_cpu_s_ += used_s;
  ++created_;
}

}  // namespace hapscene
