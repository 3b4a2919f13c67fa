// run_stoppable(): long work on a thread of its own, stopped by Ctrl-C (binding.h).
#include <chrono>
#include <future>

#include "binding.h"

namespace mg::python {

void run_stoppable(std::stop_source& stop, const std::function<void()>& work) {
  // Python runs its signal handlers on the main thread only, when the interpreter (or
  // PyErr_CheckSignals) looks: a thread of ours holding nothing but the work waits here.
  constexpr auto kSignalCheckInterval = std::chrono::milliseconds(50);
  std::future<void> done;
  {
    py::gil_scoped_release release;
    done = std::async(std::launch::async, work);
  }
  while (true) {
    std::future_status status = std::future_status::timeout;
    {
      py::gil_scoped_release release;
      status = done.wait_for(kSignalCheckInterval);
    }
    if (status == std::future_status::ready) break;
    if (PyErr_CheckSignals() != 0) {
      py::error_already_set raised;  // (KeyboardInterrupt, or what a handler raised)
      stop.request_stop();
      {
        py::gil_scoped_release release;
        done.wait();
      }
      throw raised;  // the work ended with stopped_error(), or finished first: dropped either way
    }
  }
  done.get();  // the work's own C++ exception, if any
}

}  // namespace mg::python
