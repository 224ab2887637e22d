// The image's error-reason blocks (docs/interface.md 3.4, docs/error-reasons.md) and the
// commissioning lease (3.5, docs/commissioning.md): the daemon's LeaseWatch, the tools' Lease
// (explicit renew) and LeaseClient (renewed by its thread) over a real shared-memory image.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <atomic>
#include <climits>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "ipc/lease.hpp"
#include "ipc/lease_client.hpp"
#include "ipc/lease_watch.hpp"
#include "ipc/shm_image.hpp"

namespace stepmod::ipc {
namespace {

constexpr ModuleShape k3602{ModuleType::k3602, 2, 2, 16, 16};

std::string test_name(const char* tag) {
  return std::string("t-") + tag + "-" + std::to_string(::getpid());
}

stepmod_reason_t reason(std::uint32_t seq, std::uint32_t item, const char* text) {
  stepmod_reason_t r{};
  r.seq = seq;
  r.item = item;
  std::strncpy(r.text, text, sizeof r.text - 1);
  return r;
}

TEST(ReasonBlock, AtOffset448PlusSixtyFourPerAxisUnderTheInputSeqlock) {
  EXPECT_EQ(offsetof(stepmod_image_t, reasons), 448u);
  EXPECT_EQ(offsetof(stepmod_image_t, reasons[1]), 512u);
  EXPECT_EQ(offsetof(stepmod_reason_t, item), 4u);
  EXPECT_EQ(offsetof(stepmod_reason_t, text), 8u);
  EXPECT_EQ(offsetof(stepmod_image_t, lease_holder), 576u);
  EXPECT_EQ(offsetof(stepmod_image_t, lease_seq), 580u);
  EXPECT_EQ(offsetof(stepmod_image_t, lease_expiry_ns), 584u);

  ShmImage image(test_name("reason"), k3602);
  Client client(image.name());
  EXPECT_EQ(client.read_reason(1).seq, 0u);
  image.set_reason(1, reason(3, 20206, "3602-CE-06: Vp 400 is below Vs 1000"));
  // Not visible before the publication it belongs to.
  EXPECT_EQ(client.read_reason(1).seq, 0u);
  const std::uint32_t seq_before = image.raw().input_seq;
  image.publish_inputs(ImageWords{});
  EXPECT_EQ(image.raw().input_seq, seq_before + 2);
  const stepmod_reason_t r = client.read_reason(1);
  EXPECT_EQ(r.seq, 3u);
  EXPECT_EQ(r.item, 20206u);
  EXPECT_STREQ(r.text, "3602-CE-06: Vp 400 is below Vs 1000");
  const auto* raw = reinterpret_cast<const unsigned char*>(&image.raw());
  std::uint32_t item = 0;
  std::memcpy(&item, raw + 448 + 64 + 4, 4);
  EXPECT_EQ(item, 20206u);
  EXPECT_STREQ(reinterpret_cast<const char*>(raw + 448 + 64 + 8),
               "3602-CE-06: Vp 400 is below Vs 1000");
  EXPECT_EQ(client.read_reason(0).seq, 0u);  // axis 1 untouched
}

// Threads of this process the kernel runs at SCHED_FIFO `priority` (/proc/self/task/*/stat:
// rt_priority and policy, the 40th and 41st fields; the 3rd onwards follow the name's ')').
int fifo_threads_at(int priority) {
  int n = 0;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream in(task.path() / "stat");
    std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto close = stat.rfind(')');
    if (close == std::string::npos) continue;
    std::istringstream fields(stat.substr(close + 2));
    std::string f;
    int rt_priority = -1;
    int policy = -1;
    for (int i = 3; i <= 41 && fields >> f; ++i) {
      if (i == 40) rt_priority = std::stoi(f);
      if (i == 41) policy = std::stoi(f);
    }
    if (policy == SCHED_FIFO && rt_priority == priority) ++n;
  }
  return n;
}

// Whether this process may run a thread at SCHED_FIFO `priority` (root, CAP_SYS_NICE or
// RLIMIT_RTPRIO), asked of a probe thread of its own.
bool may_run_fifo_at(int priority) {
  bool ok = false;
  std::thread probe([&] {
    sched_param sp{};
    sp.sched_priority = priority;
    ok = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp) == 0;
  });
  probe.join();
  return ok;
}

class Lease : public ::testing::Test {
 protected:
  Lease() : image_(test_name("lease"), k3602), client_(image_.name()) {}
  LeaseWatch::Event scan() { return watch_.scan(image_, heartbeat_, stepmod_monotonic_ns()); }
  stepmod_image_t& img() { return client_.writable_image(); }
  ShmImage image_;
  Client client_;
  LeaseWatch watch_;
  std::uint64_t heartbeat_ = 0;
};

