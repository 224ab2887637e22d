#include "web/controls.hpp"

#include <stdexcept>
#include <string>

#include "plc/plc_3202.hpp"
#include "plc/plc_3601.hpp"
#include "plc/plc_3602.hpp"

namespace stepmod::web {
namespace {

std::int64_t field(const nlohmann::json& req, const char* name, std::int64_t lo, std::int64_t hi) {
  if (!req.contains(name) || !req[name].is_number_integer()) {
    throw std::invalid_argument(std::string("missing integer field '") + name + "'");
  }
  const auto v = req[name].get<std::int64_t>();
  if (v < lo || v > hi) {
    throw std::invalid_argument(std::string(name) + " " + std::to_string(v) + " is outside " +
                                std::to_string(lo) + ".." + std::to_string(hi));
  }
  return v;
}

// The profile fields as the page sends them; the module itself checks the manual's ranges and
// answers with Invalid Profile / Command Error, which the page shows with the reason.
plc::Profile profile_of(const nlohmann::json& req) {
  plc::Profile p;
  p.speed = static_cast<std::int32_t>(field(req, "speed", 0, 2'000'000'000));
  p.accel = static_cast<std::int32_t>(field(req, "accel", 0, 1'000'000));
  p.decel = static_cast<std::int32_t>(field(req, "decel", 0, 1'000'000));
  const auto t = field(req, "profile", 0, 2);
  p.type = static_cast<plc::AccelType>(t);
  return p;
}

bool cw_of(const nlohmann::json& req) {
  const std::string d = req.value("dir", "");
  if (d != "cw" && d != "ccw") throw std::invalid_argument("dir must be \"cw\" or \"ccw\"");
  return d == "cw";
}

class Controls3601 final : public Controls {
 public:
  explicit Controls3601(plc::Port& port) : plc_(port) {}
  void release_jogs() override { plc_.jog_release(); }

 protected:
  plc::Outcome move(unsigned, bool a, std::int32_t t, const plc::Profile& p) override {
    return plc_.move(a, t, p);
  }
  plc::Outcome jog_press(unsigned, bool cw, const plc::Profile& p) override {
    return plc_.jog_press(cw, p);
  }
  plc::Outcome jog_release(unsigned) override { return plc_.jog_release(); }
  plc::Outcome home(unsigned, bool cw, const plc::Profile& p) override { return plc_.home(cw, p); }
  plc::Outcome hold(unsigned) override { return plc_.hold(); }
  plc::Outcome resume(unsigned) override { return plc_.resume(std::nullopt); }
  plc::Outcome stop(unsigned) override { return plc_.immediate_stop(); }
  plc::Outcome reset(unsigned) override { return plc_.reset_errors(); }
  plc::Outcome preset(unsigned, std::int32_t p) override { return plc_.preset_position(p); }
  plc::Outcome configure(unsigned, std::uint32_t bits, std::int32_t vs) override {
    return plc_.configure(static_cast<std::uint16_t>(bits >> 16),
                          static_cast<std::uint16_t>(bits & 0xFFFFu), vs);
  }
  unsigned units() const override { return 1; }

 private:
  plc::Plc3601 plc_;
};

class Controls3602 final : public Controls {
 public:
  explicit Controls3602(plc::Port& port) : plc_(port) {}
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
  plc::Outcome configure(unsigned u, std::uint32_t bits, std::int32_t vs) override {
    return plc_.configure(u, static_cast<std::uint16_t>(bits >> 16),
                          static_cast<std::uint16_t>(bits & 0xFFFFu), vs);
  }
  unsigned units() const override { return 2; }

 private:
  plc::Plc3602 plc_;
};

// The 3202's two channels: steps/s^2 rates, one configuration DINT (bit 31, the mode, is added
// by plc/), jog = the manual-move bits held.
class Controls3202 final : public Controls {
 public:
  explicit Controls3202(plc::Port& port) : plc_(port) {}
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
  std::uint32_t config_bits(const nlohmann::json& req) const override {
    return static_cast<std::uint32_t>(field(req, "bits", 0, 0x7FFFFFFF));
  }
  plc::Outcome configure(unsigned u, std::uint32_t bits, std::int32_t vs) override {
    return plc_.configure(u, bits, vs);
  }
  unsigned units() const override { return 2; }

 private:
  plc::Plc3202 plc_;
};

}  // namespace

std::uint32_t Controls::config_bits(const nlohmann::json& req) const {
  return static_cast<std::uint32_t>(field(req, "msw", 0, 0xFFFF)) << 16 |
         static_cast<std::uint32_t>(field(req, "lsw", 0, 0xFFFF));
}

plc::Outcome Controls::run(const nlohmann::json& req) {
  const std::string cmd = req.value("cmd", "");
  const auto u = static_cast<unsigned>(field(req, "unit", 0, units() - 1));
  if (cmd == "move") {
    return move(u, req.value("absolute", false),
                static_cast<std::int32_t>(field(req, "target", -2'000'000'000, 2'000'000'000)),
                profile_of(req));
  }
  if (cmd == "jog_press") return jog_press(u, cw_of(req), profile_of(req));
  if (cmd == "jog_release") return jog_release(u);
  if (cmd == "home") return home(u, cw_of(req), profile_of(req));
  if (cmd == "hold") return hold(u);
  if (cmd == "resume") return resume(u);
  if (cmd == "stop") return stop(u);
  if (cmd == "reset") return reset(u);
  if (cmd == "preset") {
    return preset(u,
                  static_cast<std::int32_t>(field(req, "position", -2'000'000'000, 2'000'000'000)));
  }
  if (cmd == "configure") {
    return configure(u, config_bits(req),
                     static_cast<std::int32_t>(field(req, "start_speed", 0, 2'000'000'000)));
  }
  throw std::invalid_argument("unknown command '" + cmd + "'");
}

std::unique_ptr<Controls> make_controls(plc::Port& port) {
  switch (port.type()) {
    case ModuleType::k3601:
      return std::make_unique<Controls3601>(port);
    case ModuleType::k3602:
      return std::make_unique<Controls3602>(port);
    case ModuleType::k3202:
      break;
  }
  return std::make_unique<Controls3202>(port);
}

}  // namespace stepmod::web
