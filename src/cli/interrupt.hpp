#pragma once
// Ctrl-C for the command line (docs/errors.md, "Interruption"). While a command reads, derives,
// compiles or checks a model it has written nothing, so SIGINT ends the process at once with
// exit 130 (a read blocked on a FIFO and a slow `check` included). Around a run that keeps what
// it computed (simulate's integration and output, a sweep) it only sets the flag the run polls.

#include <atomic>

namespace lagrange::cli {

/// Installs the SIGINT handler; returns the flag runs poll (Options::interrupt).
std::atomic<bool>* install_sigint_handler();

/// While one exists, SIGINT sets the flag instead of ending the process.
class KeepWorkOnInterrupt {
 public:
  KeepWorkOnInterrupt();
  ~KeepWorkOnInterrupt();
  KeepWorkOnInterrupt(const KeepWorkOnInterrupt&) = delete;
  KeepWorkOnInterrupt& operator=(const KeepWorkOnInterrupt&) = delete;

 private:
  bool previous_;
};

}  // namespace lagrange::cli