TEST_F(Lease, TakenRenewedAndReleased) {
  LeaseClient tool(client_, 4242);
  // A daemon reports the heartbeat stale (bit 1): the lease is taken at once.
  image_.publish_inputs(ImageWords{}, Health{STEPMOD_HEALTH_PLC_STALE, 0, 0});
  ASSERT_EQ(tool.take(std::chrono::milliseconds(1)), LeaseClient::Take::kTaken);
  EXPECT_EQ(img().lease_holder, 4242u);
  EXPECT_EQ(img().lease_seq, 1u);
  const LeaseWatch::Event taken = scan();
  EXPECT_TRUE(taken.taken);
  EXPECT_EQ(taken.holder, 4242u);
  EXPECT_TRUE(watch_.held());
  // Renewed: after twice the contract's 500 ms it is still held, the expiry ahead of now.
  for (int i = 0; i < 10; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const LeaseWatch::Event e = scan();
    EXPECT_FALSE(e.expired);
    // Atomic, as the daemon reads it: the tool's thread writes it.
    const auto expiry = __atomic_load_n(&img().lease_expiry_ns, __ATOMIC_ACQUIRE);
    const auto ahead = static_cast<std::int64_t>(expiry) - stepmod_monotonic_ns();
    EXPECT_GT(ahead, 0);
    EXPECT_LE(ahead, 500'000'000);
  }
  EXPECT_TRUE(tool.held());
  tool.release();
  EXPECT_EQ(img().lease_holder, 0u);
  EXPECT_TRUE(scan().released);
  EXPECT_FALSE(watch_.held());
  EXPECT_EQ(watch_.flags(), 0u);
}

TEST_F(Lease, ExpiredLeaseIsFreedAndSetsBit6UntilAPlcOrANewTake) {
  img().lease_expiry_ns = static_cast<std::uint64_t>(stepmod_monotonic_ns() + 50'000'000);
  img().lease_holder = 999'999;  // a tool that died without releasing
  img().lease_seq = 7;
  EXPECT_TRUE(scan().taken);
  std::this_thread::sleep_for(std::chrono::milliseconds(80));
  const LeaseWatch::Event e = scan();
  EXPECT_TRUE(e.expired);
  EXPECT_EQ(img().lease_holder, 0u);
  EXPECT_EQ(watch_.flags(), STEPMOD_HEALTH_LEASE_EXPIRED);
  EXPECT_FALSE(scan().expired);  // once
  EXPECT_EQ(watch_.flags(), STEPMOD_HEALTH_LEASE_EXPIRED);
  ++heartbeat_;  // a PLC takes over
  scan();
  EXPECT_EQ(watch_.flags(), 0u);
}

TEST_F(Lease, HeartbeatDuringALeaseSetsBit7) {
  LeaseClient tool(client_, 4343);
  image_.publish_inputs(ImageWords{}, Health{STEPMOD_HEALTH_PLC_STALE, 0, 0});
  ASSERT_EQ(tool.take(std::chrono::milliseconds(1)), LeaseClient::Take::kTaken);
  scan();
  EXPECT_EQ(watch_.flags(), 0u);
  ++heartbeat_;
  EXPECT_TRUE(scan().conflict);
  EXPECT_EQ(watch_.flags(), STEPMOD_HEALTH_LEASE_CONFLICT);
  ++heartbeat_;
  EXPECT_FALSE(scan().conflict);  // said once per lease
  tool.release();
  scan();
  EXPECT_EQ(watch_.flags(), 0u);
}

