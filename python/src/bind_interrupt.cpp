// Ctrl-C (and SIGTERM where Python handles it) during a long library call from Python (binding.h,
// SigintGuard). The interpreter runs its signal handlers only between its own instructions, so a call
// that works for minutes without the GIL would ignore Ctrl-C until it ends. While such a call runs on
// the main thread, SIGINT and SIGTERM, when Python has a handler of its own for them (the default
// handler of SIGINT raises KeyboardInterrupt; `roadbrdf report` and `study` handle SIGTERM), set the
// library's interrupt request instead (core/progress.h), which the long loops poll; the call unwinds
// with roadbrdf::Interrupted. The signal is then handed back to Python, whose handler raises.
#include <pybind11/pybind11.h>

#include <array>
#include <atomic>
#include <csignal>
#include <exception>

#include "binding.h"
#include "roadbrdf/core/progress.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

constexpr std::array<int, 2> kSignals = {SIGINT, SIGTERM};

std::atomic<int> pending_signal{0};  // lock-free: set by the handler
static_assert(std::atomic<int>::is_always_lock_free);

extern "C" void on_signal(int signal_number) {
  pending_signal.store(signal_number, std::memory_order_relaxed);
  request_interrupt();
}

int guard_depth = 0;  // nested guards (a callback into Python calling the library again): the outer one acts
std::array<struct sigaction, kSignals.size()> python_actions{};
std::array<bool, kSignals.size()> taken{};

// Python runs a handler of its own for the signal (not the default action, not ignored).
bool python_handles(const py::module_& signal, int signal_number) {
  const py::object handler = signal.attr("getsignal")(signal_number);
  return !handler.is_none() && !handler.equal(signal.attr("SIG_DFL")) && !handler.equal(signal.attr("SIG_IGN"));
}

// Hands a signal that stopped (or came during) the work to Python: its handler runs at the next check.
void hand_back(int signal_number) {
#if PY_VERSION_HEX >= 0x030A0000
  PyErr_SetInterruptEx(signal_number);
#else
  if (signal_number == SIGINT) PyErr_SetInterrupt();
#endif
}

}  // namespace

SigintGuard::SigintGuard() {
  if (guard_depth > 0) return;
  const py::module_ threading = py::module_::import("threading");
  if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return;
  const py::module_ signal = py::module_::import("signal");
  pending_signal.store(0);
  clear_interrupt();
  for (std::size_t k = 0; k < kSignals.size(); ++k) {
    taken[k] = false;
    if (!python_handles(signal, kSignals[k])) continue;
    struct sigaction action {};
    action.sa_handler = on_signal;
    action.sa_flags = SA_RESTART;  // system calls of the work go on; the loops see the request
    sigemptyset(&action.sa_mask);
    taken[k] = sigaction(kSignals[k], &action, &python_actions[k]) == 0;
    active_ = active_ || taken[k];
  }
  if (active_) ++guard_depth;
}

SigintGuard::~SigintGuard() {
  if (!active_) return;
  --guard_depth;
  for (std::size_t k = 0; k < kSignals.size(); ++k) {
    if (taken[k]) sigaction(kSignals[k], &python_actions[k], nullptr);
  }
  const int signal_number = pending_signal.exchange(0);
  if (signal_number != 0) hand_back(signal_number);
  clear_interrupt();
}

void register_interrupted() {
  // pybind11's translator type is void (*)(std::exception_ptr): the pointer is taken by value.
  py::register_exception_translator([](std::exception_ptr p) {  // NOLINT(performance-unnecessary-value-param)
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Interrupted&) {
      // The guard handed the signal back: Python's handler raises its exception here (KeyboardInterrupt for
      // Ctrl-C); one that does not raise still leaves the work stopped, reported as KeyboardInterrupt.
      if (PyErr_CheckSignals() == 0) PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
}

}  // namespace roadbrdf::python
