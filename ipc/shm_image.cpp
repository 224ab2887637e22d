#include "ipc/shm_image.hpp"

#include <unistd.h>

#include <cstring>

#include "ipc/snapshot.hpp"

namespace stepmod::ipc {

ShmImage::ShmImage(const std::string& name, const ModuleShape& shape) : name_(name), shape_(shape) {
  check_name(name);
  if ((shape.word_bytes != 2 && shape.word_bytes != 4) || shape.output_words > STEPMOD_MAX_WORDS ||
      shape.input_words > STEPMOD_MAX_WORDS) {
    throw IpcError("module shape does not fit the image layout");
  }
  map_ = ShmMapping::create(image_object(name), STEPMOD_IMAGE_SIZE, STEPMOD_IMAGE_MAGIC,
                            STEPMOD_OFF_OWNER_PID);
  img_ = static_cast<stepmod_image_t*>(map_.data());
  img_->version = STEPMOD_LAYOUT_VERSION;
  img_->module_type = static_cast<std::uint32_t>(shape.type);
  img_->word_bytes = shape.word_bytes;
  img_->output_words = shape.output_words;
  img_->input_words = shape.input_words;
  img_->owner_pid = static_cast<std::uint64_t>(::getpid());
  // The magic goes in last: a client that sees it sees a whole header.
  stepmod_publish_magic(img_->magic, STEPMOD_IMAGE_MAGIC);
}

bool ShmImage::read_outputs(ImageWords& out) const noexcept {
  return read_snapshot(&img_->output_seq, &img_->output_image, shape_.word_bytes,
                       shape_.output_words, kReadTries, out);
}

void ShmImage::publish_inputs(const ImageWords& in) noexcept {
  // Only the module writes the input image, so the lock is always free (stale_ns 0 never waits;
  // the pulse/control threads must not block on a foreign process).
  const std::uint32_t odd = stepmod_seq_write_begin(&img_->input_seq, 0);
  for (unsigned i = 0; i < shape_.input_words; ++i) {
    stepmod_word_store(&img_->input_image, shape_.word_bytes, i, in.w[i]);
  }
  __atomic_store_n(&img_->health_flags, health_flags_, __ATOMIC_RELEASE);
  __atomic_store_n(&img_->late_faults, late_faults_, __ATOMIC_RELEASE);
  stepmod_seq_write_end(&img_->input_seq, odd);
  __atomic_fetch_add(&img_->scan_counter, 1u, __ATOMIC_RELEASE);
}

std::uint64_t ShmImage::scan_counter() const noexcept {
  return __atomic_load_n(&img_->scan_counter, __ATOMIC_ACQUIRE);
}

std::uint32_t ShmImage::health_flags() const noexcept {
  return __atomic_load_n(&img_->health_flags, __ATOMIC_ACQUIRE);
}

std::uint32_t ShmImage::late_faults() const noexcept {
  return __atomic_load_n(&img_->late_faults, __ATOMIC_ACQUIRE);
}

std::uint64_t ShmImage::heartbeat() const noexcept {
  return __atomic_load_n(&img_->plc_heartbeat, __ATOMIC_ACQUIRE);
}

std::optional<BlendMessage> ShmImage::pending_message() const noexcept {
  const std::uint32_t req = __atomic_load_n(&img_->msg_request_seq, __ATOMIC_ACQUIRE);
  if (req == __atomic_load_n(&img_->msg_done_seq, __ATOMIC_RELAXED)) return std::nullopt;
  BlendMessage m;
  m.seq = req;
  for (unsigned i = 0; i < STEPMOD_MSG_DINTS; ++i) {
    m.data[i] = __atomic_load_n(&img_->msg_data[i], __ATOMIC_RELAXED);
  }
  return m;
}

void ShmImage::finish_message(std::uint32_t seq, std::int32_t result) noexcept {
  __atomic_store_n(&img_->msg_result, result, __ATOMIC_RELAXED);
  __atomic_store_n(&img_->msg_done_seq, seq, __ATOMIC_RELEASE);
}

}  // namespace stepmod::ipc
