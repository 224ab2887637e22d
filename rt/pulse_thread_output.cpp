#include "rt/pulse_thread_output.hpp"

namespace stepmod::rt {

bool PulseThreadOutput::start(const Options& options) {
  if (running()) return false;
  thread_.emplace(engine_, options);
  return thread_->start();
}

void PulseThreadOutput::stop() {
  if (!thread_) return;
  thread_->stop();
  thread_->join();
}

}  // namespace stepmod::rt
