#pragma once
// A faulty PLC's side of a 3601's image over the real shared memory, for the safety tests
// (tests/integration/daemon_safety_test.cpp): raw words written with the seqlock, and no
// heartbeat unless the test beats it (a well-behaved PLC is module_types/m3601/plc_3601.hpp over plc::ShmPort,
// which beats the heartbeat whenever it waits).
#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <thread>

#include "ipc/client.hpp"
#include "module_types/m3601/words_3601.hpp"

namespace stepmod::testing {

class RawShmPlc {
  using milliseconds = std::chrono::milliseconds;

 public:
  explicit RawShmPlc(const std::string& name) : client_(name) {}

  // A consistent snapshot of the inputs. A read that keeps overlapping the module's writes (a
  // sanitizer build with the pulse thread spinning beside the control thread) is tried again:
  // reporting zeros instead would read as "not moving" and end a wait early.
  ImageWords in() const {
    ImageWords w;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(2);
    while (!client_.read_inputs(w)) {
      if (std::chrono::steady_clock::now() > end) {
        ADD_FAILURE() << "no consistent snapshot of the input image in 2 s";
        break;
      }
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    return w;
  }
  std::uint16_t status_msw() const { return static_cast<std::uint16_t>(in().w[0]); }
  bool status(std::uint16_t bit) const { return (status_msw() & bit) != 0; }
  std::int64_t position() const {
    const auto w = in();
    return words::decode_3601_report(w.w[words::m3601::in_word::kPositionMsw],
                                     w.w[words::m3601::in_word::kPositionLsw]);
  }
  void scans(unsigned n) { ASSERT_TRUE(client_.wait_scans(n, milliseconds(2000))); }

  void write(std::uint16_t msw, std::uint16_t lsw, std::int32_t w23, std::int32_t w45,
             std::int16_t w6, std::int16_t w7) {
    const auto a = words::encode_3601(w23);
    const auto b = words::encode_3601(w45);
    ImageWords o{};
    o.w = {static_cast<std::int16_t>(msw),
           static_cast<std::int16_t>(lsw),
           a.msw,
           a.lsw,
           b.msw,
           b.lsw,
           w6,
           w7};
    client_.write_outputs(o);
  }
  // An edge-triggered command, set until the module has scanned it, then cleared.
  void command(std::uint16_t bit, std::int32_t target = 0, std::int32_t speed = 0,
               std::int16_t accel = 0, std::int16_t decel = 0) {
    write(bit, 0, target, speed, accel, decel);
    scans(3);
    client_.write_word(0, 0);
    scans(2);
  }
  void configure(std::int32_t starting_speed = 1'000) {
    const std::uint16_t cfg =
        words::m3601::cfg_msw::kCaptureUsed | words::m3601::cfg_msw::kExternalUsed |
        words::m3601::cfg_msw::kHomeUsed | words::m3601::cfg_msw::kEStopUsed |
        words::m3601::cfg_msw::kCwLimitUsed | words::m3601::cfg_msw::kCcwLimitUsed |
        words::m3601::cfg_msw::kQuadratureEncoder | words::m3601::cfg_msw::kStepDirOutput;
    write(cfg | words::m3601::cfg_msw::kConfigMode, 0x3F, starting_speed, 0, 0, 0);
    scans(3);
    ASSERT_TRUE(status(words::m3601::status_msw::kConfigMode));
    ASSERT_FALSE(status(words::m3601::status_msw::kConfigurationError));
    write(0, 0, 0, 0, 0, 0);
    scans(3);
    ASSERT_FALSE(status(words::m3601::status_msw::kConfigMode));
  }
  bool moving() const {
    return status(words::m3601::status_msw::kMovingCw) ||
           status(words::m3601::status_msw::kMovingCcw);
  }
  bool wait(const std::function<bool()>& cond, milliseconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      if (cond()) return true;
      std::this_thread::sleep_for(milliseconds(2));
    }
    return cond();
  }
  ipc::Client& client() { return client_; }

 private:
  ipc::Client client_;
};

}  // namespace stepmod::testing
