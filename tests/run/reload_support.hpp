#pragma once
// Shared by the hot-reload tests.
#include "engine/run/reload_watcher.hpp"

namespace hapscene::test {

// No watcher thread: the test calls poll(), which waits for the load it starts.
inline ReloadWatcherOptions manual_polling() {
  ReloadWatcherOptions options;
  options.poll_period_s = 0.0;
  return options;
}

}  // namespace hapscene::test
