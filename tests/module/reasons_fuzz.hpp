#pragma once
// Error bits and reasons agree on every scan (docs/error-reasons.md): random command sequences
// run on a module in virtual time, and after every scan each axis' (channel's) status bits are
// compared with the reason the daemon would publish with them (daemon/reason_publisher: after the
// scan, with the input image). Three rules:
//  * rise     - an error bit that rises comes with a new reason in the same scan;
//  * shown    - a new reason names a list whose bit is set, and starts with its own item id;
//  * specific - a new reason is a condition's own, never the general one that names only the
//               list ("3602-CE: Command Error": a bit set on a path that recorded no reason),
//               and a refusal (Command Error) names its item ("3601-CE-S2", not "3601-CE").
// Configuration mode hides every bit but Configuration Error (the status word echoes the
// configuration): what is set meanwhile is judged by the reasons recorded meanwhile. A scan whose
// words clear latches (Reset Errors, Preset Position) may record a reason of a bit it also clears.
// The drivers (reasons_fuzz_XXXX_test.cpp) write the words; seeded (STEPMOD_FUZZ_SEED replaces
// the default), so a failure is reproduced by its seed. 20,000 scans a module take well under a
// second.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <initializer_list>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "module/axis/error_reason.hpp"
#include "tests/support/virtual_machine.hpp"
#include "tools/ctl_dialects.hpp"

namespace stepmod::testing::fuzz {

// std::mt19937's sequence is fixed by the standard; the draws below use no std distribution
// (whose algorithm is the library's), so a seed gives the same run everywhere.
class Rng {
 public:
  explicit Rng(std::uint32_t seed) : g_(seed) {}
  unsigned below(unsigned n) { return static_cast<unsigned>(g_() % n); }
  bool percent(unsigned p) { return below(100) < p; }
  std::uint32_t bits() { return static_cast<std::uint32_t>(g_()); }
  template <class T>
  T pick(std::initializer_list<T> values) {
    return *(values.begin() + below(static_cast<unsigned>(values.size())));
  }

 private:
  std::mt19937 g_;
};

inline std::uint32_t seed(std::uint32_t fallback) {
  const char* s = std::getenv("STEPMOD_FUZZ_SEED");
  return s != nullptr ? static_cast<std::uint32_t>(std::strtoul(s, nullptr, 0)) : fallback;
}

struct Tally {
  unsigned scans = 0;
  unsigned rises = 0;    // error bits that rose
  unsigned reasons = 0;  // new reasons recorded
  unsigned rise_without_reason = 0;
  unsigned reason_of_clear_bit = 0;
  unsigned general_reason = 0;
  unsigned unnumbered_refusal = 0;  // a Command Error reason without its item number
  std::set<std::uint32_t> codes;    // every item code seen
  std::vector<std::string> first;   // the first mismatches, described
  unsigned mismatches() const {
    return rise_without_reason + reason_of_clear_bit + general_reason + unnumbered_refusal;
  }
};

class ReasonChecker {
 public:
  // The first scan (power-up, every word 0) is checked too: the reasons recorded before it
  // (3601-CFG-01) are its.
  explicit ReasonChecker(VirtualMachine& vm)
      : vm_(vm),
        units_(shape_of(vm.type()).axes),
        bits_(units_, 0),
        blind_(units_, false),
        seq_(units_, 0),
        text_(units_) {
    scan();
  }

  // One scan, then the rules on every unit.
  void scan() {
    vm_.run_until_true([] { return true; }, vm_options_scan_ns);
    ++t_.scans;
    const auto sums = tools::ctl::ctl_row_of(vm_.type()).summarize(vm_.plc_in());
    for (unsigned u = 0; u < units_; ++u) check(u, sums[u]);
  }
  void scans(unsigned n) {
    for (unsigned i = 0; i < n; ++i) scan();
  }
  const Tally& tally() const noexcept { return t_; }
  // Unit `u` showed an error bit after the last scan.
  bool any_error(unsigned u) const noexcept { return bits_[u] != 0; }
  // Whether this scan's words clear latches on unit `u` (Reset Errors, Preset Position): a reason
  // recorded in the same scan may then belong to a bit the scan has set and cleared (a
  // configuration's Position Invalid, cleared by a preset written with the mode bit's release).
  void set_clearing(std::function<bool(unsigned)> f) { clearing_ = std::move(f); }

