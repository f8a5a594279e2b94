#pragma once
// Every long call of the module (simulate, Scene.probe, validate, test) runs its engine
// work through run_interruptible, so Ctrl-C (a notebook's interrupt) reaches Python
// within about kSignalPoll whatever the work is.
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <exception>
#include <thread>

#include "engine/harness/stop_request.hpp"

namespace hapscene::python {

// How often the calling thread lets Python handle signals during a long call.
inline constexpr std::chrono::milliseconds kSignalPoll{20};

// Runs `work(stop)` on a thread of its own, called without the GIL. Meanwhile this thread
// sleeps kSignalPoll at a time and takes the GIL only to let Python run its signal
// handlers (PyErr_CheckSignals; only the main thread gets signals). When a handler raises
// (KeyboardInterrupt), `stop` is set: the harness's scans and runs see it through the
// worker's StopRequestScope (stop_request.hpp), a run that `work` gives `stop` to ends at
// its next tick, and once the worker has ended the handler's exception is raised here
// (whatever the worker threw on the way is dropped). Otherwise the worker's exception, if
// any, is rethrown. Nothing of Python runs on the worker's thread.
template <class Work>
void run_interruptible(Work&& work) {
  std::atomic<bool> stop{false};
  std::atomic<bool> done{false};
  std::exception_ptr failure;
  std::thread worker([&] {
    try {
      const StopRequestScope scope(&stop);
      work(stop);
    } catch (...) {
      failure = std::current_exception();
    }
    done.store(true);
  });
  bool interrupted = false;
  while (!done.load()) {
    std::this_thread::sleep_for(kSignalPoll);
    if (interrupted) continue;
    pybind11::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) {
      interrupted = true;
      stop.store(true);
    }
  }
  worker.join();
  if (interrupted) {
    pybind11::gil_scoped_acquire acquire;
    throw pybind11::error_already_set();
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace hapscene::python
