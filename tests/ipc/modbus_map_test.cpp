// The Modbus register map (docs/interface.md 6) on an image in ordinary memory: layout of the 16-
// and 32-bit modules, the header registers, every exception, and writes as one seqlock write that
// bumps the PLC heartbeat.
#include "ipc/modbus_map.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

namespace stepmod::ipc {
namespace {

struct Image {
  Image(std::uint32_t type, std::uint32_t word_bytes, std::uint32_t out, std::uint32_t in)
      : img(std::make_unique<stepmod_image_t>()) {
    std::memset(img.get(), 0, sizeof(stepmod_image_t));
    img->version = STEPMOD_LAYOUT_VERSION;
    img->module_type = type;
    img->word_bytes = word_bytes;
    img->output_words = out;
    img->input_words = in;
    std::memcpy(img->magic, STEPMOD_IMAGE_MAGIC, 8);
  }
  void set_inputs(const std::vector<std::int32_t>& w) {
    std::int32_t buf[16] = {};
    for (std::size_t i = 0; i < w.size(); ++i) buf[i] = w[i];
    stepmod_seq_write(&img->input_seq, &img->input_image, img->word_bytes, img->input_words, buf);
    ++img->scan_counter;  // as the daemon counts each publication
  }
  void set_outputs(const std::vector<std::int32_t>& w) {
    std::int32_t buf[16] = {};
    for (std::size_t i = 0; i < w.size(); ++i) buf[i] = w[i];
    stepmod_write_outputs(img.get(), buf);
  }
  std::int32_t out_word(unsigned i) const {
    return stepmod_word_load(&img->output_image, img->word_bytes, i);
  }
  std::unique_ptr<stepmod_image_t> img;
};

std::vector<std::uint8_t> read_pdu(std::uint8_t fc, std::uint16_t addr, std::uint16_t count) {
  return {fc, static_cast<std::uint8_t>(addr >> 8), static_cast<std::uint8_t>(addr),
          static_cast<std::uint8_t>(count >> 8), static_cast<std::uint8_t>(count)};
}
std::vector<std::uint8_t> write1_pdu(std::uint16_t addr, std::uint16_t v) {
  return {modbus_fc::kWriteSingle, static_cast<std::uint8_t>(addr >> 8),
          static_cast<std::uint8_t>(addr), static_cast<std::uint8_t>(v >> 8),
          static_cast<std::uint8_t>(v)};
}
std::vector<std::uint8_t> write_pdu(std::uint16_t addr, const std::vector<std::uint16_t>& v) {
  std::vector<std::uint8_t> p{
      modbus_fc::kWriteMultiple,           static_cast<std::uint8_t>(addr >> 8),
      static_cast<std::uint8_t>(addr),     static_cast<std::uint8_t>(v.size() >> 8),
      static_cast<std::uint8_t>(v.size()), static_cast<std::uint8_t>(2 * v.size())};
  for (std::uint16_t x : v) {
    p.push_back(static_cast<std::uint8_t>(x >> 8));
    p.push_back(static_cast<std::uint8_t>(x));
  }
  return p;
}
std::vector<std::uint16_t> values(const ModbusResult& r) {
  return {r.values.begin(), r.values.begin() + r.count};
}

TEST(ModbusMap, RegisterCountsFollowTheShape) {
  Image m3601(3601, 2, 8, 8);
  EXPECT_EQ(ModbusMap(*m3601.img, false).input_registers(), 8u);
  EXPECT_EQ(ModbusMap(*m3601.img, false).holding_registers(), 8u);
  Image m3202(3202, 4, 16, 16);
  EXPECT_EQ(ModbusMap(*m3202.img, false).input_registers(), 32u);
  EXPECT_EQ(ModbusMap(*m3202.img, false).holding_registers(), 32u);
}

TEST(ModbusMap, InputRegistersAreTheInputWords16Bit) {
  Image im(3601, 2, 8, 8);
  im.set_inputs({-1, 0x1234, 7, -32768, 32767, 0, 0, 9});
  ModbusMap map(*im.img, false);
  const auto r = map.handle(read_pdu(modbus_fc::kReadInput, 0, 8));
  ASSERT_EQ(r.exception, ModbusException::kNone);
  EXPECT_EQ(values(r), (std::vector<std::uint16_t>{0xFFFF, 0x1234, 7, 0x8000, 0x7FFF, 0, 0, 9}));
  const auto part = map.handle(read_pdu(modbus_fc::kReadInput, 3, 2));
  EXPECT_EQ(values(part), (std::vector<std::uint16_t>{0x8000, 0x7FFF}));
}

TEST(ModbusMap, ThirtyTwoBitWordsAreTwoRegistersHighHalfFirst) {
  Image im(3202, 4, 16, 16);
  im.set_inputs({0x12345678, -2});
  im.set_outputs({static_cast<std::int32_t>(0x89ABCDEFu)});
  ModbusMap map(*im.img, false);
  const auto in = map.handle(read_pdu(modbus_fc::kReadInput, 0, 4));
  EXPECT_EQ(values(in), (std::vector<std::uint16_t>{0x1234, 0x5678, 0xFFFF, 0xFFFE}));
  const auto odd = map.handle(read_pdu(modbus_fc::kReadInput, 1, 2));
  EXPECT_EQ(values(odd), (std::vector<std::uint16_t>{0x5678, 0xFFFF}));
  const auto out = map.handle(read_pdu(modbus_fc::kReadHolding, 0, 2));
  EXPECT_EQ(values(out), (std::vector<std::uint16_t>{0x89AB, 0xCDEF}));
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 31, 1)).exception, ModbusException::kNone);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 31, 2)).exception,
            ModbusException::kIllegalDataAddress);
}