 private:
  static constexpr Nanos vm_options_scan_ns = kNsPerMs;  // VirtualMachineOptions' default
  static constexpr unsigned kCfg = 1u << 1;              // Configuration Error's list

  // Bit n: list n's error bit. In configuration mode the status word echoes the configuration
  // words but for Configuration Error: the other bits are as they were.
  static unsigned error_bits(const tools::ctl::AxisSummary& s, unsigned before) {
    unsigned b = 0;
    for (unsigned list = 1; list <= 6; ++list) b |= s.has_list(list) ? 1u << list : 0u;
    return s.configuration_mode ? (b & kCfg) | (before & ~kCfg) : b;
  }
  void check(unsigned u, const tools::ctl::AxisSummary& s) {
    const module::axis::ErrorReason r = vm_.stack().personality().reason(u);
    const unsigned bits = error_bits(s, bits_[u]);
    const bool recorded = r.seq != seq_[u];
    const std::string text(r.text.data());
    const std::string id = module::axis::item_id_of_code(r.code);
    const unsigned list = r.code / 100u % 100u;
    const unsigned number = r.code % 100u;
    // A bit set while configuration mode hides it (the scan that enters the mode included)
    // shows when the axis leaves the mode with an invalid configuration, which keeps the
    // latches: its reason was recorded then, when the bit was set (and may have been followed
    // by a configuration's reason in the same scan: one reason is kept per scan).
    const unsigned rose = bits & ~bits_[u] & (!s.configuration_mode && blind_[u] ? kCfg : ~0u);
    t_.rises += static_cast<unsigned>(__builtin_popcount(rose));
    if (recorded) {
      ++t_.reasons;
      t_.codes.insert(r.code);
    }
    if (rose != 0 && !recorded) {
      ++t_.rise_without_reason;
      describe(u, "an error bit rose without a new reason", bits, text);
    }
    // In configuration mode only Configuration Error is shown: another list's bit cannot be.
    const bool shown = !s.configuration_mode || list == 1;
    blind_[u] = s.configuration_mode && (blind_[u] || recorded);
    const bool clear = shown && (bits >> list & 1u) == 0 && !(clearing_ && clearing_(u));
    if (recorded && (clear || id.empty() || text.rfind(id + ": ", 0) != 0)) {
      ++t_.reason_of_clear_bit;
      describe(u, "a new reason whose bit is not set (or not its own id)", bits, text);
    }
    static const char* const kNames[] = {"",
                                         "Configuration Error",
                                         "Command Error",
                                         "Invalid Profile",
                                         "Input Error",
                                         "Home Invalid",
                                         "Position Invalid"};
    if (recorded && number == 0 && list <= 6 && text == id + ": " + kNames[list]) {
      ++t_.general_reason;
      describe(u, "a general reason (no item)", bits, text);
    } else if (recorded && number == 0 && list == 2) {
      ++t_.unnumbered_refusal;
      describe(u, "a refusal that names no item", bits, text);
    }
    bits_[u] = bits;
    seq_[u] = r.seq;
    text_[u] = text;
  }
  void describe(unsigned u, const char* what, unsigned bits, const std::string& text) {
    if (t_.first.size() >= 12) return;
    char line[256];
    std::snprintf(line, sizeof line,
                  "scan %u unit %u: %s: bits %#x (were %#x), reason \"%s\" (was \"%s\")", t_.scans,
                  u + 1, what, bits, bits_[u], text.c_str(), text_[u].c_str());
    t_.first.emplace_back(line);
  }

