// Issue 29 on stepmod-web's side (web/commander.hpp): the console's take leaves another tool's
// lease alone (a page retrying "Take control" cannot keep a SIGKILLed holder's axis moving), and
// its stop command works from a page without the lease. The real stepmodd on the simulated 3601,
// a `stepmodctl ... --wait` as the other tool, and the console's Commander in this process.
#include <gtest/gtest.h>
#include <signal.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "tests/support/commissioning_daemon.hpp"
#include "web/commander.hpp"
#include "web/sampler.hpp"

namespace stepmod::testing {
namespace {

using std::chrono::milliseconds;

class WebLease : public ::testing::Test {
 protected:
  void SetUp() override {
    d_ = std::make_unique<CommissioningDaemon>();
    ASSERT_TRUE(d_->ready()) << d_->log();
    ASSERT_EQ(d_->ctl("configure --home --cw-limit --ccw-limit --estop").exit_status, 0);
    sampler_ = std::make_unique<web::Sampler>(d_->name(), [](const std::string&) {});
    web::Commander::Options opt;
    opt.plc_quiet = milliseconds(1);  // no PLC here: the lease decision is the point
    commander_ = std::make_unique<web::Commander>(d_->name(), *sampler_, opt);
    tool_ = d_->ctl_background("move rel 90000 -s 5000 -a 100 -d 100 --wait");
    ASSERT_TRUE(eventually(
        [&] { return d_->holder() == static_cast<std::uint32_t>(tool_) && d_->moving(); },
        milliseconds(10'000)))
        << d_->log();
  }
  void TearDown() override {
    commander_.reset();
    sampler_.reset();
    if (tool_ > 0) kill_and_reap(tool_);
  }
  nlohmann::json handle(const nlohmann::json& req, std::uintptr_t page) {
    return commander_->handle(req, page);
  }
  std::unique_ptr<CommissioningDaemon> d_;
  std::unique_ptr<web::Sampler> sampler_;
  std::unique_ptr<web::Commander> commander_;
  pid_t tool_ = -1;
};

TEST_F(WebLease, RetriedTakeNeverKeepsAKilledHoldersAxisMoving) {
  const std::string holder = std::to_string(tool_);
  const nlohmann::json refused = handle({{"op", "take"}}, 1);
  EXPECT_FALSE(refused["ok"].get<bool>());
  EXPECT_EQ(refused["message"].get<std::string>(),
            "refused: the lease is held by process " + holder)
      << refused.dump();
  // The page retries "Take control" every 20 ms (and keeps its keep-alives coming) while the
  // holder is SIGKILLed.
  std::atomic<bool> stop{false};
  std::atomic<bool> taken{false};
  std::thread page([&] {
    while (!stop) {
      const nlohmann::json r = handle({{"op", "take"}}, 1);
      if (r.is_object() && r["ok"].get<bool>()) taken = true;
      handle({{"op", "keepalive"}}, 1);
      std::this_thread::sleep_for(milliseconds(20));
    }
  });
  kill_and_reap(tool_);
  tool_ = -1;
  const long long took = d_->ms_until_stopped(milliseconds(4000));
  const bool got = eventually([&] { return taken.load(); }, milliseconds(2000));
  stop = true;
  page.join();
  ASSERT_GE(took, 0) << "the axis still moved 4 s after its holder's SIGKILL, the page retrying\n"
                     << d_->log();
  EXPECT_LT(took, 1500);
  EXPECT_NE(d_->log().find("commissioning lease of pid " + holder + " expired without release"),
            std::string::npos)
      << d_->log();
  EXPECT_TRUE(got) << "the page never got the freed lease";  // then it is the page's
  std::printf("[ observed ] stopped %lld ms after the holder's SIGKILL, the page retrying\n", took);
}

TEST_F(WebLease, StopFromAPageWithoutTheLeaseStopsTheAxis) {
  const nlohmann::json r = handle({{"op", "cmd"}, {"cmd", "stop"}, {"unit", 0}}, 2);
  EXPECT_TRUE(r["ok"].get<bool>()) << r.dump();
  const long long took = d_->ms_until_stopped(milliseconds(2000));
  EXPECT_GE(took, 0) << d_->log();
  // Other commands still need the lease, and the holder's lease was not touched.
  const nlohmann::json m = handle({{"op", "cmd"}, {"cmd", "reset"}, {"unit", 0}}, 2);
  EXPECT_EQ(m["message"].get<std::string>(), "refused: take the commissioning lease first");
  EXPECT_EQ(d_->log().find("taken over"), std::string::npos) << d_->log();
  std::printf("[ observed ] stopped %lld ms after the page's stop\n", took);
}

}  // namespace
}  // namespace stepmod::testing
