#pragma once
// The fixture of the EtherNet/IP end-to-end tests: the real stepmodd on the simulated machine
// with [ethernetip] on 127.0.K.1 (K per test process, so that a lingering socket of another
// test never meets this one), its VCD trace, and the npm partners run from 127.0.K.2 (the
// scanner binds UDP 2222 as the adapter does, so it needs an address of its own).
#include <gtest/gtest.h>

#include <unistd.h>

#include <memory>
#include <string>

#include "ipc/client.hpp"
#include "tests/enip/integration/partner_process.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/sim_config.hpp"

namespace stepmod::testing {

// The connection timeout in RPIs the scanner's Forward_Open asks for: st-ethernet-ip's own (32:
// 320 ms at RPI 10 ms), for the tests of the deadman; 128 (1.28 s) for the tests of everything
// else, so that a pause of this shared machine does not stop their moves (the adapter rightly
// stops the axes when the owner falls silent for its timeout).
inline constexpr unsigned kLibraryMultiplier = 32;
inline constexpr unsigned kPatientMultiplier = 128;

class EnipDaemon : public ::testing::Test {
 protected:
  // `module`: the module tables and axes (sim_config.hpp); `extra`: more [ethernetip] keys, in
  // which {SCANNER} is the scanner's address.
  void start(const std::string& module, const std::string& extra = "") {
    const std::string net = "127.0." + std::to_string(100 + ::getpid() % 150) + ".";
    target_ = net + "1";
    scanner_ip_ = net + "2";
    other_ip_ = net + "3";
    std::string keys = extra;  // "{SCANNER}": the scanner's address
    for (auto at = keys.find("{SCANNER}"); at != std::string::npos; at = keys.find("{SCANNER}")) {
      keys.replace(at, 9, scanner_ip_);
    }
    const std::string enip = "\n[ethernetip]\nenabled = true\nlisten = \"" + target_ +
                             ":44818\"\nrpi_min_us = 1000\n" + keys;
    daemon_ = std::make_unique<DaemonProcess>(module + enip);
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
    image_ = std::make_unique<ipc::Client>(daemon_->name());
  }
  // A partner.js scanner, exclusive owner at `rpi_ms`, connected (or a failed assertion); its
  // connection times out after `multiplier` RPIs.
  std::unique_ptr<PartnerProcess> connect_scanner(unsigned rpi_ms = 10,
                                                  unsigned multiplier = kPatientMultiplier) {
    const unsigned bytes = image_->raw().word_bytes * image_->raw().output_words;
    auto s = std::make_unique<PartnerProcess>(std::vector<std::string>{
        "scanner", scanner_config(scanner_ip_, rpi_ms, bytes, multiplier)});
    const auto connected = s->line_with("connected", std::chrono::seconds(10));
    EXPECT_TRUE(connected.has_value()) << s->transcript() << daemon_->log();
    return s;
  }
  std::string scanner_config(const std::string& local, unsigned rpi_ms, unsigned bytes,
                             unsigned multiplier = kLibraryMultiplier) const {
    return "{\"target\":\"" + target_ + "\",\"local\":\"" + local +
           "\",\"rpi\":" + std::to_string(rpi_ms) + ",\"in\":" + std::to_string(bytes) +
           ",\"out\":" + std::to_string(bytes) + ",\"multiplier\":" + std::to_string(multiplier) +
           "}";
  }
  void TearDown() override {
    image_.reset();
    if (daemon_ && daemon_->pid() > 0) {
      EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    }
  }

  std::string target_;
  std::string scanner_ip_;
  std::string other_ip_;
  std::unique_ptr<DaemonProcess> daemon_;
  std::unique_ptr<ipc::Client> image_;
};

}  // namespace stepmod::testing
