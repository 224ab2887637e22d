// The rules that end a Modbus/TCP connection (ipc/modbus_connection.hpp), on plain values: its
// time-outs, and which connection gives up its place for a new one when max_clients are in.
#include "ipc/modbus_connection.hpp"

#include <gtest/gtest.h>

#include <list>
#include <string>

namespace stepmod::ipc {
namespace {

constexpr Nanos kMs = kNsPerMs;
constexpr Nanos kIdle = 5000 * kMs;
constexpr Nanos kT0 = 1'000'000 * kMs;  // any moment well after the clock's start

ModbusConnection conn(const std::string& peer, Nanos last_heard, bool served) {
  ModbusConnection c;
  c.peer = peer;
  c.last_heard = last_heard;
  c.served = served;
  return c;
}

TEST(ModbusConnectionTimeout, IdleFromTheLastByte) {
  const ModbusConnection c = conn("a", kT0, true);
  const ModbusTimeout t = next_timeout(c, kIdle);
  EXPECT_EQ(t.at, kT0 + kIdle);
  EXPECT_TRUE(t.idle);
}

TEST(ModbusConnectionTimeout, AnIncompleteFrameComesFirst) {
  ModbusConnection c = conn("a", kT0, true);
  c.frame_start = kT0;
  const ModbusTimeout t = next_timeout(c, kIdle);
  EXPECT_EQ(t.at, kT0 + kModbusFrameTimeout);
  EXPECT_FALSE(t.idle);
  // An idle time-out shorter than a frame's: the idle one.
  EXPECT_EQ(next_timeout(c, 200 * kMs).at, kT0 + 200 * kMs);
}

TEST(ModbusConnectionTimeout, ClosingAfterAMalformedFrameHasItsOwn) {
  ModbusConnection c = conn("a", kT0, true);
  c.closing_since = kT0 + 10 * kMs;
  const ModbusTimeout t = next_timeout(c, kIdle);
  EXPECT_EQ(t.at, kT0 + 10 * kMs + kModbusCloseTimeout);
  EXPECT_FALSE(t.idle);
}

// The case of the report: a PLC polls every 100 ms; an idle socket connected just now, after its
// last poll. Oldest-heard alone would close the PLC.
TEST(ModbusEviction, ASocketThatAskedNothingGoesBeforeAPollingPlc) {
  std::list<ModbusConnection> cs;
  cs.push_back(conn("plc", kT0, true));
  cs.push_back(conn("idle", kT0 + 90 * kMs, false));
  EXPECT_EQ(eviction_choice(cs)->peer, "idle");
}

TEST(ModbusEviction, AmongTheSameKindTheOneHeardFromLongestAgo) {
  std::list<ModbusConnection> cs;
  cs.push_back(conn("idle2", kT0 + 20 * kMs, false));
  cs.push_back(conn("idle1", kT0 + 10 * kMs, false));
  cs.push_back(conn("idle3", kT0 + 30 * kMs, false));
  EXPECT_EQ(eviction_choice(cs)->peer, "idle1");
  std::list<ModbusConnection> served;
  served.push_back(conn("fast", kT0 + 95 * kMs, true));
  served.push_back(conn("quiet", kT0 + 5 * kMs, true));
  EXPECT_EQ(eviction_choice(served)->peer, "quiet");
}

TEST(ModbusEviction, AConnectionClosingAfterAMalformedFrameGoesFirst) {
  std::list<ModbusConnection> cs;
  cs.push_back(conn("idle", kT0, false));
  cs.push_back(conn("bad", kT0 + 50 * kMs, true));
  cs.back().closing_since = kT0 + 50 * kMs;
  EXPECT_EQ(eviction_choice(cs)->peer, "bad");
}

}  // namespace
}  // namespace stepmod::ipc
