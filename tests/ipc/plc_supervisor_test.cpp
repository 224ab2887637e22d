// The PLC supervisor (issue 12 item 2), scan by scan: heartbeat stale, sequence stuck odd and
// seqlock bypass are flagged while they last, a lost PLC trips once and freezes the words the
// module sees until it is back.
#include "ipc/plc_supervisor.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace stepmod::ipc {
namespace {

constexpr Nanos kScan = kNsPerMs;

class Supervisor : public ::testing::Test {
 protected:
  explicit Supervisor(Nanos timeout = 50 * kNsPerMs) : sup_(timeout) {}
  // One scan `kScan` after the last, with a consistent snapshot of `words_` under `seq_`.
  const ImageWords& scan() {
    now_ += kScan;
    PlcSupervisor::Sample s;
    s.now = now_;
    s.heartbeat = heartbeat_;
    s.seq = seq_;
    s.snapshot_ok = (seq_ & 1u) == 0;
    s.snapshot_seq = seq_;
    s.words = words_;
    s.lease_until = lease_until_;
    return sup_.scan(s);
  }
  void scans(int n) {
    for (int i = 0; i < n; ++i) scan();
  }
  // A PLC write through the seqlock (sequence +2) and a heartbeat.
  void plc_write(int word, std::int32_t v) {
    words_.w[word] = v;
    seq_ += 2;
  }