TEST(ModbusMap, HeaderAndHealthRegistersFrom1000) {
  Image im(3601, 2, 8, 8);
  im.img->scan_counter = 0x0001'2345'6789ull;
  im.img->health_flags = 0x0001'0012u;
  im.img->late_faults = 0x0003'0004u;
  ModbusMap map(*im.img, false);
  const auto r = map.handle(read_pdu(modbus_fc::kReadInput, 1000, 16));
  ASSERT_EQ(r.exception, ModbusException::kNone);
  EXPECT_EQ(values(r), (std::vector<std::uint16_t>{3601, 2, 8, 8, 0x6789, 0x2345, 0x0012, 0x0001,
                                                   0x0004, 0x0003, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(values(map.handle(read_pdu(modbus_fc::kReadInput, 1006, 1))),
            (std::vector<std::uint16_t>{0x0012}));
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 1019, 1)).exception, ModbusException::kNone);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 1019, 2)).exception,
            ModbusException::kIllegalDataAddress);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 999, 2)).exception,
            ModbusException::kIllegalDataAddress);
  // The header is input registers only.
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadHolding, 1000, 1)).exception,
            ModbusException::kIllegalDataAddress);
}

// docs/interface.md 3.4 / 6: input registers 1016..1019 = the reason item codes of axis 1 and 2,
// high half first (docs/error-reasons.md).
TEST(ModbusMap, ReasonItemCodesIn1016To1019) {
  Image im(3602, 2, 16, 16);
  im.img->reasons[0].item = 20205u;  // 3602-CE-05
  im.img->reasons[1].item = 0x0001'0002u;
  ModbusMap map(*im.img, false);
  const auto r = map.handle(read_pdu(modbus_fc::kReadInput, 1016, 4));
  ASSERT_EQ(r.exception, ModbusException::kNone);
  EXPECT_EQ(values(r), (std::vector<std::uint16_t>{0, 20205, 0x0001, 0x0002}));
}

