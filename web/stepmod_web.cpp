// stepmod-web: the commissioning console of one module in the browser (docs/web-console.md).
// One more client of the module's shared-memory image, like an HMI: a sampler thread reads it
// under its seqlock, commands go through the plc/ library under the commissioning lease.
#include <signal.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <memory>

#include "config/config.hpp"
#include "core/stop_signals.hpp"
#include "ipc/shm_object.hpp"
#include "web/auth.hpp"
#include "web/commander.hpp"
#include "web/image_json.hpp"
#include "web/options.hpp"
#include "web/reason_help.hpp"
#include "web/sampler.hpp"
#include "web/server.hpp"

#ifndef STEPMOD_WEB_WWW
#define STEPMOD_WEB_WWW "/usr/share/stepmod/web"
#endif

namespace {

int wait_for_signal() {
  const sigset_t set = stepmod::stop_signals();
  int sig = 0;
  sigwait(&set, &sig);
  return sig;
}

struct Args {
  std::string name{stepmod::tools::config_key("module", "name").text};  // the daemon's default
  std::string config_path;
  std::string token_file = stepmod::web::kDefaultTokenFile;
  unsigned port = 0;
  int quiet_ms = 1000;
  bool quiet_given = false;
  stepmod::web::ServerOptions opt;
};

void add_options(CLI::App& app, Args& a) {
  a.opt.www_dir = STEPMOD_WEB_WWW;
  auto* name_opt =
      app.add_option("--name,-n", a.name, "module name (the image /dev/shm/stepmod.NAME)")
          ->capture_default_str();
  app.add_option("--config", a.config_path,
                 "take the module name from this stepmodd configuration ([module] name)")
      ->excludes(name_opt);
  app.add_option("--listen", a.opt.listen,
                 "address to listen on (default 127.0.0.1; another address exposes the "
                 "console to that network: do it only on purpose)")
      ->capture_default_str();
  app.add_option("--allow-host", a.opt.allow_hosts,
                 "another name the console is served under (NAME or NAME:PORT; repeatable): "
                 "requests naming any other host are refused (default: 127.0.0.1, localhost, "
                 "[::1] and the --listen address, or every interface address for 0.0.0.0)");
  app.add_option("--port", a.port, "TCP port (default 8610 + the name's trailing number)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--token-file", a.token_file, "access token file")->capture_default_str();
  app.add_option("--www", a.opt.www_dir, "directory of the page's files")->capture_default_str();
  app.add_option("--plc-quiet-ms", a.quiet_ms,
                 "the lease is refused while the PLC heartbeat changed within this time "
                 "(default: the configuration's plc_timeout_ms, else 1000)")
      ->check(CLI::Range(100, 60000))
      ->capture_default_str();
}

// The settings the options leave open: the module name and heartbeat timeout from the
// configuration, the port from the name. Throws on a bad configuration or name.
void settle(Args& a, const CLI::App& app) {
  if (!a.config_path.empty()) {
    const auto cfg = stepmod::tools::load_config(a.config_path);
    a.name = cfg.name;
    // The contract: no PLC is in control once its heartbeat has not changed for
    // plc_timeout_ms (1 s when that is 0).
    if (cfg.plc_timeout_ns > 0 && app.count("--plc-quiet-ms") == 0) {
      a.quiet_ms = static_cast<int>(cfg.plc_timeout_ns / 1'000'000);
    }
  }
  a.opt.module_name = a.name;
  a.opt.port = a.port != 0 ? a.port : stepmod::web::default_port(a.name);
}

// Serves until SIGTERM/SIGINT/SIGHUP.
void serve(const Args& a, stepmod::web::Auth& auth) {
  using namespace stepmod::web;
  stepmod::ipc::Client probe(a.name);
  const std::string hello = hello_json(a.name, probe.type()).dump();
  ServerOptions opt = a.opt;
  opt.reasons_page = reasons_page(probe.type());
  std::unique_ptr<Server> server;
  std::mutex server_m;
  Sampler sampler(a.name, [&](const std::string& json) {
    std::lock_guard lock(server_m);
    if (server) server->publish(json);
  });
  Commander commander(a.name, sampler, {std::chrono::milliseconds(a.quiet_ms)});
  {
    std::lock_guard lock(server_m);
    server = std::make_unique<Server>(opt, auth, commander, hello);
  }
  std::fprintf(stderr, "stepmod-web: module %s, http://%s:%u/ (token: %s)\n", a.name.c_str(),
               a.opt.listen.c_str(), a.opt.port, a.token_file.c_str());
  const int sig = wait_for_signal();
  std::fprintf(stderr, "stepmod-web: signal %d, stopping\n", sig);
  std::lock_guard lock(server_m);
  server.reset();
}

int run(int argc, char** argv) {
  CLI::App app{
      "stepmod-web: the commissioning console of one stepmod module in the browser.\n"
      "Listens on 127.0.0.1, port 8610 + the number the module name ends with (stepmod: 8610,\n"
      "press2: 8612), unless --listen/--port say otherwise. The login page asks for the access\n"
      "token in /etc/stepmod/web-token (made at package install, readable by root and the\n"
      "stepmod group; --token-file). See docs/web-console.md.\n"
      "Exit status: 0 stopped by a signal, 1 the module's image or the address unavailable,\n"
      "2 bad options, configuration or token file."};
  Args a;
  add_options(app, a);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  std::unique_ptr<stepmod::web::Auth> auth;
  try {
    settle(a, app);
    auth = std::make_unique<stepmod::web::Auth>(a.token_file);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stepmod-web: %s\n", e.what());
    return 2;
  }
  serve(a, *auth);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Every thread started below inherits the blocked set: the main thread alone takes them.
  stepmod::block_stop_signals();
  signal(SIGPIPE, SIG_IGN);
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stepmod-web: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "stepmod-web: unknown error\n");
  }
  return 1;
}
