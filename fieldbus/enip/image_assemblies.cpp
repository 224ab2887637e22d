#include "fieldbus/enip/image_assemblies.hpp"

#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

namespace {
// Attempts of one read before the last consistent words are kept: the module holds the input
// seqlock for a few stores once per scan.
constexpr unsigned kReadTries = 64;
}  // namespace

AssemblyLayout ImageAssemblies::layout() const noexcept {
  return assembly_layout(img_.word_bytes, img_.output_words, img_.input_words);
}

void ImageAssemblies::read(std::uint32_t instance, std::span<std::uint8_t> out) noexcept {
  const bool input = instance == kInputInstance;
  auto& words = input ? last_input_ : last_output_;
  const unsigned n = input ? img_.input_words : img_.output_words;
  const std::uint32_t* seq = input ? &img_.input_seq : &img_.output_seq;
  const stepmod_words_t* image = input ? &img_.input_image : &img_.output_image;
  std::array<std::int32_t, STEPMOD_MAX_WORDS> fresh{};
  if (stepmod_seq_read(seq, image, img_.word_bytes, n, fresh.data(), kReadTries) != 0) {
    words = fresh;
  }
  Writer w(out);
  for (unsigned i = 0; i < n; ++i) {
    if (img_.word_bytes == 2) {
      w.u16(static_cast<std::uint16_t>(words[i]));
    } else {
      w.u32(static_cast<std::uint32_t>(words[i]));
    }
  }
}

void ImageAssemblies::write_output(std::span<const std::uint8_t> bytes) noexcept {
  std::array<std::int32_t, STEPMOD_MAX_WORDS> words{};
  Reader r(bytes);
  for (unsigned i = 0; i < img_.output_words; ++i) {
    words[i] = img_.word_bytes == 2 ? static_cast<std::int16_t>(r.u16())
                                    : static_cast<std::int32_t>(r.u32());
  }
  if (!r.ok()) return;  // the router checked the size: never a partial write
  stepmod_seq_write(&img_.output_seq, &img_.output_image, img_.word_bytes, img_.output_words,
                    words.data());
  // The adapter that writes is the PLC: its writes are its heartbeat.
  beat();
}

void ImageAssemblies::beat() noexcept {
  __atomic_fetch_add(&img_.plc_heartbeat, 1u, __ATOMIC_RELEASE);
}

}  // namespace stepmod::enip
