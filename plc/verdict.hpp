#pragma once
// Whether THIS command was refused (issue 20): the error bits after a command may be stale,
// left by an earlier one. With the image's error reasons (docs/interface.md 3.4) a command is
// refused when a new reason of one of the lists it checks was recorded while it ran; a bit that was
// already set only gets a note. Without reasons (the virtual test machine) the bits decide.
#include <string>
#include <vector>

#include "plc/move_profile.hpp"
#include "plc/port.hpp"

namespace stepmod::plc {

// The error lists (docs/error-reasons.md), as bits of a list mask.
enum ListBit : unsigned {
  kListCfg = 1u << 1,
  kListCe = 1u << 2,
  kListIp = 1u << 3,
  kListIe = 1u << 4,
  kListHi = 1u << 5,
  kListPi = 1u << 6,
};

// What an error bit left by an earlier command means for this one.
enum class Stale : std::uint8_t {
  kRefused,  // the module ignored the command (3601-CE-L1: only Reset Errors is looked at)
  kNote,     // Hold, Resume, Immediate Stop: say so, but the command itself was not refused
};

class Verdict {
 public:
  Verdict(const Port& port, unsigned units);
  // `errors`: the command's error bits now set, `names` their names, `lists` the lists they
  // belong to. Updates `o` (ok, message, note) and takes the reasons as the next baseline.
  void judge(Outcome& o, unsigned unit, std::uint32_t errors, const std::string& names,
             unsigned lists, const std::string& what, Stale stale = Stale::kRefused);
  // Takes the reasons now as the baseline (before a command that does not end in judge()).
  void rebase();

 private:
  const Port& port_;
  std::vector<std::uint32_t> seen_;  // per unit: the reason sequence at the baseline
};

}  // namespace stepmod::plc

namespace stepmod::plc {

// While it lives, a stale error bit is a note (Hold, Resume, Immediate Stop), not a refusal.
class StaleIsNote {
 public:
  explicit StaleIsNote(Stale& s) noexcept : s_(s) { s_ = Stale::kNote; }
  ~StaleIsNote() { s_ = Stale::kRefused; }
  StaleIsNote(const StaleIsNote&) = delete;
  StaleIsNote& operator=(const StaleIsNote&) = delete;

 private:
  Stale& s_;
};

// The list mask of a status word's error bits (each dialect names its own bits).
template <typename Bits>
unsigned lists_of(std::uint32_t mask, const Bits& b) noexcept {
  unsigned l = 0;
  if (mask & b.cfg) l |= kListCfg;
  if (mask & b.ce) l |= kListCe;
  if (mask & b.ip) l |= kListIp;
  if (mask & b.ie) l |= kListIe;
  if (mask & b.hi) l |= kListHi;
  if (mask & b.pi) l |= kListPi;
  return l;
}
struct ErrorBitSet {
  std::uint32_t cfg, ce, ip, ie, hi, pi;
};

}  // namespace stepmod::plc
