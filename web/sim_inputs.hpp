#pragma once
// The simulated machine's inputs from the page: on a daemon with the sim backend (its panel,
// /dev/shm/stepmod.<name>.sim, ipc/sim_panel.hpp) the page shows which inputs are forced and to
// which level, the outputs (step/CW, dir/CCW, GPO), and forces or releases an input as
// `stepmodctl panel force|release` does. Without the panel (real hardware) there is nothing to
// show and a force is refused.
#include <array>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "ipc/sim_panel.hpp"

namespace stepmod::web {

// The inputs of an axis in the panel's order (STEPMOD_IN_*, InputLine 0..5), named as stepmodctl
// panel names them.
inline constexpr std::array<std::string_view, 6> kInputNames = {"capture", "external", "home",
                                                                "estop",   "cw_limit", "ccw_limit"};

class SimInputs {
 public:
  // Opens the panel of module `name` if there is one.
  explicit SimInputs(const std::string& name);

  bool present() const noexcept { return panel_ != nullptr; }
  // [{"forced": {"cw_limit": 1, ...}, "outputs": {"step": 0, "dir": 0, "gpo": 1}}, ...] per
  // axis; null without a panel.
  nlohmann::json state() const;
  // {"unit", "input": "capture" | "external" | "home" | "estop" | "cw_limit" | "ccw_limit",
  // "level": 0 | 1, or null to release}; std::invalid_argument for a bad field or no panel.
  void force(const nlohmann::json& req);

 private:
  std::unique_ptr<ipc::SimPanelClient> panel_;
};

}  // namespace stepmod::web
