// The io_uring reader of v1 line events, fed through pipes with the kernel's record layout (the
// build machines have no GPIO chip; the gpio-sim tests cover the real fds).
#include "gpio/line_event_reader.hpp"

#include <gtest/gtest.h>
#include <linux/gpio.h>
#include <unistd.h>

#include <vector>

namespace stepmod::gpio {
namespace {

struct Pipe {
  int r = -1, w = -1;
  Pipe() {
    int fds[2];
    EXPECT_EQ(::pipe(fds), 0);
    r = fds[0];
    w = fds[1];
  }
  ~Pipe() {
    if (r >= 0) ::close(r);
    if (w >= 0) ::close(w);
  }
  // One write() of whole records, as the kernel hands them out.
  void send(const std::vector<gpioevent_data>& evs) const {
    const auto bytes = static_cast<ssize_t>(evs.size() * sizeof(gpioevent_data));
    ASSERT_EQ(::write(w, evs.data(), static_cast<std::size_t>(bytes)), bytes);
  }
};

gpioevent_data rec(std::uint64_t t, bool rising) {
  gpioevent_data e{};
  e.timestamp = t;
  e.id = rising ? GPIOEVENT_EVENT_RISING_EDGE : GPIOEVENT_EVENT_FALLING_EDGE;
  return e;
}

std::vector<InputEvent> collect(LineEventReader& r, std::size_t want, std::size_t chunk) {
  std::vector<InputEvent> got;
  std::vector<InputEvent> buf(chunk);
  const Nanos deadline = monotonic_now() + kNsPerSec;
  while (got.size() < want && monotonic_now() < deadline) {
    const std::size_t n = r.wait(buf, deadline);
    got.insert(got.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(n));
  }
  return got;
}

TEST(GpioLineEventReader, ConvertsRecordsToInputEventsWithTheirTimestamps) {
  Pipe p;
  LineEventReader r({{p.r, 1, InputLine::kHome, "home"}});
  p.send({rec(123, true), rec(456, false)});
  const auto got = collect(r, 2, 8);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].t, 123);
  EXPECT_EQ(got[0].axis, 1);
  EXPECT_EQ(got[0].line, InputLine::kHome);
  EXPECT_TRUE(got[0].level);
  EXPECT_EQ(got[1].t, 456);
  EXPECT_FALSE(got[1].level);
}

TEST(GpioLineEventReader, TimesOutAtTheDeadline) {
  Pipe p;
  LineEventReader r({{p.r, 0, InputLine::kCapture, "capture"}});
  InputEvent ev[4];
  const Nanos t0 = monotonic_now();
  EXPECT_EQ(r.wait(ev, t0 + 3 * kNsPerMs), 0u);
  const Nanos dt = monotonic_now() - t0;
  EXPECT_GE(dt, 3 * kNsPerMs);
  EXPECT_LT(dt, 500 * kNsPerMs);
}

TEST(GpioLineEventReader, ManyEventsInSmallChunksKeepTheirOrder) {
  Pipe p;
  LineEventReader r({{p.r, 0, InputLine::kEncA, "enc_a"}});
  std::vector<gpioevent_data> recs;
  for (int i = 0; i < 100; ++i) recs.push_back(rec(1000 + i, i % 2 == 0));
  p.send(recs);  // more than several read batches
  const auto got = collect(r, 100, 3);
  ASSERT_EQ(got.size(), 100u);
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(got[i].t, 1000 + i);
    EXPECT_EQ(got[i].level, i % 2 == 0);
  }
}

TEST(GpioLineEventReader, SeveralSourcesMapToTheirLines) {
  Pipe a, b;
  LineEventReader r({{a.r, 0, InputLine::kCwLimit, "cw"}, {b.r, 1, InputLine::kCcwLimit, "ccw"}});
  b.send({rec(20, true)});
  a.send({rec(10, true)});
  auto got = collect(r, 2, 8);
  ASSERT_EQ(got.size(), 2u);
  for (const auto& e : got) {
    if (e.t == 10) {
      EXPECT_EQ(e.axis, 0);
      EXPECT_EQ(e.line, InputLine::kCwLimit);
    } else {
      EXPECT_EQ(e.t, 20);
      EXPECT_EQ(e.axis, 1);
      EXPECT_EQ(e.line, InputLine::kCcwLimit);
    }
  }
  // Both reads are back in flight.
  a.send({rec(30, false)});
  b.send({rec(40, false)});
  got = collect(r, 2, 8);
  EXPECT_EQ(got.size(), 2u);
}

TEST(GpioLineEventReader, ReadErrorNamesTheSource) {
  Pipe p;
  // The write end cannot be read: the read fails with EBADF.
  LineEventReader r({{p.w, 0, InputLine::kEStop, "GPIO chip 'x', line 7 (axis1.estop)"}});
  InputEvent ev[4];
  try {
    r.wait(ev, monotonic_now() + kNsPerSec);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("line 7 (axis1.estop)"), std::string::npos) << e.what();
  }
}

TEST(GpioLineEventReader, EndOfFileStopsThatSourceWithoutSpinning) {
  Pipe p, q;
  LineEventReader r({{p.r, 0, InputLine::kHome, "home"}, {q.r, 0, InputLine::kEStop, "estop"}});
  ::close(p.w);
  p.w = -1;
  InputEvent ev[4];
  EXPECT_EQ(r.wait(ev, monotonic_now() + 5 * kNsPerMs), 0u);
  q.send({rec(5, true)});
  const auto got = collect(r, 1, 4);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].line, InputLine::kEStop);
}

TEST(GpioLineEventReader, V1RepeatedDirectionCountsALostEdge) {
  Pipe p;
  LineEventReader r({{p.r, 0, InputLine::kHome, "home"}});
  p.send({rec(1, true), rec(2, true), rec(3, false)});
  const auto got = collect(r, 3, 8);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(r.lost(), 1u);
}

TEST(GpioLineEventReader, V2RecordsWithASequenceGapCountTheLostEdges) {
  Pipe p;
  LineEventReader r({{p.r, 0, InputLine::kCapture, "capture"}}, EdgeRecordFormat::kV2);
  std::vector<gpio_v2_line_event> recs(3);
  const std::uint32_t seq[] = {1, 2, 6};
  for (int i = 0; i < 3; ++i) {
    recs[i].timestamp_ns = 100u + static_cast<unsigned>(i);
    recs[i].id = i % 2 == 0 ? GPIO_V2_LINE_EVENT_RISING_EDGE : GPIO_V2_LINE_EVENT_FALLING_EDGE;
    recs[i].line_seqno = seq[i];
    recs[i].seqno = seq[i];
  }
  const auto bytes = static_cast<ssize_t>(recs.size() * sizeof(gpio_v2_line_event));
  ASSERT_EQ(::write(p.w, recs.data(), static_cast<std::size_t>(bytes)), bytes);
  const auto got = collect(r, 3, 8);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[2].t, 102);
  EXPECT_TRUE(got[2].level);
  EXPECT_EQ(r.lost(), 3u);
}

}  // namespace
}  // namespace stepmod::gpio
