// Ctrl-C during a long library call from Python (binding.h, SigintGuard). The interpreter runs its
// SIGINT handler only between its own instructions, so a call that works for minutes without the GIL
// would ignore Ctrl-C until it ends. While such a call runs on the main thread with Python's default
// handler in place, SIGINT instead sets the library's interrupt request (core/progress.h), which the
// long loops poll; the call unwinds with roadbrdf::Interrupted, which becomes KeyboardInterrupt.
#include <pybind11/pybind11.h>

#include <csignal>
#include <exception>

#include "binding.h"
#include "roadbrdf/core/progress.h"

namespace py = pybind11;

namespace roadbrdf::python {

namespace {

extern "C" void on_sigint(int /*signal*/) { request_interrupt(); }

int guard_depth = 0;  // nested guards (a callback into Python calling the library again): the outer one acts
struct sigaction python_action {};

// Python's default handler (raise KeyboardInterrupt) on the main thread: the only case the guard takes over.
bool takes_over() {
  const py::module_ threading = py::module_::import("threading");
  if (!threading.attr("current_thread")().is(threading.attr("main_thread")())) return false;
  const py::module_ signal = py::module_::import("signal");
  return signal.attr("getsignal")(SIGINT).is(signal.attr("default_int_handler"));
}

}  // namespace

SigintGuard::SigintGuard() {
  if (guard_depth > 0 || !takes_over()) return;
  struct sigaction action {};
  action.sa_handler = on_sigint;
  action.sa_flags = SA_RESTART;  // system calls of the work go on; the loops see the request
  sigemptyset(&action.sa_mask);
  if (sigaction(SIGINT, &action, &python_action) != 0) return;
  clear_interrupt();
  active_ = true;
  ++guard_depth;
}

SigintGuard::~SigintGuard() {
  if (!active_) return;
  --guard_depth;
  sigaction(SIGINT, &python_action, nullptr);
  // A Ctrl-C that came after the last poll (the work ended anyway) is handed to Python, which raises
  // KeyboardInterrupt at its next instruction; one that stopped the work is raised by the translator.
  if (interrupt_requested() && std::uncaught_exceptions() == 0) PyErr_SetInterrupt();
  clear_interrupt();
}

void register_interrupted() {
  // pybind11's translator type is void (*)(std::exception_ptr): the pointer is taken by value.
  py::register_exception_translator([](std::exception_ptr p) {  // NOLINT(performance-unnecessary-value-param)
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Interrupted&) {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
    }
  });
}

}  // namespace roadbrdf::python
