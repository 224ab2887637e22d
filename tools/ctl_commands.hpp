#pragma once
// PLC-like command sequencing for the 3601, shared by stepmodctl and the tests: each command is
// written exactly the way a PLC program would do it (parameter words + command bit, wait until
// the module has scanned it, release the edge-triggered bit), then the status is read back.
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ipc/client.hpp"
#include "module/personality.hpp"

namespace stepmod::tools::ctl {

enum class AccelType { kConstant, kTriangularS, kTrapezoidalS };

struct Profile {
  std::int32_t speed = 0;  // steps/s (decimal split on the wire)
  std::int32_t accel = 0;  // steps/ms/s, 1..2000
  std::int32_t decel = 0;  // steps/ms/s, 1..2000
  AccelType type = AccelType::kConstant;
};

struct BlendSegment {
  std::int32_t length = 0;  // steps, > 0
  std::int32_t speed = 0;   // steps/s
  std::int32_t accel = 0;   // steps/ms/s used to reach `speed`
  AccelType type = AccelType::kConstant;
};

struct BlendProfile {
  std::vector<BlendSegment> segments;  // 2..16
  std::int32_t final_decel = 0;        // steps/ms/s
  AccelType final_type = AccelType::kConstant;
};

// What a command produced.
struct Outcome {
  bool ok = true;          // no error bit for this command, no timeout
  bool timed_out = false;  // the module did not scan or did not answer a handshake
  std::string message;     // error bits by name, or the timeout, when !ok
  ImageWords in;           // input image after the command
};

class Plc3601 {
 public:
  // `timeout` bounds each wait for the module (scans, handshakes). Throws IpcError if the image
  // is not a 3601's.
  explicit Plc3601(ipc::Client& client,
                   std::chrono::milliseconds timeout = std::chrono::milliseconds(2000));

  // Configuration mode: config bits MSW (bit 15 is added), active levels LSW and starting speed;
  // then back to command mode. Error: Configuration Error.
  Outcome configure(std::uint16_t cfg_msw, std::uint16_t cfg_lsw, std::int32_t start_speed);
  Outcome move(bool absolute, std::int32_t target, const Profile& p, bool encoder_move = false);
  // Manual move (level-held bit) for `duration`, then released and waited until stopped.
  // `registration` > 0 makes it a registration move (digest 7.9).
  Outcome jog(bool cw, const Profile& p, std::chrono::milliseconds duration,
              std::int32_t registration = 0);
  Outcome home(bool cw, const Profile& p);
  Outcome hold();
  // Without a profile the speed/accel/decel words of the previous move stay as they are.
  Outcome resume(const std::optional<Profile>& p);
  Outcome immediate_stop();
  Outcome preset_position(std::int32_t position);
  Outcome preset_encoder(std::int32_t value);
  Outcome reset_errors();
  Outcome set_min_registration(std::int32_t distance);
  // Blend programming handshake (digest 7.10): program bit held, one transmit edge per block,
  // each acknowledged by the module.
  Outcome blend_program(const BlendProfile& b);
  Outcome blend_run(bool cw);
  // Polls until neither Moving CW/CCW nor Blend Running is set.
  Outcome wait_idle(std::chrono::milliseconds timeout);
  // The input image now.
  Outcome status();

  // Bit patterns, exposed for tests.
  static std::uint16_t accel_bits(AccelType t);  // command LSW bits 0/1
  static std::uint16_t pair_bits(AccelType t);   // blend type pair (low = S, high = trapezoid)

 private:
  // Waits until a scan that started after now has completed (counter +2); bumps the heartbeat.
  bool settle();
  // Makes sure none of `bits` is set in output word `word` (so the next set is a 0->1 edge).
  bool release_bits(unsigned word, std::uint16_t bits);
  // Writes words (the whole image), waits for the module, clears `edge_bit` in word 0, waits.
  Outcome edge_command(const ImageWords& words, std::uint16_t edge_bit, std::uint16_t error_mask);
  Outcome finish(std::uint16_t error_mask, bool timed_out, const std::string& what);
  ImageWords outputs() const;
  bool wait_status(std::uint16_t lsw_bit, bool want, std::chrono::milliseconds timeout);

  ipc::Client& c_;
  std::chrono::milliseconds timeout_;
};

}  // namespace stepmod::tools::ctl
