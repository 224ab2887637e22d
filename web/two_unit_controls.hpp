#pragma once
// The console's controls of a two-unit module (3602 axes, 3202 channels): their plc/ drivers
// take the same verbs with the unit first, so every command but the configuration (each module
// has its own configuration words) forwards here once.
#include <optional>

#include "web/controls.hpp"

namespace stepmod::web {

template <class Plc>
class TwoUnitControls : public Controls {
 public:
  explicit TwoUnitControls(plc::Port& port) : plc_(port) {}
  void release_jogs() override {
    for (unsigned u = 0; u < 2; ++u) plc_.jog_release(u);
  }

 protected:
  plc::Outcome move(unsigned u, bool a, std::int32_t t, const plc::Profile& p) override {
    return plc_.move(u, a, t, p);
  }
  plc::Outcome jog_press(unsigned u, bool cw, const plc::Profile& p) override {
    return plc_.jog_press(u, cw, p);
  }
  plc::Outcome jog_release(unsigned u) override { return plc_.jog_release(u); }
  plc::Outcome home(unsigned u, bool cw, const plc::Profile& p) override {
    return plc_.home(u, cw, p);
  }
  plc::Outcome hold(unsigned u) override { return plc_.hold(u); }
  plc::Outcome resume(unsigned u) override { return plc_.resume(u, std::nullopt); }
  plc::Outcome stop(unsigned u) override { return plc_.immediate_stop(u); }
  plc::Outcome reset(unsigned u) override { return plc_.reset_errors(u); }
  plc::Outcome preset(unsigned u, std::int32_t p) override { return plc_.preset_position(u, p); }
  unsigned units() const override { return 2; }

  Plc plc_;
};

}  // namespace stepmod::web
