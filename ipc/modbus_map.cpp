#include "ipc/modbus_map.hpp"

#include <sched.h>

#include "core/clock.hpp"

namespace stepmod::ipc {
namespace {

std::uint16_t be16(std::span<const std::uint8_t> p, std::size_t at) {
  return static_cast<std::uint16_t>((p[at] << 8) | p[at + 1]);
}

ModbusResult fail(ModbusResult r, ModbusException e) {
  r.exception = e;
  r.count = 0;
  return r;
}

// A consistent snapshot, or "busy" only for a writer stuck in the middle of a publication. The
// module holds the input seqlock for a few stores once per scan, but on a loaded machine its
// control thread can be preempted inside that window for milliseconds: under ThreadSanitizer
// 1,000 immediate retries all found the sequence odd and mbpoll got "busy" for a healthy daemon.
// So: a few immediate tries, then one every 100 us, and "busy" after 200 ms without a consistent
// read (well inside a Modbus master's usual 0.5 s or more response timeout). Only the Modbus
// thread waits here; the control thread never does (the server is not on its path).
constexpr unsigned kSpinTries = 64;
constexpr Nanos kRetryEvery = 100 * kNsPerUs;
constexpr Nanos kBusyAfter = 200 * kNsPerMs;

template <class Attempt>
bool until_consistent(Attempt attempt) noexcept {
  for (unsigned t = 0; t < kSpinTries; ++t) {
    if (attempt()) return true;
    if (t % 16 == 15) sched_yield();
  }
  const Nanos give_up = monotonic_now() + kBusyAfter;
  while (monotonic_now() < give_up) {
    sleep_until(monotonic_now() + kRetryEvery);
    if (attempt()) return true;
  }
  return false;
}

}  // namespace

ModbusMap::ModbusMap(stepmod_image_t& image, bool writes)
    : img_(image),
      writes_(writes),
      word_bytes_(image.word_bytes),
      output_words_(image.output_words),
      input_words_(image.input_words),
      input_regs_(image.input_words * image.word_bytes / 2),
      holding_regs_(image.output_words * image.word_bytes / 2) {}

std::uint16_t ModbusMap::reg_of(const std::int32_t* words, unsigned reg) const noexcept {
  if (word_bytes_ == 2) return static_cast<std::uint16_t>(words[reg]);
  // 3202: register 2k = bits 31..16 of word k, 2k+1 = bits 15..0 (docs/interface.md 6).
  const auto w = static_cast<std::uint32_t>(words[reg / 2]);
  return static_cast<std::uint16_t>(reg % 2 == 0 ? w >> 16 : w & 0xFFFFu);
}

ModbusResult ModbusMap::handle(std::span<const std::uint8_t> pdu) noexcept {
  ModbusResult r;
  if (pdu.empty()) return fail(r, ModbusException::kIllegalDataValue);
  r.function = pdu[0];
  switch (r.function) {
    case modbus_fc::kReadHolding:
    case modbus_fc::kReadInput: {
      if (pdu.size() != 5) return fail(r, ModbusException::kIllegalDataValue);
      r.address = be16(pdu, 1);
      r.count = be16(pdu, 3);
      if (r.count < 1 || r.count > kModbusMaxRead) {
        return fail(r, ModbusException::kIllegalDataValue);
      }
      return r.function == modbus_fc::kReadInput ? read_inputs(r) : read_holding(r);
    }
    case modbus_fc::kWriteSingle: {
      // Refused outright while another program owns the outputs ([modbus] writes = false).
      if (!writes_) return fail(r, ModbusException::kIllegalFunction);
      if (pdu.size() != 5) return fail(r, ModbusException::kIllegalDataValue);
      r.address = be16(pdu, 1);
      r.count = 1;
      r.values[0] = be16(pdu, 3);
      return write(r);
    }
    case modbus_fc::kWriteMultiple: {
      if (!writes_) return fail(r, ModbusException::kIllegalFunction);
      if (pdu.size() < 6) return fail(r, ModbusException::kIllegalDataValue);
      r.address = be16(pdu, 1);
      r.count = be16(pdu, 3);
      const unsigned bytes = pdu[5];
      if (r.count < 1 || r.count > kModbusMaxWrite || bytes != 2u * r.count ||
          pdu.size() != 6u + bytes) {
        return fail(r, ModbusException::kIllegalDataValue);
      }
      for (unsigned i = 0; i < r.count; ++i) r.values[i] = be16(pdu, 6 + 2 * i);
      return write(r);
    }
    default:
      return fail(r, ModbusException::kIllegalFunction);
  }
}

ModbusResult ModbusMap::read_inputs(ModbusResult r) const noexcept {
  const unsigned first = r.address;
  const unsigned end = first + r.count;
  const bool words = end <= input_regs_;
  const bool header = first >= kHeaderBase && end <= kHeaderBase + kHeaderRegisters;
  if (!words && !header) return fail(r, ModbusException::kIllegalDataAddress);
  // Before the daemon's first publication the words are the zeros of a new image, not the
  // module's state: a master that read them would take "Module OK = 0, position 0" as a fact.
  // It gets "busy" and retries; the header (scan counter 0) stays readable to say why.
  if (words && __atomic_load_n(&img_.scan_counter, __ATOMIC_ACQUIRE) == 0) {
    return fail(r, ModbusException::kServerDeviceBusy);
  }

  // One consistent publication: the input words and the health fields share the input seqlock.
  std::int32_t in[STEPMOD_MAX_WORDS] = {};
  std::uint32_t health = 0;
  std::uint32_t late = 0;
  std::array<std::uint32_t, 2> items{};
  const bool ok = until_consistent([&] {
    const std::uint32_t s0 = __atomic_load_n(&img_.input_seq, __ATOMIC_ACQUIRE);
    if (s0 & 1u) return false;
    for (unsigned i = 0; i < input_words_; ++i) {
      in[i] = stepmod_word_load(&img_.input_image, word_bytes_, i);
    }
    health = __atomic_load_n(&img_.health_flags, __ATOMIC_ACQUIRE);
    late = __atomic_load_n(&img_.late_faults, __ATOMIC_ACQUIRE);
    for (unsigned a = 0; a < items.size(); ++a) {
      items[a] = __atomic_load_n(&img_.reasons[a].item, __ATOMIC_ACQUIRE);
    }
    return __atomic_load_n(&img_.input_seq, __ATOMIC_RELAXED) == s0;
  });
  if (!ok) return fail(r, ModbusException::kServerDeviceBusy);

  if (words) {
    for (unsigned i = 0; i < r.count; ++i) r.values[i] = reg_of(in, first + i);
    return r;
  }
  const std::uint64_t scans = __atomic_load_n(&img_.scan_counter, __ATOMIC_ACQUIRE);
  std::array<std::uint16_t, kHeaderRegisters> h{};
  h[kHeaderModuleType] = static_cast<std::uint16_t>(img_.module_type);
  h[kHeaderWordBytes] = static_cast<std::uint16_t>(word_bytes_);
  h[kHeaderOutputWords] = static_cast<std::uint16_t>(output_words_);
  h[kHeaderInputWords] = static_cast<std::uint16_t>(input_words_);
  h[kHeaderScanLow] = static_cast<std::uint16_t>(scans & 0xFFFFu);
  h[kHeaderScanHigh] = static_cast<std::uint16_t>((scans >> 16) & 0xFFFFu);
  h[kHeaderHealthLow] = static_cast<std::uint16_t>(health & 0xFFFFu);
  h[kHeaderHealthHigh] = static_cast<std::uint16_t>(health >> 16);
  h[kHeaderLateLow] = static_cast<std::uint16_t>(late & 0xFFFFu);
  h[kHeaderLateHigh] = static_cast<std::uint16_t>(late >> 16);
  h[kHeaderReason1High] = static_cast<std::uint16_t>(items[0] >> 16);
  h[kHeaderReason1Low] = static_cast<std::uint16_t>(items[0] & 0xFFFFu);
  h[kHeaderReason2High] = static_cast<std::uint16_t>(items[1] >> 16);
  h[kHeaderReason2Low] = static_cast<std::uint16_t>(items[1] & 0xFFFFu);
  for (unsigned i = 0; i < r.count; ++i) r.values[i] = h[first - kHeaderBase + i];
  return r;
}

ModbusResult ModbusMap::read_holding(ModbusResult r) const noexcept {
  if (static_cast<unsigned>(r.address) + r.count > holding_regs_) {
    return fail(r, ModbusException::kIllegalDataAddress);
  }
  std::int32_t out[STEPMOD_MAX_WORDS] = {};
  const bool ok = until_consistent([&] {
    return stepmod_seq_read(&img_.output_seq, &img_.output_image, word_bytes_, output_words_, out,
                            1) != 0;
  });
  if (!ok) return fail(r, ModbusException::kServerDeviceBusy);
  for (unsigned i = 0; i < r.count; ++i) r.values[i] = reg_of(out, r.address + i);
  return r;
}

ModbusResult ModbusMap::write(ModbusResult r) noexcept {
  if (static_cast<unsigned>(r.address) + r.count > holding_regs_) {
    return fail(r, ModbusException::kIllegalDataAddress);
  }
  // One seqlock write of the whole output image (docs/interface.md 6): the registers not written
  // keep their values (a 3202 word written by halves keeps its other half), read while the lock is
  // held so that no other cooperating writer can slip in between. The values are not checked:
  // a word outside the manual's ranges reaches the module as the PLC's word would.
  const std::uint32_t odd = stepmod_seq_write_begin(&img_.output_seq, STEPMOD_SEQ_STALE_NS);
  std::int32_t out[STEPMOD_MAX_WORDS] = {};
  for (unsigned i = 0; i < output_words_; ++i) {
    out[i] = stepmod_word_load(&img_.output_image, word_bytes_, i);
  }
  for (unsigned i = 0; i < r.count; ++i) {
    const unsigned reg = r.address + i;
    const std::uint16_t v = r.values[i];
    if (word_bytes_ == 2) {
      out[reg] = static_cast<std::int16_t>(v);
    } else {
      auto w = static_cast<std::uint32_t>(out[reg / 2]);
      w = reg % 2 == 0 ? (w & 0x0000FFFFu) | (static_cast<std::uint32_t>(v) << 16)
                       : (w & 0xFFFF0000u) | v;
      out[reg / 2] = static_cast<std::int32_t>(w);
    }
  }
  for (unsigned i = 0; i < output_words_; ++i) {
    stepmod_word_store(&img_.output_image, word_bytes_, i, out[i]);
  }
  stepmod_seq_write_end(&img_.output_seq, odd);
  // The master that writes is the PLC: its writes are its heartbeat (docs/interface.md 3.2, 6).
  __atomic_fetch_add(&img_.plc_heartbeat, 1u, __ATOMIC_RELEASE);
  r.wrote = true;
  return r;
}

}  // namespace stepmod::ipc