  VirtualMachine& vm_;
  unsigned units_;
  std::vector<unsigned> bits_;  // per unit: the error bits after the last scan (bit n = list n)
  std::vector<bool> blind_;     // reasons were recorded while configuration mode hid bits
  std::vector<std::uint32_t> seq_;
  std::vector<std::string> text_;
  std::function<bool(unsigned)> clearing_;
  Tally t_;
};

// A module's words, written the way a PLC might (and might not): one driver per module.
class Driver {
 public:
  virtual ~Driver() = default;
  // Configuration words of unit `u`, the mode bit set (valid or not).
  virtual void configure(ImageWords& out, unsigned u, Rng& r) = 0;
  // A command on unit `u`: its bits (one, several, undefined) and words (valid or not).
  virtual void command(ImageWords& out, unsigned u, Rng& r) = 0;
  // One data word of unit `u` changed, its command bits kept (a change while a move runs).
  virtual void tweak(ImageWords& out, unsigned u, Rng& r) = 0;
  // Command bits of unit `u` cleared, its other words kept (a PLC's release).
  virtual void release(ImageWords& out, unsigned u) = 0;
  // Every word of unit `u` 0 (command mode, nothing commanded).
  virtual void clear(ImageWords& out, unsigned u) = 0;
  virtual void reset_errors(ImageWords& out, unsigned u) = 0;
  // `out` commands Reset Errors or Preset Position on unit `u` (ReasonChecker::set_clearing).
  virtual bool clears_latches(const ImageWords& out, unsigned u) const = 0;
  // What only this module has (the 3602's interpolated move, the 3202's blend message).
  virtual void extra(VirtualMachine& /*vm*/, ReasonChecker& /*ck*/, Rng& /*r*/) {}
};

// Random steps until `scans` scans have been checked.
inline void run(VirtualMachine& vm, Driver& d, Rng& r, ReasonChecker& ck, unsigned scans) {
  const unsigned units = shape_of(vm.type()).axes;
  std::vector<std::uint32_t> mask(units, 0), levels(units, 0);
  ck.set_clearing([&vm, &d](unsigned u) { return d.clears_latches(vm.plc_out(), u); });
  const InputLine lines[] = {InputLine::kCwLimit,  InputLine::kCcwLimit, InputLine::kEStop,
                             InputLine::kExternal, InputLine::kHome,     InputLine::kCapture};
  while (ck.tally().scans < scans) {
    const unsigned u = r.below(units);
    ImageWords& out = vm.plc_out();
    const unsigned a = r.below(100);
    if (a < 10) {
      d.configure(out, u, r);
      ck.scans(2 + r.below(3));
      if (r.percent(75)) d.clear(out, u);  // else it stays until the next command's words
    } else if (a < 55) {
      d.command(out, u, r);
      ck.scans(1 + r.below(4));
      if (r.percent(80)) d.release(out, u);
      if (ck.any_error(u) && r.percent(50)) {
        // A PLC that resets the errors it caused (CE ignores every other command).
        ck.scans(1 + r.below(3));
        d.reset_errors(out, u);
        ck.scans(1 + r.below(3));
        d.release(out, u);
      }
    } else if (a < 62) {
      d.tweak(out, u, r);
    } else if (a < 72) {
      d.reset_errors(out, u);
      ck.scans(1 + r.below(3));
      d.release(out, u);
    } else if (a < 78) {
      const std::uint32_t bit = 1u << static_cast<unsigned>(lines[r.below(6)]);
      mask[u] |= bit;
      levels[u] = r.percent(70) ? levels[u] | bit : levels[u] & ~bit;
      vm.sim().force(u, mask[u], levels[u], vm.now());
    } else if (a < 84) {
      mask[u] = 0;  // the machine's own inputs again
      vm.sim().force(u, mask[u], levels[u], vm.now());
    } else {
      d.extra(vm, ck, r);
    }
    ck.scans(r.percent(10) ? 10 + r.below(100) : 1 + r.below(6));
  }
}

// The verdict and a summary line (the before/after numbers of a fix are read from it).
inline void expect_agreement(const char* module, std::uint32_t seed, const Tally& t) {
  std::printf(
      "[reasons fuzz %s seed %u] %u scans, %u error-bit rises, %u reasons, %zu items; "
      "mismatches: %u rise without reason, %u reason of a clear bit, %u general, "
      "%u refusal without item\n",
      module, seed, t.scans, t.rises, t.reasons, t.codes.size(), t.rise_without_reason,
      t.reason_of_clear_bit, t.general_reason, t.unnumbered_refusal);
  std::string detail;
  for (const std::string& s : t.first) detail += s + "\n";
  EXPECT_EQ(t.mismatches(), 0u) << "STEPMOD_FUZZ_SEED=" << seed << " reproduces it\n" << detail;
}

}  // namespace stepmod::testing::fuzz
