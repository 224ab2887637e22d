#include "tools/ctl_board.hpp"

#include <iostream>

namespace stepmod::tools::ctl {

void add_board_commands(CLI::App& app, BoardCommands& b) {
  b.doctor_cmd = app.add_subcommand(
      "doctor",
      "what this board can do for the pulse thread: kernel, CPUs, throttling, GPIO chips and "
      "lines, then the pulse thread's wake-up measured for --seconds beside whatever load runs, "
      "and the safe step rate per axis under the configured guard. Exit 0 fit, 1 not fit for "
      "--speed (or a pause beyond late_limit_us), 2 usage or config error");
  b.doctor_cmd->add_option("--config", b.doctor.config, "the module's config (default: defaults)");
  b.doctor_cmd->add_option("--seconds", b.doctor.seconds, "how long to measure (5)");
  b.doctor_cmd->add_option("--interval-us", b.doctor.interval_us, "wake-up period (200)");
  b.doctor_cmd->add_option("--speed", b.doctor.speed,
                           "the step rate (steps/s) every axis must hold; the config has none");
  b.doctor_cmd->add_option("--root", b.doctor.root, "read proc, sys, dev, etc under DIR (tests)");

  b.isolate_cmd = app.add_subcommand(
      "isolate",
      "give the pulse thread CPU N of its own (systemd drop-ins, sysctl, [rt] cpu in --config), "
      "or --off to remove exactly that; docs/performance.md \"A CPU of its own\"");
  auto* cpu = b.isolate_cmd->add_option("--cpu", b.isolate.cpu, "the CPU to give the pulse thread")
                  ->check(CLI::Range(0, 4095));
  b.isolate_cmd->add_flag("--off", b.isolate.off, "remove what --cpu wrote")->excludes(cpu);
  b.isolate_cmd->add_option("--config", b.isolate.config, "the module's config: sets [rt] cpu");
  b.isolate_cmd->add_option("--root", b.isolate.root, "write under DIR instead of / (tests)");
}

std::optional<int> run_board_command(const BoardCommands& b) {
  if (b.doctor_cmd != nullptr && b.doctor_cmd->parsed()) {
    return doctor::run_doctor(b.doctor, std::cout, std::cerr);
  }
  if (b.isolate_cmd != nullptr && b.isolate_cmd->parsed()) {
    return doctor::run_isolate(b.isolate, std::cout, std::cerr);
  }
  return std::nullopt;
}

}  // namespace stepmod::tools::ctl
