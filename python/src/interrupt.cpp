#include "interrupt.hpp"

namespace py = pybind11;

namespace lagrange::python {

namespace {

std::atomic<bool> g_sigint{false};

extern "C" void on_sigint(int) {
  g_sigint.store(true);
}

// Whether this thread is Python's main thread, the one signal handlers run on.
bool on_main_thread() {
  const py::module_ threading = py::module_::import("threading");
  return threading.attr("current_thread")().is(threading.attr("main_thread")());
}

// Whether SIGINT goes to a Python function (not SIG_IGN, SIG_DFL or a handler set outside Python).
bool python_handles_sigint() {
  const py::object handler = py::module_::import("signal").attr("getsignal")(SIGINT);
  return !handler.is_none() && PyCallable_Check(handler.ptr());
}

}  // namespace

InterruptibleRun::InterruptibleRun() {
  if (!on_main_thread() || !python_handles_sigint()) return;
  // A Ctrl-C that came before the run (Python has not run its handler yet) is Python's.
  g_sigint.store(false);
  struct sigaction action {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  installed_ = sigaction(SIGINT, &action, &previous_) == 0;
}

InterruptibleRun::~InterruptibleRun() {
  // Left by an exception before raised(): a Ctrl-C that came meanwhile is still Python's.
  const bool was_installed = installed_;
  restore();
  if (was_installed && g_sigint.exchange(false)) PyErr_SetInterrupt();
}

void InterruptibleRun::restore() {
  if (!installed_) return;
  sigaction(SIGINT, &previous_, nullptr);
  installed_ = false;
}

const std::atomic<bool>* InterruptibleRun::flag() const {
  return installed_ ? &g_sigint : nullptr;
}

bool InterruptibleRun::raised() {
  const bool was_installed = installed_;
  restore();
  if (!was_installed || !g_sigint.exchange(false)) return false;
  PyErr_SetInterrupt();  // SIGINT as though it came now: Python's handler runs at the check
  return PyErr_CheckSignals() != 0;
}

void InterruptibleRun::throw_with(
    std::initializer_list<std::pair<const char*, py::handle>> attributes) {
  PyObject *type = nullptr, *error = nullptr, *traceback = nullptr;
  PyErr_Fetch(&type, &error, &traceback);
  PyErr_NormalizeException(&type, &error, &traceback);
  for (const auto& [name, value] : attributes)
    if (error != nullptr && PyObject_SetAttrString(error, name, value.ptr()) != 0) PyErr_Clear();
  PyErr_Restore(type, error, traceback);
  throw py::error_already_set();
}

}  // namespace lagrange::python
