// stepmodd: one emulated stepper-controller module per process (INTERFACE.md section 1).
//   stepmodd --config FILE [--trace FILE.vcd] [--log-level LEVEL]
// Exit status: 0 after SIGINT/SIGTERM, 2 for a bad command line or config file, 1 when the
// module cannot be started (GPIO lines, shared memory, trace file), 3 after SIGINT/SIGTERM when
// the trace lost records (the VCD says so too).
#include <spdlog/sinks/stdout_color_sinks.h>  // declares stderr_color_mt too
#include <spdlog/spdlog.h>

#include <pthread.h>
#include <CLI/CLI.hpp>
#include <atomic>
#include <csignal>
#include <exception>
#include <optional>
#include <thread>

#include "tools/config.hpp"
#include "tools/daemon.hpp"

namespace {

int run(int argc, char** argv) {
  CLI::App app{"stepmodd: software replacement for an AMCI 3601/3602/3202 stepper module"};
  std::string config_path;
  std::optional<std::string> trace_path;
  std::string log_level = "info";
  app.add_option("--config", config_path, "module configuration (TOML, see README)")->required();
  app.add_option("--trace", trace_path, "write every GPIO line change to this VCD file");
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error, critical or off")
      ->check(CLI::IsMember({"trace", "debug", "info", "warn", "error", "critical", "off"}));
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }

  auto logger = spdlog::stderr_color_mt("stepmodd");
  spdlog::set_default_logger(logger);
  spdlog::set_level(spdlog::level::from_str(log_level));

  stepmod::tools::Config config;
  try {
    config = stepmod::tools::load_config(config_path);
  } catch (const stepmod::tools::ConfigError& e) {
    spdlog::error("{}", e.what());
    return 2;
  }

  // SIGINT/SIGTERM are blocked in every thread (the threads created below inherit the mask) and
  // taken here with sigtimedwait, so no handler ever runs on the pulse thread.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

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

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (...) {
    // Logging itself failed (or worse): nothing more can be reported.
    return 1;
  }
}
