#pragma once
// Shared by the hot-reload tests.
#include <mutex>
#include <string>
#include <vector>

#include "engine/run/reload_watcher.hpp"

namespace hapscene::test {

// No watcher thread: the test calls poll(), which waits for the load it starts.
inline ReloadWatcherOptions manual_polling() {
  ReloadWatcherOptions options;
  options.poll_period_s = 0.0;
  return options;
}

// Collects a watcher's report lines (from its thread or the test's).
struct Reports {
  std::mutex mutex;
  std::vector<std::string> lines;
  ReloadWatcher::Report sink() {
    return [this](const std::string& line) {
      std::lock_guard lock(mutex);
      lines.push_back(line);
    };
  }
  std::string last() {
    std::lock_guard lock(mutex);
    return lines.empty() ? "" : lines.back();
  }
  std::size_t count() {
    std::lock_guard lock(mutex);
    return lines.size();
  }
};

}  // namespace hapscene::test
