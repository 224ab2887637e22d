#include "plc/verdict.hpp"

namespace stepmod::plc {

Verdict::Verdict(const Port& port, unsigned units) : port_(port), seen_(units, 0) {
  rebase();
}

void Verdict::rebase() {
  for (unsigned u = 0; u < seen_.size(); ++u) {
    if (const auto r = port_.reason(u)) seen_[u] = r->seq;
  }
}

void Verdict::judge(Outcome& o, unsigned unit, std::uint32_t errors, const std::string& names,
                    unsigned lists, const std::string& what, Stale stale) {
  const auto r = port_.reason(unit);
  const bool new_reason = r && unit < seen_.size() && r->seq != seen_[unit];
  if (r && unit < seen_.size()) seen_[unit] = r->seq;
  if (errors == 0) return;
  if (!r) {
    o.ok = false;
    o.message = what + ": " + names;
    return;
  }
  if (new_reason && (lists & (1u << r->list())) != 0) {
    o.ok = false;
    o.message = what + ": " + names + ": " + r->text;
    return;
  }
  const bool ce = names.find("Command Error") != std::string::npos;
  const std::string before =
      what + ": " + names + " was already set before this command" +
      (r->text.empty() ? "" : " (" + r->text + ")") +
      (ce ? "; while it is set the module ignores every command but Reset Errors "
            "('stepmodctl reset')"
          : "");
  if (stale == Stale::kNote) {
    o.note = before;
  } else {
    o.ok = false;
    o.message = before;
  }
}

}  // namespace stepmod::plc
