// stepmodd: one emulated stepper-controller module per process, or a rack of them
// (docs/interface.md sections 1 and 7).
//   stepmodd --config FILE [--trace FILE.vcd] [--log-level LEVEL]   FILE: a module or rack file
//   stepmodd --check --config FILE     validate the configuration (every file of a rack) and
//                                      this machine (creates and requests nothing)
//   stepmodd --version
// Exit status: 0 after SIGINT/SIGTERM/SIGHUP (or a valid --check), 2 for a bad command line or
// config file (or an [rt] cpu this machine has not), 1 when the module cannot be started (GPIO
// chip or lines missing or busy, shared memory, trace file; --check: the chip or lines), 3
// after such a signal when the trace lost records (the VCD says so too). SIGPIPE is ignored: a
// closed log pipe never ends the daemon.
#include <spdlog/sinks/stdout_color_sinks.h>  // declares stderr_color_mt too
#include <spdlog/spdlog.h>

#include <pthread.h>
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <exception>
#include <optional>
#include <thread>
#include <vector>

#include "config/config.hpp"
#include "config/rack_config.hpp"
#include "core/stop_signals.hpp"
#include "core/version.hpp"
#include "daemon/backend_factory.hpp"
#include "daemon/daemon.hpp"
#include "daemon/daemon_log.hpp"
#include "gpio/chip_probe.hpp"
#include "rt/cpus_online.hpp"

namespace {

// The daemon on a thread of its own until one of `signals` (or its failure); the exit status.
int run_until_signal(const stepmod::tools::RackConfig& config,
                     const std::optional<std::string>& trace_path, const sigset_t& signals) {
  try {
    stepmod::tools::Daemon daemon(config, trace_path);
    std::atomic<bool> stop{false};
    std::atomic<bool> finished{false};
    std::exception_ptr failure;
    bool trace_complete = true;
    std::thread runner([&] {
      try {
        trace_complete = daemon.run(stop);
      } catch (...) {
        failure = std::current_exception();
      }
      finished.store(true, std::memory_order_release);
    });
    // The runner only ends on its own after a failure; look at it every 100 ms.
    const timespec poll{0, 100'000'000};
    while (!finished.load(std::memory_order_acquire)) {
      const int sig = sigtimedwait(&signals, nullptr, &poll);
      if (sig > 0) {
        spdlog::info("signal {}: stopping", sig);
        stop.store(true, std::memory_order_release);
        break;
      }
    }
    runner.join();
    if (failure) std::rethrow_exception(failure);
    if (!trace_complete) {
      spdlog::error("stopped; the trace is incomplete (exit status 3)");
      return 3;
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  spdlog::info("stopped");
  return 0;
}

// The configuration against this machine, for --check and before a start: [rt] cpu online (else
// exit 2, a configuration error), and with the gpiod backend the chip there (by name, path or
// label) with every configured line on it and free, nothing requested (else exit 1). 0: fine.
int check_module_here(const stepmod::tools::Config& config) {
  if (const auto online = stepmod::rt::cpus_online()) {
    if (const std::string p = stepmod::rt::rt_cpu_problem(config.rt_cpu, *online); !p.empty()) {
      spdlog::error("{}: key 'rt.cpu': {}", config.file, p);
      return 2;
    }
  }
  if (config.backend != stepmod::tools::Config::Backend::kGpiod) return 0;
  try {
    const std::vector<stepmod::gpio::AxisLines> lines = stepmod::tools::module_lines(config);
    const stepmod::gpio::ChipInfo chip = stepmod::gpio::probe_chip(config.chip, lines);
    spdlog::info("GPIO chip '{}': {} [{}], {} lines; the configured lines are there and free",
                 config.chip, chip.path, chip.label, chip.lines);
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}

// Every module of the rack against this machine: the first problem's status.
int check_this_machine(const stepmod::tools::RackConfig& rack) {
  for (const stepmod::tools::Config& m : rack.modules) {
    if (const int rc = check_module_here(m); rc != 0) return rc;
  }
  return 0;
}

int run(int argc, char** argv) {
  CLI::App app{"stepmodd: software replacement for an AMCI 3601/3602/3202 stepper module"};
  std::string config_path;
  std::optional<std::string> trace_path;
  std::string log_level = "info";
  bool check_only = false;
  app.set_version_flag("--version", "stepmodd " STEPMOD_VERSION);
  app.add_option("--config", config_path,
                 "module configuration, or a rack file naming several (TOML, see README)")
      ->required();
  app.add_flag("--check", check_only,
               "validate the configuration and exit: 0 valid, 2 not; with the gpiod backend also "
               "the chip and lines (1: missing or busy; nothing is created or requested)");
  app.add_option("--trace", trace_path, "write every GPIO line change to this VCD file");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }

  // A closed stderr pipe (`stepmodd ... 2>&1 | head`) must not kill the daemon with the outputs
  // where they are: a failed write is just a lost log line.
  std::signal(SIGPIPE, SIG_IGN);
  stepmod::tools::make_daemon_logger();
  spdlog::set_level(spdlog::level::from_str(log_level));

  stepmod::tools::RackConfig config;
  try {
    config = stepmod::tools::load_rack(config_path);
  } catch (const stepmod::tools::ConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }
  if (const int rc = check_this_machine(config); rc != 0) return rc;
  if (check_only) {
    for (const stepmod::tools::Config& m : config.modules) {
      spdlog::info("{}: valid (module {} '{}', {} axis/axes)", m.file,
                   static_cast<unsigned>(m.type), m.name, m.axes.size());
    }
    if (config.rack_file) {
      spdlog::info("{}: valid rack of {} modules", config_path, config.modules.size());
    }
    return 0;
  }

  const sigset_t signals = stepmod::block_stop_signals();
  return run_until_signal(config, trace_path, signals);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (...) {
    // Logging itself failed (or worse): nothing more can be reported.
    return 1;
  }
}
