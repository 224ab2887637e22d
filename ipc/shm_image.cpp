#include "ipc/shm_image.hpp"

#include <unistd.h>

#include <cstdio>
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

bool ShmImage::read_outputs(ImageWords& out, std::uint32_t& seq) const noexcept {
  for (unsigned t = 0; t < kReadTries; ++t) {
    const std::uint32_t s0 = __atomic_load_n(&img_->output_seq, __ATOMIC_ACQUIRE);
    if ((s0 & 1u) != 0) continue;
    ImageWords tmp;
    for (unsigned i = 0; i < shape_.output_words; ++i) {
      tmp.w[i] = stepmod_word_load(&img_->output_image, shape_.word_bytes, i);
    }
    if (__atomic_load_n(&img_->output_seq, __ATOMIC_RELAXED) == s0) {
      out = tmp;
      seq = s0;
      return true;
    }
  }
  return false;
}

std::uint32_t ShmImage::output_seq() const noexcept {
  return __atomic_load_n(&img_->output_seq, __ATOMIC_ACQUIRE);
}

void ShmImage::publish_inputs(const ImageWords& in, const Health& health) noexcept {
  // Only the module writes the input image, so the lock is always free (stale_ns 0 never waits;
  // the pulse/control threads must not block on a foreign process).
  const std::uint32_t odd = stepmod_seq_write_begin(&img_->input_seq, 0);
  for (unsigned i = 0; i < shape_.input_words; ++i) {
    stepmod_word_store(&img_->input_image, shape_.word_bytes, i, in.w[i]);
  }
  __atomic_store_n(&img_->health_flags, health.flags, __ATOMIC_RELAXED);
  __atomic_store_n(&img_->late_faults, health.late_faults, __ATOMIC_RELAXED);
  __atomic_store_n(&img_->worst_late_us, health.worst_late_us, __ATOMIC_RELAXED);
  for (unsigned a = 0; a < reasons_.size(); ++a) {
    stepmod_reason_t& r = img_->reasons[a];
    if (__atomic_load_n(&r.seq, __ATOMIC_RELAXED) == reasons_[a].seq) continue;
    __atomic_store_n(&r.item, reasons_[a].item, __ATOMIC_RELAXED);
    for (unsigned i = 0; i < STEPMOD_REASON_TEXT; ++i) {
      __atomic_store_n(&r.text[i], reasons_[a].text[i], __ATOMIC_RELAXED);
    }
    __atomic_store_n(&r.seq, reasons_[a].seq, __ATOMIC_RELAXED);
  }
  for (unsigned a = 0; a < units_.size(); ++a) {
    stepmod_unit_state_t& u = img_->units[a];
    __atomic_store_n(&u.config_seq, units_[a].config_seq, __ATOMIC_RELAXED);
    __atomic_store_n(&u.inputs, units_[a].inputs, __ATOMIC_RELAXED);
    __atomic_store_n(&u.drive_enable, units_[a].drive_enable, __ATOMIC_RELAXED);
    for (unsigned i = 0; i < STEPMOD_UNIT_CONFIG_WORDS; ++i) {
      __atomic_store_n(&u.config_words[i], units_[a].config_words[i], __ATOMIC_RELAXED);
    }
  }
  health_ = health;
  stepmod_seq_write_end(&img_->input_seq, odd);
  __atomic_fetch_add(&img_->scan_counter, 1u, __ATOMIC_RELEASE);
}

std::string ShmImage::replaced_description() const {
  if (map_.replaced_pid() == 0) return {};
  std::string d = "a stale /dev/shm" + image_object(name_) + " of stepmodd pid " +
                  std::to_string(map_.replaced_pid()) + " (no longer running)";
  const auto& c = map_.replaced_content();
  if (c.size() >= sizeof(stepmod_image_t)) {
    stepmod_image_t old;
    std::memcpy(&old, c.data(), sizeof old);
    const bool odd = (old.output_seq & 1u) != 0;
    d += ": module " + std::to_string(old.module_type) + ", " + std::to_string(old.scan_counter) +
         " scans, PLC heartbeat " + std::to_string(old.plc_heartbeat) + ", output sequence " +
         std::to_string(old.output_seq) + (odd ? " (odd: a PLC was mid-write)" : "") +
         ", health flags 0x" +
         [&] {
           char b[16];
           std::snprintf(b, sizeof b, "%x", old.health_flags);
           return std::string(b);
         }() +
         " (" + health_flag_names(old.health_flags) + "), " + std::to_string(old.late_faults) +
         " late-edge faults";
  }
  return d;
}

std::uint64_t ShmImage::scan_counter() const noexcept {
  return __atomic_load_n(&img_->scan_counter, __ATOMIC_ACQUIRE);
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

namespace stepmod::ipc {

void ShmImage::set_reason(unsigned axis, const stepmod_reason_t& reason) noexcept {
  if (axis < reasons_.size()) reasons_[axis] = reason;
}

void ShmImage::set_unit_state(unsigned axis, const stepmod_unit_state_t& state) noexcept {
  if (axis < units_.size()) units_[axis] = state;
}

ShmImage::Lease ShmImage::lease() const noexcept {
  Lease l;
  l.holder = __atomic_load_n(&img_->lease_holder, __ATOMIC_ACQUIRE);
  l.seq = __atomic_load_n(&img_->lease_seq, __ATOMIC_ACQUIRE);
  l.expiry_ns =
      static_cast<std::int64_t>(__atomic_load_n(&img_->lease_expiry_ns, __ATOMIC_ACQUIRE));
  return l;
}

bool ShmImage::free_lease(std::uint32_t holder) noexcept {
  std::uint32_t expected = holder;
  return __atomic_compare_exchange_n(&img_->lease_holder, &expected, 0u, false, __ATOMIC_ACQ_REL,
                                     __ATOMIC_ACQUIRE);
}

}  // namespace stepmod::ipc
