#pragma once
// The console's view of the image: a thread that takes a seqlock snapshot of the input image every
// `period` (1 ms by default; the plot's resolution) and hands a batch of samples plus the latest
// full status to `publish` every `batch` (40 ms: 25 updates a second, a margin over the 20 the page
// needs on a loaded machine). It only reads the image, so the module's threads never wait for it.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "ipc/client.hpp"
#include "web/sim_inputs.hpp"

namespace stepmod::web {

// What the sampler knows of the PLC link, for the lease decision.
struct PlcLink {
  std::uint64_t heartbeat = 0;
  std::chrono::steady_clock::time_point heartbeat_changed{};
  bool stale = false;  // daemon health bit 1
};

// The daemon is taken for gone when its image's scan counter has not moved for this long (its
// scan period is at most 100 ms; a stopped or killed daemon's image stays mapped, frozen).
inline constexpr std::chrono::milliseconds kDaemonGone{500};

class Sampler {
 public:
  using Publish = std::function<void(const std::string& json)>;

  Sampler(const std::string& module_name, Publish publish,
          std::chrono::microseconds period = std::chrono::microseconds(1000),
          std::chrono::milliseconds batch = std::chrono::milliseconds(40));
  ~Sampler();
  Sampler(const Sampler&) = delete;
  Sampler& operator=(const Sampler&) = delete;

  // The heartbeat as last seen (thread-safe copy).
  PlcLink plc_link() const;
  // How long the image's scan counter has not moved (the daemon is gone past kDaemonGone).
  std::chrono::milliseconds image_quiet() const;
  // Samples taken and batches published so far (for the measurement in docs/web-console.md).
  std::uint64_t samples() const noexcept { return samples_.load(); }

 private:
  struct Sample {
    std::int64_t t_us;
    std::int64_t pos[2];
    std::int64_t enc[2];  // the encoder registers (0 on a module without encoder input)
  };
  void run();
  void take_sample(std::int64_t t_us);
  std::string batch_json();

  ipc::Client client_;
  SimInputs sim_;  // the simulated machine's forced inputs and outputs, where there is one
  Publish publish_;
  std::chrono::microseconds period_;
  std::chrono::milliseconds batch_;
  std::vector<Sample> pending_;
  ImageWords last_in_{};
  mutable std::mutex link_m_;
  PlcLink link_;
  std::uint64_t scan_ = 0;
  std::chrono::steady_clock::time_point scan_changed_{};
  std::atomic<std::uint64_t> samples_{0};
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace stepmod::web
