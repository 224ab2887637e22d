#include "web/sim_inputs.hpp"

#include <array>
#include <stdexcept>
#include <string_view>

#include "web/controls.hpp"

namespace stepmod::web {
namespace {
constexpr const auto& kInputs = kInputNames;
}  // namespace

SimInputs::SimInputs(const std::string& name) {
  try {
    panel_ = std::make_unique<ipc::SimPanelClient>(name);
  } catch (const ipc::IpcError&) {
    panel_.reset();  // real hardware (or no daemon): no simulated inputs
  }
}

nlohmann::json SimInputs::state() const {
  if (!panel_) return nullptr;
  nlohmann::json axes = nlohmann::json::array();
  for (unsigned a = 0; a < panel_->axes(); ++a) {
    const ipc::PanelAxis p = panel_->read(a);
    nlohmann::json forced = nlohmann::json::object();
    for (unsigned i = 0; i < kInputs.size(); ++i) {
      if (p.force_mask & (1u << i)) forced[std::string(kInputs[i])] = (p.force_levels >> i) & 1u;
    }
    axes.push_back({{"forced", forced},
                    {"outputs",
                     {{"step", p.outputs & 1u},
                      {"dir", (p.outputs >> 1) & 1u},
                      {"gpo", (p.outputs >> 2) & 1u}}}});
  }
  return axes;
}

void SimInputs::force(const nlohmann::json& req) {
  if (!panel_) throw std::invalid_argument("no simulated machine: inputs are forced only there");
  const auto unit = static_cast<unsigned>(request_int(req, "unit", 0, panel_->axes() - 1));
  const std::string input = req.contains("input") && req["input"].is_string() ? req["input"] : "";
  unsigned index = 0;
  while (index < kInputs.size() && kInputs[index] != input) ++index;
  if (index == kInputs.size()) {
    throw std::invalid_argument(
        "input must be capture, external, home, estop, cw_limit or "
        "ccw_limit");
  }
  if (!req.contains("level")) throw std::invalid_argument("missing field 'level' (0, 1 or null)");
  if (req["level"].is_null()) {
    panel_->release(unit, index);
  } else {
    panel_->force(unit, index, request_int(req, "level", 0, 1) != 0);
  }
}

}  // namespace stepmod::web
