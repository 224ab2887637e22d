#pragma once
// The simulator panel /dev/shm/stepmod.<name>.sim (docs/interface.md section 4): the sim backend
// publishes the simulated machine there and reads the inputs a person or a test forces.
#include <cstdint>
#include <string>

#include "ipc/shm_object.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::ipc {

// One axis as read from the panel.
struct PanelAxis {
  std::int64_t position = 0;
  std::int64_t encoder = 0;
  std::uint32_t force_mask = 0;    // bit per input (STEPMOD_IN_*)
  std::uint32_t force_levels = 0;  // electrical level of forced inputs
  std::uint32_t outputs = 0;       // bit 0 step/CW, 1 dir/CCW, 2 GPO
};

// Daemon side. Any thread may publish (each field is one atomic store); forces are read with
// acquire so that a level is never applied before its mask bit is seen.
class SimPanelServer {
 public:
  // Creates the panel for `axes` axes (1..STEPMOD_PANEL_MAX_AXES); same stale-object rules as the
  // image (owner pid at panel offset 16). Throws IpcError.
  SimPanelServer(const std::string& name, unsigned axes);
  SimPanelServer(const SimPanelServer&) = delete;
  SimPanelServer& operator=(const SimPanelServer&) = delete;

  unsigned axes() const noexcept { return axes_; }
  void publish_position(unsigned axis, std::int64_t steps) noexcept;
  void publish_encoder(unsigned axis, std::int64_t counts) noexcept;
  void publish_outputs(unsigned axis, std::uint32_t levels) noexcept;
  // Forced inputs: bit set in the mask = that input reads the matching bit of `levels`.
  std::uint32_t force_mask(unsigned axis) const noexcept;
  std::uint32_t force_levels(unsigned axis) const noexcept;

 private:
  ShmMapping map_;
  stepmod_panel_t* p_ = nullptr;
  unsigned axes_ = 0;
};

// Client side (stepmodctl panel, tests).
class SimPanelClient {
 public:
  // Throws IpcError if the panel is absent (daemon not running or not using the sim backend) or
  // not a version-1 panel.
  explicit SimPanelClient(const std::string& name);

  unsigned axes() const noexcept { return axes_; }
  PanelAxis read(unsigned axis) const;  // axis 0-based; throws IpcError if out of range
  // input: STEPMOD_IN_* (0..5); level: electrical level to force.
  void force(unsigned axis, unsigned input, bool level);
  void release(unsigned axis, unsigned input);
  void release_all(unsigned axis);

 private:
  void check(unsigned axis, unsigned input) const;
  ShmMapping map_;
  stepmod_panel_t* p_ = nullptr;
  unsigned axes_ = 0;
};

}  // namespace stepmod::ipc