// A new image's zeros are not the module's state: until the daemon's first publication the
// input words answer "busy" (0x06), the header (scan counter 0) answers.
TEST(ModbusMap, InputWordsAreBusyUntilTheFirstPublication) {
  Image im(3601, 2, 8, 8);
  ModbusMap map(*im.img, false);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 0, 8)).exception,
            ModbusException::kServerDeviceBusy);
  const auto header = map.handle(read_pdu(modbus_fc::kReadInput, 1000, 6));
  ASSERT_EQ(header.exception, ModbusException::kNone);
  EXPECT_EQ(header.values[4], 0u);
  im.set_inputs({5});
  const auto r = map.handle(read_pdu(modbus_fc::kReadInput, 0, 1));
  ASSERT_EQ(r.exception, ModbusException::kNone);
  EXPECT_EQ(r.values[0], 5u);
}

TEST(ModbusMap, IllegalAddressesAndCounts) {
  Image im(3601, 2, 8, 8);
  ModbusMap map(*im.img, true);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 7, 2)).exception,
            ModbusException::kIllegalDataAddress);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 8, 1)).exception,
            ModbusException::kIllegalDataAddress);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadHolding, 0, 9)).exception,
            ModbusException::kIllegalDataAddress);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 65535, 1)).exception,
            ModbusException::kIllegalDataAddress);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 0, 0)).exception,
            ModbusException::kIllegalDataValue);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadHolding, 0, 126)).exception,
            ModbusException::kIllegalDataValue);
  EXPECT_EQ(map.handle(write1_pdu(8, 1)).exception, ModbusException::kIllegalDataAddress);
  EXPECT_EQ(map.handle(write_pdu(7, {1, 2})).exception, ModbusException::kIllegalDataAddress);
  // Nothing of a refused write reaches the image.
  EXPECT_EQ(im.out_word(7), 0);
  EXPECT_EQ(im.img->plc_heartbeat, 0u);
}

TEST(ModbusMap, MalformedRequestsAreIllegalDataValue) {
  Image im(3601, 2, 8, 8);
  ModbusMap map(*im.img, true);
  EXPECT_EQ(map.handle({}).exception, ModbusException::kIllegalDataValue);
  EXPECT_EQ(map.handle(std::vector<std::uint8_t>{0x04, 0, 0, 0}).exception,
            ModbusException::kIllegalDataValue);
  auto p = write_pdu(0, {1, 2});
  p[5] = 3;  // byte count does not match the quantity
  EXPECT_EQ(map.handle(p).exception, ModbusException::kIllegalDataValue);
  p = write_pdu(0, {1, 2});
  p.pop_back();  // truncated
  EXPECT_EQ(map.handle(p).exception, ModbusException::kIllegalDataValue);
  p = write_pdu(0, std::vector<std::uint16_t>(124, 0));  // over 123 registers
  p[5] = 0;                                              // (a byte count cannot say 248 anyway)
  EXPECT_EQ(map.handle(p).exception, ModbusException::kIllegalDataValue);
  EXPECT_EQ(im.img->plc_heartbeat, 0u);
}

TEST(ModbusMap, UnsupportedFunctionsAreIllegalFunction) {
  Image im(3601, 2, 8, 8);
  ModbusMap map(*im.img, true);
  for (std::uint8_t fc : {0x01, 0x02, 0x05, 0x0F, 0x16, 0x17, 0x2B, 0x7F}) {
    EXPECT_EQ(map.handle(read_pdu(fc, 0, 1)).exception, ModbusException::kIllegalFunction)
        << int(fc);
  }
}

TEST(ModbusMap, WritesRefusedUnlessConfigured) {
  Image im(3601, 2, 8, 8);
  ModbusMap map(*im.img, false);
  EXPECT_EQ(map.handle(write1_pdu(0, 0x8000)).exception, ModbusException::kIllegalFunction);
  EXPECT_EQ(map.handle(write_pdu(0, {1, 2, 3})).exception, ModbusException::kIllegalFunction);
  EXPECT_EQ(im.out_word(0), 0);
  EXPECT_EQ(im.img->output_seq, 0u);
  EXPECT_EQ(im.img->plc_heartbeat, 0u);
  // Reading the outputs is always allowed.
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadHolding, 0, 8)).exception, ModbusException::kNone);
}

