#pragma once
// `stepmodctl doctor`: what this board can do, measured (docs/board.md, "Set up a board for fast
// axes"). Reads the board (doctor/board_facts.hpp), the GPIO chips and the configured lines, runs
// the pulse thread's wake-up loop at the configured [rt] priority and CPU beside whatever load
// the user runs, and prints the safe step rate per axis and what to change to raise it.
#include <ostream>
#include <string>

namespace stepmod::doctor {

struct DoctorOptions {
  std::string config;       // a module's config file; "" = the key table's defaults, one axis
  double seconds = 5;       // how long the wake-up loop runs
  double interval_us = 200;  // its wake-up period
  double speed = 0;         // the step rate every axis must hold (0: judged by late_limit_us)
  std::string root;         // a fake / for proc, sys, dev and etc (tests); "" the machine
};

enum DoctorExit : int { kFit = 0, kNotFit = 1, kUsage = 2 };

// The exit status: kFit, kNotFit, kUsage (a bad config or option, said on `err`).
int run_doctor(const DoctorOptions& options, std::ostream& out, std::ostream& err);

}  // namespace stepmod::doctor
