#include "ipc/client.hpp"

#include <sched.h>

#include <cstring>
#include <thread>

#include "ipc/snapshot.hpp"

namespace stepmod::ipc {
namespace {
// How long a writer waits for another writer's odd sequence before assuming it died.
constexpr std::int64_t kStaleWriterNs = STEPMOD_SEQ_STALE_NS;
}  // namespace

Client::Client(const std::string& name) : name_(name) {
  check_name(name);
  img_ = open_checked<stepmod_image_t>(map_, image_object(name), STEPMOD_IMAGE_SIZE,
                                       {STEPMOD_IMAGE_MAGIC, STEPMOD_LAYOUT_VERSION,
                                        "a stepmod image", "; daemon still starting?", "layout"});
  const std::string path = "/dev/shm" + image_object(name);
  const auto type = module_type_from_number(img_->module_type);
  if (!type) {
    throw IpcError(path + " names unknown module type " + std::to_string(img_->module_type));
  }
  shape_ = shape_of(*type);
  if (img_->word_bytes != shape_.word_bytes || img_->output_words != shape_.output_words ||
      img_->input_words != shape_.input_words) {
    throw IpcError(path + " has a shape (word size or word counts) that is not the " +
                   std::to_string(img_->module_type) + "'s");
  }
}

bool Client::read_inputs(ImageWords& in) const noexcept {
  return read_snapshot(&img_->input_seq, &img_->input_image, shape_.word_bytes, shape_.input_words,
                       kReadTries, in);
}

Health Client::read_health() const noexcept {
  Health h;
  for (unsigned t = 0; t < kReadTries; ++t) {
    if (t > 0 && t % 32u == 0) sched_yield();
    const std::uint32_t s0 = __atomic_load_n(&img_->input_seq, __ATOMIC_ACQUIRE);
    if ((s0 & 1u) != 0) continue;
    h.flags = __atomic_load_n(&img_->health_flags, __ATOMIC_ACQUIRE);
    h.late_faults = __atomic_load_n(&img_->late_faults, __ATOMIC_ACQUIRE);
    h.worst_late_us = __atomic_load_n(&img_->worst_late_us, __ATOMIC_ACQUIRE);
    if (__atomic_load_n(&img_->input_seq, __ATOMIC_RELAXED) == s0) break;
  }
  return h;
}

bool Client::read_outputs(ImageWords& out) const noexcept {
  return read_snapshot(&img_->output_seq, &img_->output_image, shape_.word_bytes,
                       shape_.output_words, kReadTries, out);
}

void Client::require_writable() const {
  if (!map_.writable()) {
    throw IpcError("/dev/shm" + image_object(name_) + " is read-only for this user (" + kGroupHint +
                   ")");
  }
}

void Client::write_outputs(const ImageWords& out) {
  require_writable();
  const std::uint32_t odd = stepmod_seq_write_begin(&img_->output_seq, kStaleWriterNs);
  for (unsigned i = 0; i < shape_.output_words; ++i) {
    stepmod_word_store(&img_->output_image, shape_.word_bytes, i, out.w[i]);
  }
  stepmod_seq_write_end(&img_->output_seq, odd);
}

void Client::update_outputs(const std::function<void(ImageWords&)>& edit) {
  require_writable();
  const std::uint32_t odd = stepmod_seq_write_begin(&img_->output_seq, kStaleWriterNs);
  // Holding the sequence odd makes us the only writer, so a plain read of the words is current.
  ImageWords w;
  for (unsigned i = 0; i < shape_.output_words; ++i) {
    w.w[i] = stepmod_word_load(&img_->output_image, shape_.word_bytes, i);
  }
  edit(w);
  for (unsigned i = 0; i < shape_.output_words; ++i) {
    stepmod_word_store(&img_->output_image, shape_.word_bytes, i, w.w[i]);
  }
  stepmod_seq_write_end(&img_->output_seq, odd);
}

void Client::write_word(unsigned index, std::int32_t value) {
  if (index >= shape_.output_words) {
    throw IpcError("output word " + std::to_string(index) + " out of range 0.." +
                   std::to_string(shape_.output_words - 1));
  }
  update_outputs([&](ImageWords& w) { w.w[index] = value; });
}

std::uint64_t Client::scan_counter() const noexcept {
  return __atomic_load_n(&img_->scan_counter, __ATOMIC_ACQUIRE);
}

bool Client::wait_scan_counter(std::uint64_t target, std::chrono::milliseconds timeout) const {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  // Polling at 100 us: scans are >= 250 us apart, and a client has no futex to wait on.
  while (scan_counter() < target) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  return true;
}

bool Client::wait_scans(std::uint64_t n, std::chrono::milliseconds timeout) const {
  return wait_scan_counter(scan_counter() + n, timeout);
}

void Client::heartbeat() {
  require_writable();
  __atomic_fetch_add(&img_->plc_heartbeat, 1u, __ATOMIC_RELEASE);
}

std::uint64_t Client::heartbeat_value() const noexcept {
  return __atomic_load_n(&img_->plc_heartbeat, __ATOMIC_ACQUIRE);
}

std::optional<std::int32_t> Client::send_message(std::span<const std::int32_t> data,
                                                 std::chrono::milliseconds timeout) {
  require_writable();
  for (unsigned i = 0; i < STEPMOD_MSG_DINTS; ++i) {
    const std::int32_t v = i < data.size() ? data[i] : 0;
    __atomic_store_n(&img_->msg_data[i], v, __ATOMIC_RELAXED);
  }
  // Release: the module that sees the new request sequence sees the data written above.
  const std::uint32_t seq = __atomic_add_fetch(&img_->msg_request_seq, 1u, __ATOMIC_RELEASE);
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (__atomic_load_n(&img_->msg_done_seq, __ATOMIC_ACQUIRE) != seq) {
    if (std::chrono::steady_clock::now() >= deadline) return std::nullopt;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return __atomic_load_n(&img_->msg_result, __ATOMIC_RELAXED);
}

stepmod_reason_t Client::read_reason(unsigned axis) const noexcept {
  stepmod_reason_t r{};
  if (axis >= shape_.axes || !stepmod_read_reason(img_, axis, &r)) return stepmod_reason_t{};
  return r;
}

std::optional<stepmod_unit_state_t> Client::read_unit_state(unsigned axis) const noexcept {
  stepmod_unit_state_t u{};
  if (axis >= shape_.axes || !stepmod_read_unit_state(img_, axis, &u)) return std::nullopt;
  return u;
}

stepmod_image_t& Client::writable_image() {
  require_writable();
  return *img_;
}

}  // namespace stepmod::ipc
