#pragma once
// plc::Port over EtherNet/IP: the PLC programs of the suite (module_types/*/plc_*.hpp) drive the
// module through st-ethernet-ip's class 1 scanner alone. The output words go out as the
// scanner's O→T data; the input words are the scanner's T→O data, exactly as it received them.
// The shared-memory image is only looked at: a write returns once the image holds the words
// (so a test knows the module can scan them), and scans are counted there.
#include <chrono>
#include <cstdint>
#include <string>

#include "ipc/client.hpp"
#include "plc/port.hpp"
#include "tests/enip/integration/partner_process.hpp"

namespace stepmod::testing {

class EnipPort : public plc::Port {
 public:
  // `scanner`: a partner.js scanner already connected; `image`: the module's image.
  EnipPort(PartnerProcess& scanner, ipc::Client& image);

  ModuleType type() const override { return image_.type(); }
  ImageWords outputs() const override { return out_; }
  void write_outputs(const ImageWords& out) override;
  void update_outputs(const std::function<void(ImageWords&)>& edit) override;
  bool read_inputs(ImageWords& in) const override;
  bool wait_scans(unsigned n) override;
  void pass(std::chrono::nanoseconds d) override;
  bool wait_inputs(const std::function<bool(const ImageWords&)>& done,
                   std::chrono::nanoseconds limit) override;

  // Writes that did not reach the image within the timeout (a test expects none).
  unsigned lost_writes() const { return lost_writes_; }

 private:
  std::string hex_of(const ImageWords& w) const;
  bool wait_fresh_inputs();

  PartnerProcess& scanner_;
  ipc::Client& image_;
  unsigned word_bytes_;
  unsigned out_words_;
  unsigned in_words_;
  ImageWords out_{};
  unsigned lost_writes_ = 0;
};

}  // namespace stepmod::testing