TEST(ModbusMap, AcceptedWriteIsOneSeqlockWriteAndAHeartbeat) {
  Image im(3601, 2, 8, 8);
  im.set_outputs({11, 22, 33, 44, 55, 66, 77, 88});
  const std::uint32_t seq0 = im.img->output_seq;
  ModbusMap map(*im.img, true);
  const auto r = map.handle(write_pdu(2, {0xFFFF, 0x8000, 5}));
  ASSERT_EQ(r.exception, ModbusException::kNone);
  EXPECT_TRUE(r.wrote);
  EXPECT_EQ(r.address, 2);
  EXPECT_EQ(r.count, 3);
  EXPECT_EQ(im.img->output_seq, seq0 + 2);  // one write: odd, then even
  EXPECT_EQ(im.img->plc_heartbeat, 1u);
  const std::vector<std::int32_t> expect{11, 22, -1, -32768, 5, 66, 77, 88};
  for (unsigned i = 0; i < 8; ++i) EXPECT_EQ(im.out_word(i), expect[i]) << i;

  ASSERT_EQ(map.handle(write1_pdu(7, 0x1234)).exception, ModbusException::kNone);
  EXPECT_EQ(im.out_word(7), 0x1234);
  EXPECT_EQ(im.out_word(6), 77);
  EXPECT_EQ(im.img->output_seq, seq0 + 4);
  EXPECT_EQ(im.img->plc_heartbeat, 2u);
  // And reads back through function 3.
  EXPECT_EQ(values(map.handle(read_pdu(modbus_fc::kReadHolding, 6, 2))),
            (std::vector<std::uint16_t>{77, 0x1234}));
}

TEST(ModbusMap, HalfOfA32BitWordKeepsTheOtherHalf) {
  Image im(3202, 4, 16, 16);
  im.set_outputs({0x11112222, 0x33334444});
  ModbusMap map(*im.img, true);
  ASSERT_EQ(map.handle(write1_pdu(1, 0xBEEF)).exception, ModbusException::kNone);
  EXPECT_EQ(static_cast<std::uint32_t>(im.out_word(0)), 0x1111BEEFu);
  ASSERT_EQ(map.handle(write1_pdu(2, 0xDEAD)).exception, ModbusException::kNone);
  EXPECT_EQ(static_cast<std::uint32_t>(im.out_word(1)), 0xDEAD4444u);
  ASSERT_EQ(map.handle(write_pdu(30, {0x8000, 0x0001})).exception, ModbusException::kNone);
  EXPECT_EQ(static_cast<std::uint32_t>(im.out_word(15)), 0x80000001u);
  EXPECT_EQ(map.handle(write_pdu(31, {1, 2})).exception, ModbusException::kIllegalDataAddress);
}

TEST(ModbusMap, OutOfRangeWordValuesReachTheModuleUnchanged) {
  // The map never judges a value: the module rejects a bad word as the manual says.
  Image im(3601, 2, 8, 8);
  ModbusMap map(*im.img, true);
  ASSERT_EQ(map.handle(write1_pdu(6, 0xFFFF)).exception, ModbusException::kNone);
  EXPECT_EQ(im.out_word(6), -1);
}

TEST(ModbusMap, ReaderNeverReturnsATornInputImage) {
  // A writer left in the middle of a publication (odd sequence): the map answers "busy" after its
  // bounded retries instead of returning half-old, half-new words.
  Image im(3601, 2, 8, 8);
  im.img->input_seq = 1;
  ModbusMap map(*im.img, false);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 0, 1)).exception,
            ModbusException::kServerDeviceBusy);
  EXPECT_EQ(map.handle(read_pdu(modbus_fc::kReadInput, 1000, 1)).exception,
            ModbusException::kServerDeviceBusy);
}

}  // namespace
}  // namespace stepmod::ipc
