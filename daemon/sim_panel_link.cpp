#include "daemon/sim_panel_link.hpp"

#include "gpio/sim_backend.hpp"

namespace stepmod::tools {

SimPanelLink::SimPanelLink(const std::string& name, gpio::SimBackend& sim, unsigned axes)
    : sim_(sim), server_(name, axes), axes_(axes) {}

void SimPanelLink::take_forces() {
  for (unsigned a = 0; a < axes_; ++a) {
    sim_.force(a, server_.force_mask(a), server_.force_levels(a));
  }
}

void SimPanelLink::publish() {
  for (unsigned a = 0; a < axes_; ++a) {
    server_.publish_position(a, sim_.position(a));
    server_.publish_encoder(a, sim_.encoder(a));
    server_.publish_outputs(a, sim_.output_levels(a));
  }
}

}  // namespace stepmod::tools
