#pragma once
// The page's commissioning commands, each written exactly as a PLC writes it: one JSON request
// ({"cmd": "move", "unit": 0, ...}) becomes one call of the module's plc/ dialect (Plc3601,
// Plc3602, Plc3202) over a port without heartbeat. Bad input (unknown command, missing or
// out-of-range field) is refused with a message before anything is written.
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "plc/move_profile.hpp"
#include "plc/port.hpp"

namespace stepmod::web {

class Controls {
 public:
  virtual ~Controls() = default;
  // Runs the command; the outcome of the plc/ call (ok, message = error bits by name).
  plc::Outcome run(const nlohmann::json& req);
  // Ends a held jog of every unit (the operator let go; also before a release of the lease).
  virtual void release_jogs() = 0;

 protected:
  virtual plc::Outcome move(unsigned u, bool absolute, std::int32_t target,
                            const plc::Profile& p) = 0;
  virtual plc::Outcome jog_press(unsigned u, bool cw, const plc::Profile& p) = 0;
  virtual plc::Outcome jog_release(unsigned u) = 0;
  virtual plc::Outcome home(unsigned u, bool cw, const plc::Profile& p) = 0;
  virtual plc::Outcome hold(unsigned u) = 0;
  virtual plc::Outcome resume(unsigned u) = 0;
  virtual plc::Outcome stop(unsigned u) = 0;
  virtual plc::Outcome reset(unsigned u) = 0;
  virtual plc::Outcome preset(unsigned u, std::int32_t position) = 0;
  // The configuration bits as one 32-bit value: MSW << 16 | LSW on the 3601/3602 (the request's
  // "msw" and "lsw"), the configuration DINT on the 3202 ("bits").
  virtual std::uint32_t config_bits(const nlohmann::json& req) const;
  // `homing_timeout_s`: the 3602's homing timeout word (0: none); the other modules have no
  // such word, and a request that sets one is refused before this.
  virtual plc::Outcome configure(unsigned u, std::uint32_t bits, std::int32_t start_speed,
                                 std::int16_t homing_timeout_s) = 0;
  virtual unsigned units() const = 0;
  // Whether the configuration has a homing timeout word (the 3602's).
  virtual bool has_homing_timeout() const { return false; }
  // A command only this module has (the 3602's "path" and "gpo"); nullopt: none such.
  virtual std::optional<plc::Outcome> module_command(const std::string& cmd, unsigned u,
                                                     const nlohmann::json& req) {
    (void)cmd, (void)u, (void)req;
    return std::nullopt;
  }
};

// The integer field `name` of a request, checked against lo..hi (std::invalid_argument naming the
// field otherwise).
std::int64_t request_int(const nlohmann::json& req, const char* name, std::int64_t lo,
                         std::int64_t hi);

// The controls of the module behind `port` (its row in web/module_views.cpp).
std::unique_ptr<Controls> make_controls(plc::Port& port);

}  // namespace stepmod::web
