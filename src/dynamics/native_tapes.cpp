// Dynamics on machine code (docs/theory.md §8): NativeTapes and the Dynamics methods that choose
// it. The interpreter and the library compute the same bits, so switching from one to the other
// in the middle of a run (Background mode) changes no result.

#include "dynamics/native_tapes.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace lagrange {

namespace dynamics {

void NativeTapes::reset() {
  cancel.store(true);
  if (worker.joinable()) worker.join();
  cancel.store(false);
  ready.store(false, std::memory_order_release);
  const std::lock_guard<std::mutex> lock(mutex);
  library.reset();
  why.clear();
  skipped.clear();
  cache_note.clear();
  shared_key.clear();
}

void NativeTapes::publish(std::shared_ptr<const MachineCode> lib) {
  for (size_t i = 0; i < functions.size(); ++i) functions[i] = lib->function(i);
  {
    const std::lock_guard<std::mutex> lock(mutex);
    library = std::move(lib);
  }
  ready.store(true, std::memory_order_release);
}

void NativeTapes::fail(const std::string& reason) {
  const std::lock_guard<std::mutex> lock(mutex);
  why = reason;
}

void NativeTapes::skip(const std::string& reason) {
  const std::lock_guard<std::mutex> lock(mutex);
  skipped = reason;
}

std::string NativeTapes::error() const {
  const std::lock_guard<std::mutex> lock(mutex);
  return why;
}

void NativeTapes::start(const std::vector<const Tape*>& tapes) {
  reset();
  if (mode == Evaluation::Interpreter) return;
  functions.assign(tapes.size(), nullptr);
  MachineCodeOptions opts = options;
  opts.cancel = &cancel;
  try {
    if (mode == Evaluation::MachineCode) {
      publish(MachineCode::build(tapes, opts));
      return;
    }
    std::string rejected;
    auto lib = MachineCode::cached(tapes, opts, &rejected);
    if (!rejected.empty()) {
      const std::lock_guard<std::mutex> lock(mutex);
      cache_note = rejected;
    }
    if (lib) {
      publish(std::move(lib));
      return;
    }
  } catch (const MachineCodeError& e) {
    fail(e.what());
    return;
  }
  if (tapes[0]->num_instructions() < min_instructions) {
    skip(fmt::format("the {}-instruction tape interprets faster than it compiles",
                     tapes[0]->num_instructions()));
    return;
  }
  // The worker owns copies of the tapes: the Dynamics may re-specialise its own meanwhile
  // (set_parameters joins the worker first, but a copy keeps the thread independent of it).
  std::vector<Tape> copies;
  for (const Tape* t : tapes) copies.push_back(*t);
  opts.interrupted = nullptr;  // the caller's poll is not for this thread; reset() cancels
  worker = std::thread([this, copies = std::move(copies), opts]() {
    std::vector<const Tape*> ptrs;
    for (const Tape& t : copies) ptrs.push_back(&t);
    try {
      publish(MachineCode::build(ptrs, opts));
    } catch (const MachineCodeError& e) {
      fail(e.what());
    }
  });
}

void NativeTapes::start_shared(const std::vector<const Tape*>& tapes,
                               const std::vector<size_t>& offsets) {
  std::string key;
  for (size_t i = 0; i < tapes.size(); ++i)
    key += tapes[i]->to_shared_c(fmt::format("f{}", i), offsets[i]);
  if (key == shared_key) return;  // the loaded library reads the new constants
  reset();
  functions.assign(tapes.size(), nullptr);
  shared_key = std::move(key);
  MachineCodeOptions opts = options;
  opts.cancel = &cancel;
  opts.constants_at = offsets;
  try {
    publish(MachineCode::build(tapes, opts));
  } catch (const MachineCodeError& e) {
    fail(e.what());
  }
}

std::string NativeTapes::note() const {
  const std::lock_guard<std::mutex> lock(mutex);
  if (ready.load(std::memory_order_acquire) && library) {
    if (library->from_cache()) return "machine code (from the cache)";
    const std::string& replaced = library->note().empty() ? cache_note : library->note();
    return fmt::format("machine code (compiled in {:.2f} s{}{})", library->seconds(),
                       replaced.empty() ? "" : "; ", replaced);
  }
  const std::string also = cache_note.empty() ? "" : "; " + cache_note;
  if (!why.empty()) return fmt::format("interpreter (machine code: {}{})", why, also);
  if (!skipped.empty()) return fmt::format("interpreter ({}{})", skipped, also);
  if (worker.joinable()) return fmt::format("interpreter (machine code still compiling{})", also);
  return "interpreter" + (also.empty() ? "" : " (" + cache_note + ")");
}

}  // namespace dynamics

void Dynamics::set_evaluation(Evaluation mode, const MachineCodeOptions& options) {
  if (!native_) native_ = std::make_unique<dynamics::NativeTapes>();
  native_->mode = mode;
  native_->options = options;
  refresh_machine_code();
}

void Dynamics::refresh_machine_code() {
  if (!native_) return;
  const std::vector<const Tape*> tapes{&dyn_, &obs_, &sig_};
  if (native_->mode != Evaluation::SharedMachineCode) {
    native_->start(tapes);
    return;
  }
  // docs/theory.md §9.3: each tape's constants follow the registers in work_.
  work_.resize(std::max({dyn_.work_size(), obs_.work_size(), sig_.work_size(), size_t{1}}));
  std::vector<size_t> offsets;
  for (const Tape* t : tapes) {
    offsets.push_back(work_.size());
    const std::vector<double> k = t->constants();
    work_.insert(work_.end(), k.begin(), k.end());
  }
  native_->start_shared(tapes, offsets);
}

bool Dynamics::uses_machine_code() const {
  return native_ && native_->function(dynamics::kDynamicsTape) != nullptr;
}

std::string Dynamics::machine_code_error() const {
  return native_ ? native_->error() : std::string();
}

std::string Dynamics::evaluation_note() const {
  return native_ ? native_->note() : "interpreter";
}

}  // namespace lagrange
