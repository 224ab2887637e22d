#pragma once
// What to change to raise the safe step rate, from what the probes found (docs/performance.md,
// "A CPU of its own"; docs/board.md, "Set up a board for fast axes"), most effective first.
#include <string>
#include <vector>

#include "doctor/board_facts.hpp"
#include "rt/output_thread.hpp"

namespace stepmod::doctor {

struct AdviceInput {
  const BoardFacts& facts;
  int priority = 80;           // [rt] priority
  rt::OutputThreadStatus wake;  // the wake-up probe's setup
  bool late_limit_exceeded = false;
};

std::vector<std::string> advise(const AdviceInput& in);

}  // namespace stepmod::doctor
