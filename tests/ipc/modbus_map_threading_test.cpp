// The Modbus map's reads against a writer that really runs beside them (a thread; TSan covers it).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <memory>
#include <thread>

#include "ipc/modbus_map.hpp"

namespace stepmod::ipc {
namespace {

// A module's control thread preempted inside its input publication: the sequence stays odd for
// 20 ms, then the new words and the even sequence land. A healthy daemon on a loaded machine does
// this now and then (ThreadSanitizer showed it); the read waits for the publication instead of
// answering "busy", and returns the new words, never a mix.
TEST(ModbusMapThreading, AWriterPreemptedMidPublicationIsWaitedForNotAnsweredBusy) {
  auto img = std::make_unique<stepmod_image_t>();
  std::memset(img.get(), 0, sizeof(stepmod_image_t));
  img->version = STEPMOD_LAYOUT_VERSION;
  img->module_type = 3601;
  img->word_bytes = 2;
  img->output_words = 10;
  img->input_words = 10;
  std::memcpy(img->magic, STEPMOD_IMAGE_MAGIC, 8);
  img->scan_counter = 1;  // a running daemon's image: published before
  stepmod_word_store(&img->input_image, 2, 0, 111);
  stepmod_word_store(&img->input_image, 2, 1, 222);
  const std::uint32_t odd = stepmod_seq_write_begin(&img->input_seq, STEPMOD_SEQ_STALE_NS);
  stepmod_word_store(&img->input_image, 2, 0, 1234);  // half of the publication written ...

  std::thread writer([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // ... then preempted
    stepmod_word_store(&img->input_image, 2, 1, 5678);
    stepmod_seq_write_end(&img->input_seq, odd);
  });
  ModbusMap map(*img, false);
  const std::uint8_t read_two[] = {modbus_fc::kReadInput, 0, 0, 0, 2};  // input registers 0, 1
  const ModbusResult r = map.handle(read_two);
  writer.join();

  EXPECT_EQ(r.exception, ModbusException::kNone);
  ASSERT_EQ(r.count, 2u);
  EXPECT_EQ(r.values[0], 1234);
  EXPECT_EQ(r.values[1], 5678);
}

}  // namespace
}  // namespace stepmod::ipc
