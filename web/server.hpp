#pragma once
// The console's HTTP and WebSocket server (civetweb): the login page and form, the page's files
// (index.html, console.js, plot.js, style.css from `www_dir`), /api/hello, and /ws, the
// WebSocket that carries sample batches to the page and the page's requests to the Commander.
// Everything but the login needs a session: HTTP answers 401, a WebSocket is refused. Every
// request must name the console in its Host header, and the WebSocket and the login form must
// come from the console's own page (Origin); the limits that keep it served under idle, slow or
// hostile connections are in docs/web-console.md ("Limits").
#include <cstdint>
#include <string>
#include <vector>

#include "web/auth.hpp"
#include "web/commander.hpp"
#include "web/http_guard.hpp"
#include "web/login_limiter.hpp"
#include "web/origin.hpp"
#include "web/ws_hub.hpp"

struct mg_context;
struct mg_connection;

namespace stepmod::web {

struct ServerOptions {
  std::string listen = "127.0.0.1";
  unsigned port = 8610;
  std::string www_dir;
  std::string module_name;
  std::vector<std::string> allow_hosts;  // --allow-host: more names the console is served under
  std::string reasons_page;              // /reasons: the module's error items (reason_help.hpp)
};

// civetweb's worker threads: WebSockets keep one each (at most WsLimits::max_sessions), waiting
// connections at most kMaxWaiting (the guard), and the rest serve requests.
inline constexpr int kServerThreads = 64;
inline constexpr std::size_t kMaxWaiting = 32;
inline constexpr int kRequestTimeoutMs = 5000;  // a request's headers (and body) must be in by

class Server {
 public:
  // Starts listening; throws std::runtime_error when the address cannot be bound.
  Server(const ServerOptions& opt, Auth& auth, Commander& commander, const std::string& hello);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Queues a batch for every open WebSocket (called by the sampler thread; never blocks on a
  // client).
  void publish(const std::string& json) { hub_.broadcast(json); }

  // civetweb callbacks (public for the C trampolines only).
  void on_open(const mg_connection* conn);
  void on_closed(const mg_connection* conn) { guard_.closed(conn); }
  int on_http(mg_connection* conn);
  int on_http_error(mg_connection* conn, int status, const char* msg);
  int on_ws_connect(const mg_connection* conn);
  void on_ws_ready(mg_connection* conn);
  void on_ws_close(const mg_connection* conn);

 private:
  int login(mg_connection* conn);
  int check_login(mg_connection* conn, const std::string& client);
  int serve_file(mg_connection* conn, const std::string& uri);
  int logout(mg_connection* conn);

  ServerOptions opt_;
  Auth& auth_;
  Commander& commander_;
  std::string hello_;
  HostPolicy hosts_;
  HttpGuard guard_;
  LoginLimiter limiter_;
  LogThrottle refusals_;
  WsHub hub_;
  mg_context* ctx_ = nullptr;
};

}  // namespace stepmod::web
