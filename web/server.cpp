#include "web/server.hpp"

#include <civetweb.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stepmod::web {
namespace {

constexpr std::size_t kQueueMax = 40;  // 2 s of batches for a slow page, then the oldest go

Server* self(void* cb) {
  return static_cast<Server*>(cb);
}
int http_cb(mg_connection* c, void* cb) {
  return self(cb)->on_http(c);
}
int ws_connect_cb(const mg_connection* c, void* cb) {
  return self(cb)->on_ws_connect(c);
}
void ws_ready_cb(mg_connection* c, void* cb) {
  self(cb)->on_ws_ready(c);
}
int ws_data_cb(mg_connection* c, int flags, char* data, size_t len, void* cb) {
  return self(cb)->on_ws_data(c, flags, data, len);
}
void ws_close_cb(const mg_connection* c, void* cb) {
  self(cb)->on_ws_close(c);
}

const char* mime_of(const std::string& path) {
  if (path.ends_with(".html")) return "text/html; charset=utf-8";
  if (path.ends_with(".js")) return "text/javascript; charset=utf-8";
  if (path.ends_with(".css")) return "text/css; charset=utf-8";
  if (path.ends_with(".png")) return "image/png";
  return "application/octet-stream";
}

std::string read_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return "";
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

void respond(mg_connection* c, int status, const char* mime, const std::string& body,
             const std::string& extra_headers = "") {
  mg_printf(c,
            "HTTP/1.1 %d %s\r\nContent-Type: %s\r\nContent-Length: %zu\r\n"
            "Cache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\n"
            "Content-Security-Policy: default-src 'self'; connect-src 'self' ws: wss:\r\n"
            "%sConnection: close\r\n\r\n",
            status, mg_get_response_code_text(c, status), mime, body.size(), extra_headers.c_str());
  mg_write(c, body.data(), body.size());
}

}  // namespace

Server::Server(const ServerOptions& opt, Auth& auth, Commander& commander, const std::string& hello)
    : opt_(opt), auth_(auth), commander_(commander), hello_(hello) {
  const std::string ports = opt.listen + ":" + std::to_string(opt.port);
  const char* options[] = {"listening_ports",   ports.c_str(), "num_threads", "8",
                           "enable_keep_alive", "no",          nullptr};
  mg_callbacks callbacks{};
  ctx_ = mg_start(&callbacks, this, options);
  if (ctx_ == nullptr) throw std::runtime_error("cannot listen on " + ports);
  mg_set_request_handler(ctx_, "/", http_cb, this);
  mg_set_websocket_handler(ctx_, "/ws", ws_connect_cb, ws_ready_cb, ws_data_cb, ws_close_cb, this);
  pusher_ = std::thread([this] { push_loop(); });
}

Server::~Server() {
  {
    std::lock_guard lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  pusher_.join();
  mg_stop(ctx_);
}

void Server::publish(const std::string& json) {
  {
    std::lock_guard lock(m_);
    if (sockets_.empty()) return;
    if (queue_.size() >= kQueueMax) queue_.pop_front();
    queue_.push_back(json);
  }
  cv_.notify_all();
}

void Server::push_loop() {
  std::unique_lock lock(m_);
  for (;;) {
    cv_.wait(lock, [this] { return stop_ || !queue_.empty(); });
    if (stop_) return;
    const std::string msg = std::move(queue_.front());
    queue_.pop_front();
    for (mg_connection* c : sockets_) send(c, msg);
  }
}

void Server::send(mg_connection* c, const std::string& text) {
  mg_lock_connection(c);
  mg_websocket_write(c, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size());
  mg_unlock_connection(c);
}

int Server::login(mg_connection* c) {
  const mg_request_info* ri = mg_get_request_info(c);
  const std::string page = read_file(opt_.www_dir + "/login.html");
  if (std::string(ri->request_method) != "POST") {
    respond(c, 200, "text/html; charset=utf-8", page);
    return 200;
  }
  char body[512] = {};
  const int n = mg_read(c, body, sizeof body - 1);
  char token[256] = {};
  if (n <= 0 || mg_get_var(body, static_cast<size_t>(n), "token", token, sizeof token) < 0) {
    respond(c, 400, "text/plain", "the login form needs a token\n");
    return 400;
  }
  const std::string id = auth_.login(token);
  if (id.empty()) {
    respond(c, 401, "text/html; charset=utf-8", page);
    return 401;
  }
  respond(c, 303, "text/plain", "logged in\n",
          std::string("Set-Cookie: ") + Auth::kCookie + "=" + id +
              "; HttpOnly; SameSite=Strict; Path=/\r\nLocation: /\r\n");
  return 303;
}

int Server::serve_file(mg_connection* c, const std::string& uri) {
  static const std::set<std::string> kFiles = {"/index.html", "/console.js", "/plot.js",
                                               "/style.css", "/picture.html", "/picture.js"};
  const std::string path = uri == "/" ? "/index.html" : uri;
  if (kFiles.count(path) == 0) {
    respond(c, 404, "text/plain", "not found\n");
    return 404;
  }
  respond(c, 200, mime_of(path), read_file(opt_.www_dir + path));
  return 200;
}

int Server::on_http(mg_connection* c) {
  const mg_request_info* ri = mg_get_request_info(c);
  const std::string uri = ri->local_uri != nullptr ? ri->local_uri : "/";
  if (uri == "/login") return login(c);
  if (uri == "/style.css") return serve_file(c, uri);  // the login page's look: no secret
  if (!auth_.valid(mg_get_header(c, "Cookie"))) {
    // The page itself answers 401 with the login form, so a browser shows it.
    if (uri == "/" || uri == "/index.html") {
      respond(c, 401, "text/html; charset=utf-8", read_file(opt_.www_dir + "/login.html"));
    } else {
      respond(c, 401, "text/plain", "401: log in first (/login)\n");
    }
    return 401;
  }
  if (uri == "/api/hello") {
    respond(c, 200, "application/json", hello_);
    return 200;
  }
  return serve_file(c, uri);
}

int Server::on_ws_connect(const mg_connection* c) {
  return auth_.valid(mg_get_header(c, "Cookie")) ? 0 : 1;  // nonzero: civetweb closes it
}

void Server::on_ws_ready(mg_connection* c) {
  send(c, hello_);
  std::lock_guard lock(m_);
  sockets_.insert(c);
}

int Server::on_ws_data(mg_connection* c, int flags, char* data, std::size_t len) {
  const int opcode = flags & 0xF;
  if (opcode == MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE) return 0;
  if (opcode != MG_WEBSOCKET_OPCODE_TEXT) return 1;
  nlohmann::json reply;
  try {
    reply = commander_.handle(nlohmann::json::parse(std::string(data, len)),
                              reinterpret_cast<std::uintptr_t>(c));
  } catch (const nlohmann::json::exception& e) {
    reply = {
        {"type", "reply"}, {"ok", false}, {"message", std::string("bad request: ") + e.what()}};
  }
  if (!reply.is_null()) send(c, reply.dump());
  return 1;
}

void Server::on_ws_close(const mg_connection* c) {
  commander_.disconnected(reinterpret_cast<std::uintptr_t>(c));
  std::lock_guard lock(m_);
  sockets_.erase(const_cast<mg_connection*>(c));
}

}  // namespace stepmod::web
