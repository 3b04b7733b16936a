#include "cli/interrupt.hpp"

#include <unistd.h>

#include <csignal>

#include "compile/c_compiler.hpp"

namespace lagrange::cli {

namespace {

std::atomic<bool> g_interrupt{false};
std::atomic<bool> g_keep_work{false};

extern "C" void on_sigint(int) {
  if (!g_keep_work.load()) {
    kill_running_c_compilers();  // in process groups of their own: the terminal's ^C misses them
    static const char message[] = "\nlagrange: interrupted\n";
    (void)!write(STDERR_FILENO, message, sizeof message - 1);
    _exit(130);  // async-signal-safe; nothing has been written that needs finishing
  }
  g_interrupt.store(true);
}

}  // namespace

std::atomic<bool>* install_sigint_handler() {
  struct sigaction action {};
  action.sa_handler = on_sigint;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  return &g_interrupt;
}

KeepWorkOnInterrupt::KeepWorkOnInterrupt() : previous_(g_keep_work.exchange(true)) {}

KeepWorkOnInterrupt::~KeepWorkOnInterrupt() {
  g_keep_work.store(previous_);
}

}  // namespace lagrange::cli