  PlcSupervisor sup_;
  Nanos now_ = kNsPerSec;
  std::uint64_t heartbeat_ = 1;
  std::uint32_t seq_ = 10;
  ImageWords words_{};
  Nanos lease_until_ = 0;  // a commissioning lease's expiry (0: none)
};

TEST_F(Supervisor, LiveWordsPassWhileTheHeartbeatMoves) {
  for (int i = 0; i < 200; ++i) {
    ++heartbeat_;
    plc_write(0, i);
    EXPECT_EQ(scan().w[0], i);
    EXPECT_EQ(sup_.flags(), 0u);
    EXPECT_FALSE(sup_.tripped());
  }
}

TEST_F(Supervisor, StaleHeartbeatTripsOnceFreezesTheWordsAndRecovers) {
  plc_write(0, 0x0004);  // e.g. a relative move bit, set before the loss
  scans(10);
  ++heartbeat_;
  scans(50);  // the change seen, then 49 ms without one
  EXPECT_EQ(sup_.flags(), 0u);
  scan();  // 50 ms without a heartbeat change
  EXPECT_TRUE(sup_.tripped());
  EXPECT_TRUE(sup_.plc_lost());
  EXPECT_EQ(sup_.flags(), STEPMOD_HEALTH_PLC_STALE);
  EXPECT_EQ(sup_.started(), STEPMOD_HEALTH_PLC_STALE);
  // While stale, a new command written by someone is not what the module sees.
  plc_write(0, 0x0008);
  plc_write(2, 5000);
  for (int i = 0; i < 100; ++i) {
    const ImageWords& w = scan();
    EXPECT_EQ(w.w[0], 0x0004);
    EXPECT_EQ(w.w[2], 0);
    EXPECT_FALSE(sup_.tripped());  // once per loss
    EXPECT_EQ(sup_.flags(), STEPMOD_HEALTH_PLC_STALE);
  }
  // The heartbeat moves: the live words again, the condition ends.
  ++heartbeat_;
  const ImageWords& w = scan();
  EXPECT_EQ(w.w[0], 0x0008);
  EXPECT_EQ(w.w[2], 5000);
  EXPECT_EQ(sup_.flags(), 0u);
  EXPECT_EQ(sup_.ended(), STEPMOD_HEALTH_PLC_STALE);
  EXPECT_FALSE(sup_.plc_lost());
  // And it trips again at the next loss.
  scans(49);
  EXPECT_FALSE(sup_.tripped());
  EXPECT_FALSE(sup_.tripped());
  scan();
  EXPECT_TRUE(sup_.tripped());
}

TEST_F(Supervisor, HeartbeatWatchOffNeverTrips) {
  PlcSupervisor off(0);
  PlcSupervisor::Sample s;
  for (int i = 0; i < 10'000; ++i) {
    s.now = i * kScan;
    s.snapshot_ok = true;
    off.scan(s);
    ASSERT_EQ(off.flags(), 0u);
  }
}

// Issue 34: a fieldbus PLC out of Run (the EtherNet/IP owner Idle, timed out or closed) is a
// stale heartbeat at once, with the heartbeat watch off (plc_timeout_ms = 0) and a heartbeat
// that keeps moving; the words freeze until the PLC is back in Run.
TEST(SupervisorFieldbus, APlcOutOfRunIsAStaleHeartbeatWhateverTheTimeout) {
  PlcSupervisor off(0);
  PlcSupervisor::Sample s;
  s.snapshot_ok = true;
  s.words.w[0] = 7;
  for (int i = 0; i < 10; ++i) {
    s.now = i * kScan;
    ++s.heartbeat;
    off.scan(s);
    ASSERT_EQ(off.flags(), 0u);
  }
  s.plc_not_in_run = true;
  s.now += kScan;
  ++s.heartbeat;
  s.words.w[0] = 8;  // written (through the seqlock) after the PLC left Run: not acted on
  s.snapshot_seq = s.seq = 2;
  EXPECT_EQ(off.scan(s).w[0], 7);
  EXPECT_TRUE(off.tripped());
  EXPECT_TRUE(off.plc_lost());
  EXPECT_EQ(off.flags(), STEPMOD_HEALTH_PLC_STALE);
  EXPECT_TRUE(off.not_in_run());  // the log says why
  s.now += kScan;
  off.scan(s);
  EXPECT_FALSE(off.tripped());  // once per loss
  EXPECT_TRUE(off.plc_lost());
  s.plc_not_in_run = false;  // the next Run packet
  s.now += kScan;
  EXPECT_EQ(off.scan(s).w[0], 8);
  EXPECT_FALSE(off.plc_lost());
  EXPECT_EQ(off.flags(), 0u);
}

// Issue 29: a lease stands in for the heartbeat only while its expiry is one a live holder writes
// (now .. now + 500 ms). Before, any held lease reset the heartbeat timer at every scan: garbage
// lease words switched the PLC watchdog off.
TEST_F(Supervisor, ALeaseHoldsOffTheTimeoutOnlyWithinItsOwnExpiry) {
  // A live holder's lease, renewed (400 ms ahead at every scan): no timeout for 1 s.
  for (int i = 0; i < 1000; ++i) {
    lease_until_ = now_ + kScan + 400 * kNsPerMs;
    scan();
    ASSERT_EQ(sup_.flags(), 0u) << i;
  }
  // No more renewals: the lease stands until its expiry, then the 50 ms timeout runs.
  scans(400);
  EXPECT_EQ(sup_.flags(), 0u);
  scans(50);
  EXPECT_TRUE(sup_.flags() & STEPMOD_HEALTH_PLC_STALE);
  EXPECT_TRUE(sup_.tripped() || sup_.plc_lost());
}

TEST(SupervisorLease, AnExpiryNoLiveHolderWritesDoesNotHoldOffTheTimeout) {
  const struct {
    const char* what;
    Nanos (*until)(Nanos now);
  } cases[] = {
      {"2^63-1", [](Nanos) { return Nanos{INT64_MAX}; }},
      {"2^64-1 (read as -1)", [](Nanos) { return Nanos{-1}; }},
      {"10 s ahead", [](Nanos now) { return now + 10 * kNsPerSec; }},
      {"501 ms ahead", [](Nanos now) { return now + 501 * kNsPerMs; }},
      {"passed", [](Nanos now) { return now - kNsPerMs; }},
  };
  for (const auto& c : cases) {
    PlcSupervisor sup(50 * kNsPerMs);
    PlcSupervisor::Sample s;
    s.heartbeat = 7;
    bool stale = false;
    for (int i = 1; i <= 60 && !stale; ++i) {
      s.now = kNsPerSec + i * kScan;
      s.lease_until = c.until(s.now);
      sup.scan(s);
      stale = (sup.flags() & STEPMOD_HEALTH_PLC_STALE) != 0;
    }
    EXPECT_TRUE(stale) << c.what;
  }
}

TEST_F(Supervisor, SequenceStuckOddIsALostPlc) {
  plc_write(0, 0x0080);  // a held manual move
  scans(5);
  ++seq_;                            // the PLC begins a write ... and dies
  words_.w[0] = 0x0010;              // half written: Immediate Stop, never published
  for (int i = 0; i < 50; ++i) {     // odd seen, then 49 ms more
    ++heartbeat_;                    // even with the heartbeat alive (another task of the PLC)
    EXPECT_EQ(scan().w[0], 0x0080);  // the last good snapshot
    EXPECT_EQ(sup_.flags(), 0u);
  }
  ++heartbeat_;
  scan();
  EXPECT_TRUE(sup_.tripped());
  EXPECT_EQ(sup_.flags(), STEPMOD_HEALTH_SEQ_STUCK);
  EXPECT_EQ(sup_.stuck_seq(), seq_);
  ++seq_;  // the write completes (or a new PLC writes)
  ++heartbeat_;
  EXPECT_EQ(scan().w[0], 0x0010);
  EXPECT_EQ(sup_.ended(), STEPMOD_HEALTH_SEQ_STUCK);
  EXPECT_FALSE(sup_.plc_lost());
}

TEST_F(Supervisor, OddSequenceThatKeepsChangingIsABusyWriterNotADeadOne) {
  for (int i = 0; i < 500; ++i) {
    ++heartbeat_;
    seq_ = (i % 2 == 0) ? seq_ + 2 : seq_;  // a new odd value every other scan
    seq_ |= 1u;
    scan();
    EXPECT_EQ(sup_.flags() & STEPMOD_HEALTH_SEQ_STUCK, 0u);
  }
}

TEST(SupervisorDefaults, StuckOddTimeoutIs100msWithoutTheHeartbeat) {
  PlcSupervisor sup(0);
  EXPECT_EQ(sup.odd_timeout(), 100 * kNsPerMs);
  PlcSupervisor::Sample s;
  s.seq = 7;
  s.now = 1'000 * kNsPerMs;
  sup.scan(s);
  s.now += 99 * kNsPerMs;
  sup.scan(s);
  EXPECT_EQ(sup.flags(), 0u);
  s.now += kNsPerMs;
  sup.scan(s);
  EXPECT_EQ(sup.flags(), STEPMOD_HEALTH_SEQ_STUCK);
  EXPECT_TRUE(sup.tripped());
}

TEST_F(Supervisor, WordsChangedUnderAnUnchangedSequenceAreABypass) {
  plc_write(2, 0);
  scans(3);
  for (int i = 0; i < 20; ++i) ++heartbeat_, scan();
  words_.w[3] = 2444;  // written directly, sequence untouched
  ++heartbeat_;
  EXPECT_EQ(scan().w[3], 2444);  // passed on (logged and flagged, not refused)
  EXPECT_EQ(sup_.started(), STEPMOD_HEALTH_SEQ_BYPASS);
  EXPECT_EQ(sup_.bypass_changes(), 1u);
  EXPECT_FALSE(sup_.plc_lost());
  // Set while bypassing writes keep coming, cleared a second after the last one.
  for (int i = 0; i < 999; ++i) {
    ++heartbeat_;
    scan();
    ASSERT_EQ(sup_.flags(), STEPMOD_HEALTH_SEQ_BYPASS) << i;
  }
  ++heartbeat_;
  scan();
  EXPECT_EQ(sup_.flags(), 0u);
  EXPECT_EQ(sup_.ended(), STEPMOD_HEALTH_SEQ_BYPASS);
  // Proper seqlock writes are never a bypass.
  for (int i = 0; i < 100; ++i) {
    ++heartbeat_;
    plc_write(3, i);
    scan();
    ASSERT_EQ(sup_.flags(), 0u);
  }
}

}  // namespace
}  // namespace stepmod::ipc