TEST_F(Lease, RefusedWhileAPlcHeartbeatIsLive) {
  std::atomic<bool> stop{false};
  Client plc(image_.name());
  std::thread beat([&] {
    while (!stop.load()) {
      plc.heartbeat();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  });
  LeaseClient tool(client_, 4444);
  EXPECT_EQ(tool.take(std::chrono::milliseconds(300)), LeaseClient::Take::kPlcInControl);
  EXPECT_EQ(img().lease_holder, 0u);
  stop = true;
  beat.join();
  // The PLC gone: the heartbeat unchanged for the whole watch, the lease is taken.
  EXPECT_EQ(tool.take(std::chrono::milliseconds(100)), LeaseClient::Take::kTaken);
  // A second tool finds it held.
  LeaseClient other(client_, 4545);
  EXPECT_EQ(other.take(std::chrono::milliseconds(1)), LeaseClient::Take::kHeldByOther);
}

// The daemon's watcher is its SCHED_FIFO control thread: a renewer at normal priority held off
// the CPU by ordinary load let stepmodctl's lease expire mid-move (CI, Debian 13 stage). The
// renewer runs at SCHED_FIFO kRenewerPriority whenever the process may, and the kernel says so.
TEST_F(Lease, RenewerRunsAtSchedFifoWheneverTheProcessMay) {
  const int prio = LeaseClient::kRenewerPriority;
  const bool may = may_run_fifo_at(prio);
  const int before = fifo_threads_at(prio);
  LeaseClient tool(client_, 4646);
  image_.publish_inputs(ImageWords{}, Health{STEPMOD_HEALTH_PLC_STALE, 0, 0});
  ASSERT_EQ(tool.take(std::chrono::milliseconds(1)), LeaseClient::Take::kTaken);
  EXPECT_EQ(tool.renewer_realtime(), may);
  EXPECT_EQ(fifo_threads_at(prio), before + (may ? 1 : 0));
  tool.release();
  EXPECT_FALSE(tool.renewer_realtime());
  EXPECT_EQ(fifo_threads_at(prio), before);  // the renewer is gone with the lease
}

// The explicit core (stepmod-web's deadman): held while renewed, expired by the daemon once the
// renewals stop, and then no longer renewable; a second holder is refused; a release frees only
// its own lease.
TEST_F(Lease, ExplicitLeaseExpiresWhenRenewalsStop) {
  ipc::Lease lease(client_, 5151);
  ipc::Lease other(client_, 5252);
  ASSERT_TRUE(lease.take());
  EXPECT_EQ(ipc::Lease::holder_of(client_.raw()), 5151u);
  EXPECT_EQ(img().lease_seq, 1u);
  EXPECT_FALSE(other.take());
  other.release();  // not its lease: nothing happens
  EXPECT_EQ(lease.holder(), 5151u);
  EXPECT_TRUE(scan().taken);
  for (int i = 0; i < 6; ++i) {  // renewed: still held after 600 ms
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    ASSERT_TRUE(lease.renew());
    EXPECT_FALSE(scan().expired);
  }
  const auto ahead =
      static_cast<std::int64_t>(ipc::Lease::expiry_of(client_.raw())) - stepmod_monotonic_ns();
  EXPECT_GT(ahead, 0);
  EXPECT_LE(ahead, 500'000'000);
  // No more renewals: the daemon's watch finds it expired within the contract's 500 ms.
  bool expired = false;
  for (int i = 0; i < 60 && !expired; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    expired = scan().expired;
  }
  EXPECT_TRUE(expired);
  EXPECT_FALSE(lease.held());
  EXPECT_FALSE(lease.renew());  // freed by the daemon: nothing written
  EXPECT_EQ(watch_.flags(), STEPMOD_HEALTH_LEASE_EXPIRED);
  EXPECT_TRUE(other.take());  // free again for the next tool
}

// ---- issue 29: only a live holder keeps a lease -------------------------------------------------

// A take that finds the lease held writes nothing: not the expiry (before the fix it stored its
// own expiry ahead of the compare-and-swap), not the sequence.
TEST_F(Lease, TakeOfAHeldLeaseWritesNothing) {
  ipc::Lease holder(client_, 6161);
  ASSERT_TRUE(holder.take());
  const std::uint64_t expiry = ipc::Lease::expiry_of(client_.raw());
  const std::uint32_t seq = img().lease_seq;
  ipc::Lease other(client_, 6262);
  for (int i = 0; i < 20; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    EXPECT_FALSE(other.take());
  }
  EXPECT_EQ(ipc::Lease::expiry_of(client_.raw()), expiry);
  EXPECT_EQ(img().lease_seq, seq);
  EXPECT_EQ(holder.holder(), 6161u);
}

// A holder that died 100 ms before its expiry, and a tool retrying its take every 5 ms: the
// daemon's watch still expires the dead holder's lease at its own expiry.
TEST_F(Lease, RetriedTakeDoesNotExtendADeadHoldersLease) {
  const Nanos last = stepmod_monotonic_ns() + 100'000'000;
  img().lease_expiry_ns = static_cast<std::uint64_t>(last);
  img().lease_holder = 999'998;
  img().lease_seq = 3;
  ASSERT_TRUE(scan().taken);
  ipc::Lease retrier(client_, 6363);
  LeaseWatch::Event e;
  const Nanos give_up = last + 2'000'000'000;
  while (!e.expired && stepmod_monotonic_ns() < give_up) {
    EXPECT_FALSE(retrier.take());  // held by the dead holder until the watch frees it
    e = scan();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(e.expired) << "the retried take kept the dead holder's lease for 2 s";
  EXPECT_EQ(e.holder, 999'998u);
  // Expired at its own deadline: 5 ms polls, a loaded machine's margin.
  EXPECT_LT(stepmod_monotonic_ns() - last, 300'000'000);
  EXPECT_EQ(watch_.flags(), STEPMOD_HEALTH_LEASE_EXPIRED);
  EXPECT_TRUE(retrier.take());  // then free for the live tool
}

// Expiries no live holder writes: expired (and freed, bit 6) at the scan that sees them.
TEST_F(Lease, ExpiryFurtherAheadThanTheContractIsExpiredAtOnce) {
  timespec rt{};
  ::clock_gettime(CLOCK_REALTIME, &rt);
  const std::uint64_t realtime = static_cast<std::uint64_t>(rt.tv_sec) * 1'000'000'000u +
                                 static_cast<std::uint64_t>(rt.tv_nsec) + 400'000'000u;
  const auto ahead = [](Nanos ns) {
    return static_cast<std::uint64_t>(stepmod_monotonic_ns() + ns);
  };
  const std::uint64_t garbage[] = {ahead(10'000'000'000), ahead(700'000'000), realtime,
                                   static_cast<std::uint64_t>(INT64_MAX), UINT64_MAX};
  std::uint32_t pid = 7000;
  for (const std::uint64_t expiry : garbage) {
    img().lease_expiry_ns = expiry;
    img().lease_holder = ++pid;
    ++img().lease_seq;
    const LeaseWatch::Event e = scan();
    EXPECT_TRUE(e.taken) << expiry;
    EXPECT_TRUE(e.expired) << expiry;
    EXPECT_EQ(img().lease_holder, 0u) << expiry;
    EXPECT_EQ(watch_.flags(), STEPMOD_HEALTH_LEASE_EXPIRED) << expiry;
    EXPECT_FALSE(watch_.held());
  }
  // What a live holder writes (400 ms ahead) stands.
  img().lease_expiry_ns = ahead(400'000'000);
  img().lease_holder = ++pid;
  ++img().lease_seq;
  EXPECT_FALSE(scan().expired);
  EXPECT_TRUE(watch_.held());
}

// The take's order, compare-and-swap first: between it and the take's expiry the image still holds
// the previous holder's (here passed) expiry. That is no expiry of the new holder's: the watch
// waits for the take's sequence increment, for 500 ms at most.
TEST_F(Lease, TakeUnderWayIsNotExpiredByThePreviousExpiry) {
  img().lease_expiry_ns = static_cast<std::uint64_t>(stepmod_monotonic_ns() - 1'000'000'000);
  img().lease_holder = 8080;  // compare-and-swap done; expiry and sequence to come
  LeaseWatch::Event e = scan();
  EXPECT_FALSE(e.expired);
  EXPECT_FALSE(e.taken);
  EXPECT_FALSE(watch_.held());  // nothing held yet: the heartbeat timeout applies
  img().lease_expiry_ns = static_cast<std::uint64_t>(stepmod_monotonic_ns() + 400'000'000);
  ++img().lease_seq;
  e = scan();
  EXPECT_TRUE(e.taken);
  EXPECT_FALSE(e.expired);
  EXPECT_TRUE(watch_.held());
  // A taker that dies between the two: expired once 500 ms have passed without the increment.
  img().lease_holder = 0;
  scan();
  img().lease_holder = 9090;
  const Nanos from = stepmod_monotonic_ns();
  e = scan();
  while (!e.expired && stepmod_monotonic_ns() - from < 2'000'000'000) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    e = scan();
  }
  ASSERT_TRUE(e.expired);
  EXPECT_GE(stepmod_monotonic_ns() - from, kLeaseMaxAheadNs);
  EXPECT_EQ(e.cause, LeaseWatch::Cause::kIncompleteTake);
  EXPECT_EQ(img().lease_holder, 0u);
  EXPECT_EQ(watch_.flags(), STEPMOD_HEALTH_LEASE_EXPIRED);
}

// stepmodctl --steal: the lease changes hands without a release, and the watch says from whom.
TEST_F(Lease, TakeOverReplacesTheHolderAndTheWatchSaysFromWhom) {
  ipc::Lease first(client_, 4711);
  ipc::Lease second(client_, 4712);
  ASSERT_TRUE(first.take());
  EXPECT_TRUE(scan().taken);
  EXPECT_FALSE(second.take_over(4799));  // not the holder: nothing
  EXPECT_TRUE(first.held());
  ASSERT_TRUE(second.take_over(4711));
  EXPECT_FALSE(first.held());
  EXPECT_FALSE(first.renew());  // the old holder's renewals stop
  const LeaseWatch::Event e = scan();
  EXPECT_TRUE(e.taken);
  EXPECT_EQ(e.taken_from, 4711u);
  EXPECT_EQ(e.holder, 4712u);
  EXPECT_NE(watch_.held_until(), 0);
}

TEST(LeaseProcess, RunningIsKillZero) {
  EXPECT_TRUE(ipc::Lease::process_running(static_cast<std::uint32_t>(::getpid())));
  EXPECT_FALSE(ipc::Lease::process_running(0));
  EXPECT_FALSE(ipc::Lease::process_running(0xFFFFFFFFu));  // not kill(-1, 0)
}

}  // namespace
}  // namespace stepmod::ipc
