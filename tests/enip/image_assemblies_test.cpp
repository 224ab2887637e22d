// The assembly data over a real image: words little-endian as CIP carries them, a write is one
// seqlock write and a heartbeat.
#include "fieldbus/enip/image_assemblies.hpp"

#include <gtest/gtest.h>

#include <array>
#include <memory>

#include "tests/enip/enip_bytes.hpp"

namespace stepmod::enip {
namespace {

using test::hex;

std::unique_ptr<stepmod_image_t> image_of(std::uint32_t word_bytes, std::uint32_t words) {
  auto img = std::make_unique<stepmod_image_t>();
  *img = stepmod_image_t{};
  img->word_bytes = word_bytes;
  img->output_words = words;
  img->input_words = words;
  return img;
}

TEST(EnipImageAssemblies, A3601sWordsAreInts) {
  auto img = image_of(2, 8);
  ImageAssemblies a(*img);
  EXPECT_EQ(a.layout().input_bytes, 16);
  const std::int32_t in[16] = {1, -2, 3, 4, 5, 6, 7, 0x7FFF};
  stepmod_seq_write(&img->input_seq, &img->input_image, 2, 8, in);
  std::array<std::uint8_t, 16> out{};
  a.read(kInputInstance, out);
  EXPECT_EQ(std::vector<std::uint8_t>(out.begin(), out.end()),
            hex("0100 feff 0300 0400 0500 0600 0700 ff7f"));
}

TEST(EnipImageAssemblies, AWriteIsOneSeqlockWriteAndAHeartbeat) {
  auto img = image_of(4, 16);
  ImageAssemblies a(*img);
  std::vector<std::uint8_t> bytes(64, 0);
  bytes[0] = 0x10;  // word 0 = 10000 (0x2710)
  bytes[1] = 0x27;
  bytes[60] = 0xFF;  // word 15 = -1
  bytes[61] = 0xFF;
  bytes[62] = 0xFF;
  bytes[63] = 0xFF;
  a.write_output(bytes);
  EXPECT_EQ(img->output_seq, 2u);
  EXPECT_EQ(img->plc_heartbeat, 1u);
  EXPECT_EQ(img->output_image.w32[0], 10000);
  EXPECT_EQ(img->output_image.w32[15], -1);
  std::array<std::uint8_t, 64> back{};
  a.read(kOutputInstance, back);
  EXPECT_EQ(std::vector<std::uint8_t>(back.begin(), back.end()), bytes);
  a.write_output(std::span(bytes).first(63));  // short: nothing is written
  EXPECT_EQ(img->output_seq, 2u);
  EXPECT_EQ(img->plc_heartbeat, 1u);
}

// A Run packet repeating the last CIP count: the PLC's heartbeat, the words untouched.
TEST(EnipImageAssemblies, ABeatIsAHeartbeatWithoutAWrite) {
  auto img = image_of(2, 8);
  ImageAssemblies a(*img);
  a.beat();
  a.beat();
  EXPECT_EQ(img->plc_heartbeat, 2u);
  EXPECT_EQ(img->output_seq, 0u);
}

TEST(EnipImageAssemblies, AReadDuringAWriteKeepsTheLastConsistentWords) {
  auto img = image_of(2, 8);
  ImageAssemblies a(*img);
  const std::int32_t in[16] = {42};
  stepmod_seq_write(&img->input_seq, &img->input_image, 2, 8, in);
  std::array<std::uint8_t, 16> out{};
  a.read(kInputInstance, out);
  img->input_seq = 3;  // a writer in the middle of its write
  img->input_image.w16[0] = 99;
  a.read(kInputInstance, out);
  EXPECT_EQ(out[0], 42);
}

}  // namespace
}  // namespace stepmod::enip
