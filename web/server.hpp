#pragma once
// The console's HTTP and WebSocket server (civetweb): the login page and form, the page's files
// (index.html, console.js, plot.js, style.css from `www_dir`), /api/status, and /ws, the
// WebSocket that carries sample batches to the page and the page's requests to the Commander.
// Everything but the login needs a session: HTTP answers 401, a WebSocket is refused.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "web/auth.hpp"
#include "web/commander.hpp"

struct mg_context;
struct mg_connection;

namespace stepmod::web {

struct ServerOptions {
  std::string listen = "127.0.0.1";
  unsigned port = 8610;
  std::string www_dir;
  std::string module_name;
};

class Server {
 public:
  // Starts listening; throws std::runtime_error when the address cannot be bound.
  Server(const ServerOptions& opt, Auth& auth, Commander& commander, const std::string& hello);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  // Queues a batch for every open WebSocket (called by the sampler thread; never blocks on a
  // client: a pusher thread sends).
  void publish(const std::string& json);

  // civetweb callbacks (public for the C trampolines only).
  int on_http(mg_connection* conn);
  int on_ws_connect(const mg_connection* conn);
  void on_ws_ready(mg_connection* conn);
  int on_ws_data(mg_connection* conn, int flags, char* data, std::size_t len);
  void on_ws_close(const mg_connection* conn);

 private:
  int login(mg_connection* conn);
  int serve_file(mg_connection* conn, const std::string& uri);
  void send(mg_connection* conn, const std::string& text);
  void push_loop();

  ServerOptions opt_;
  Auth& auth_;
  Commander& commander_;
  std::string hello_;
  mg_context* ctx_ = nullptr;

  std::mutex m_;
  std::condition_variable cv_;
  std::set<mg_connection*> sockets_;
  std::deque<std::string> queue_;
  bool stop_ = false;
  std::thread pusher_;
};

}  // namespace stepmod::web
