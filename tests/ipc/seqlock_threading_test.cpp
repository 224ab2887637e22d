// Seqlock under concurrency: a writer thread and reader threads on the same image; no snapshot
// may ever mix two writes (docs/interface.md 3.1). Labelled "threading" (runs under TSan too).
#include <unistd.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "ipc/shm_image.hpp"

namespace stepmod::ipc {
namespace {

std::string test_name(const char* tag) {
  return std::string("s-") + tag + "-" + std::to_string(::getpid());
}

// Every word of write k holds a value derived from k, so a torn snapshot is detectable: word i
// must equal f(k, i) for the same k in all words.
std::int32_t pattern(std::int32_t k, unsigned i, unsigned word_bytes) {
  const std::int32_t v = k * 17 + static_cast<std::int32_t>(i) * 3;
  return word_bytes == 2 ? static_cast<std::int16_t>(v & 0xFFFF) : v;
}

bool consistent(const ImageWords& w, unsigned n, unsigned word_bytes) {
  // Consecutive words of one write differ by 3 (modulo the word size), whatever k was.
  for (unsigned i = 1; i < n; ++i) {
    std::int32_t expect = w.w[0] + 3 * static_cast<std::int32_t>(i);
    if (word_bytes == 2) expect = static_cast<std::int16_t>(expect & 0xFFFF);
    if (w.w[i] != expect) return false;
  }
  return true;
}

void run_plc_to_module(const ModuleShape& shape, const char* tag) {
  const std::string n = test_name(tag);
  ShmImage img(n, shape);
  Client plc(n);
  ImageWords first;  // the image starts all-zero, which is not a pattern of the check
  for (unsigned i = 0; i < shape.output_words; ++i) first.w[i] = pattern(0, i, shape.word_bytes);
  plc.write_outputs(first);
  std::atomic<bool> stop{false};
  std::thread writer([&] {
    for (std::int32_t k = 1; !stop.load(std::memory_order_relaxed); ++k) {
      ImageWords w;
      for (unsigned i = 0; i < shape.output_words; ++i) w.w[i] = pattern(k, i, shape.word_bytes);
      plc.write_outputs(w);
    }
  });
  unsigned good = 0;
  unsigned torn = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
  while (std::chrono::steady_clock::now() < end) {
    ImageWords w;
    if (img.read_outputs(w)) {
      ++good;
      if (!consistent(w, shape.output_words, shape.word_bytes)) ++torn;
    }
  }
  stop = true;
  writer.join();
  EXPECT_EQ(torn, 0u) << "torn snapshots";
  EXPECT_GT(good, 100u);
}

TEST(Seqlock, NoTornOutputSnapshot16Bit) {
  run_plc_to_module({ModuleType::k3602, 2, 2, 16, 16}, "o16");
}

TEST(Seqlock, NoTornOutputSnapshot32Bit) {
  run_plc_to_module({ModuleType::k3202, 2, 4, 16, 16}, "o32");
}

TEST(Seqlock, NoTornInputSnapshotAndScanCounterMonotonic) {
  const ModuleShape shape{ModuleType::k3601, 1, 2, 8, 8};
  const std::string n = test_name("in");
  ShmImage img(n, shape);
  Client plc(n);
  ImageWords first;
  for (unsigned i = 0; i < shape.input_words; ++i) first.w[i] = pattern(0, i, 2);
  img.publish_inputs(first);
  std::atomic<bool> stop{false};
  std::thread module([&] {
    for (std::int32_t k = 1; !stop.load(std::memory_order_relaxed); ++k) {
      ImageWords w;
      for (unsigned i = 0; i < shape.input_words; ++i) w.w[i] = pattern(k, i, 2);
      img.publish_inputs(w);
    }
  });
  std::uint64_t last = 0;
  unsigned good = 0;
  unsigned torn = 0;
  bool backwards = false;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(300);
  while (std::chrono::steady_clock::now() < end) {
    ImageWords w;
    if (plc.read_inputs(w)) {
      ++good;
      if (!consistent(w, shape.input_words, 2)) ++torn;
    }
    const std::uint64_t s = plc.scan_counter();
    backwards = backwards || s < last;
    last = s;
  }
  stop = true;
  module.join();
  EXPECT_EQ(torn, 0u) << "torn snapshots";
  EXPECT_FALSE(backwards) << "scan counter went backwards";
  EXPECT_GT(good, 100u);
}

TEST(Seqlock, TwoCooperatingWritersNeverInterleave) {
  // A PLC program and stepmodctl both writing: each update_outputs() is one whole write.
  const ModuleShape shape{ModuleType::k3601, 1, 2, 8, 8};
  const std::string n = test_name("two");
  ShmImage img(n, shape);
  Client a(n);
  Client b(n);
  a.update_outputs([](ImageWords& w) {
    for (unsigned i = 0; i < 8; ++i) w.w[i] = pattern(0, i, 2);
  });
  std::atomic<bool> stop{false};
  auto writer = [&](Client& c, std::int32_t base) {
    for (std::int32_t k = 0; !stop.load(std::memory_order_relaxed); ++k) {
      c.update_outputs([&](ImageWords& w) {
        for (unsigned i = 0; i < 8; ++i) w.w[i] = pattern(base + (k % 1000), i, 2);
      });
    }
  };
  std::thread ta(writer, std::ref(a), 0);
  std::thread tb(writer, std::ref(b), 5000);
  unsigned torn = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(200);
  while (std::chrono::steady_clock::now() < end) {
    ImageWords w;
    if (img.read_outputs(w) && !consistent(w, 8, 2)) ++torn;
  }
  stop = true;
  ta.join();
  tb.join();
  EXPECT_EQ(torn, 0u);
}

TEST(Message, BlendMessageRoundTrip3202) {
  const std::string n = test_name("msg");
  ShmImage img(n, {ModuleType::k3202, 2, 4, 16, 16});
  Client plc(n);
  std::atomic<bool> stop{false};
  std::thread module([&] {
    while (!stop.load()) {
      if (auto m = img.pending_message()) {
        img.finish_message(m->seq, m->data[0] == 1 && m->data[51] == 77 ? 0 : -1);
      }
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
  });
  std::int32_t data[52] = {};
  data[0] = 1;
  data[51] = 77;
  EXPECT_EQ(plc.send_message(data, std::chrono::seconds(2)), 0);
  data[0] = 3;
  EXPECT_EQ(plc.send_message(data, std::chrono::seconds(2)), -1);
  stop = true;
  module.join();
  EXPECT_FALSE(img.pending_message().has_value());
}

}  // namespace
}  // namespace stepmod::ipc
