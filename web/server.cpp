#include "web/server.hpp"

#include <civetweb.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "web/conn_socket.hpp"
#include "web/requests.hpp"

namespace stepmod::web {
namespace {

Server* self(const mg_connection* c) {
  return static_cast<Server*>(mg_get_user_data(mg_get_context(c)));
}
int init_connection_cb(const mg_connection* c, void** conn_data) {
  *conn_data = nullptr;
  self(c)->on_open(c);
  return 0;
}
void connection_close_cb(const mg_connection* c) {
  self(c)->on_closed(c);
}
int http_error_cb(mg_connection* c, int status, const char* msg) {
  return self(c)->on_http_error(c, status, msg);
}
int http_cb(mg_connection* c, void*) {
  return self(c)->on_http(c);
}
int ws_connect_cb(const mg_connection* c, void*) {
  return self(c)->on_ws_connect(c);
}
void ws_ready_cb(mg_connection* c, void*) {
  self(c)->on_ws_ready(c);
}
// civetweb's own frame reader is never used (it buffers a frame of any size): the console reads
// the frames in on_ws_ready. It runs only after that returns, or where the socket was not found:
// it closes the connection.
int ws_data_cb(mg_connection*, int, char*, size_t, void*) {
  return 0;
}
void ws_close_cb(const mg_connection* c, void*) {
  self(c)->on_ws_close(c);
}
// The handlers are set here, before civetweb starts the thread that accepts connections: set
// after mg_start returned, a request that came in between met civetweb's own 404 (a login the
// moment the port opened was refused so). civetweb hands the context out const; it is ours, and
// no other thread uses it yet.
void init_context_cb(const mg_context* ctx) {
  auto* own = const_cast<mg_context*>(ctx);
  void* server = mg_get_user_data(ctx);
  mg_set_request_handler(own, "/", http_cb, server);
  mg_set_websocket_handler(own, "/ws", ws_connect_cb, ws_ready_cb, ws_data_cb, ws_close_cb, server);
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

// On every answer: no page of another site may frame the console (clickjacking: a click on
// "Take control" or a jog button under a decoy), nor read it, nor be given its address.
constexpr const char* kSecurityHeaders =
    "Cache-Control: no-store\r\n"
    "X-Content-Type-Options: nosniff\r\n"
    "X-Frame-Options: DENY\r\n"
    "Content-Security-Policy: default-src 'self'; connect-src 'self'; frame-ancestors 'none'; "
    "form-action 'self'; base-uri 'none'; object-src 'none'\r\n"
    "Referrer-Policy: same-origin\r\n"  // (no-referrer would make the form's Origin "null")
    "Cross-Origin-Opener-Policy: same-origin\r\n"
    "Cross-Origin-Resource-Policy: same-origin\r\n";

int respond(mg_connection* c, int status, const char* mime, const std::string& body,
            const std::string& extra_headers = "") {
  mg_printf(
      c,
      "HTTP/1.1 %d %s\r\nContent-Type: %s\r\nContent-Length: %zu\r\n%s%sConnection: close\r\n\r\n",
      status, mg_get_response_code_text(c, status), mime, body.size(), kSecurityHeaders,
      extra_headers.c_str());
  mg_write(c, body.data(), body.size());
  return status;
}

// The socket of a connection whose request is being read. (During civetweb's init_connection
// callback its request information is not given out yet; its address and ports, filled in
// before, are given out from the moment the worker starts reading the request.)
int socket_of_connection(const void* conn) {
  const mg_request_info* ri = mg_get_request_info(static_cast<const mg_connection*>(conn));
  if (ri == nullptr) return -1;
  return socket_of(ri->remote_addr, static_cast<unsigned>(ri->remote_port),
                   static_cast<unsigned>(ri->server_port));
}

std::string peer_of(const mg_request_info* ri) {
  return std::string(ri->remote_addr) + ":" + std::to_string(ri->remote_port);
}

// A header as a log shows it: printable ASCII, at most 100 characters.
std::string printable(const char* s) {
  std::string out = s != nullptr ? s : "none";
  if (out.size() > 100) out.resize(100);
  for (char& ch : out) ch = ch >= 0x20 && ch < 0x7F ? ch : '?';
  return out;
}

}  // namespace

Server::Server(const ServerOptions& opt, Auth& auth, Commander& commander, const std::string& hello)
    : opt_(opt),
      auth_(auth),
      commander_(commander),
      hello_(hello),
      hosts_(opt.listen, opt.port, opt.allow_hosts),
      guard_(kMaxWaiting, [](const void* conn) { return socket_of_connection(conn); }),
      hub_(WsLimits{}, [this](std::uintptr_t id, std::string_view msg, bool text) {
        return answer(commander_, id, msg, text);
      }) {
  const std::string ports = opt.listen + ":" + std::to_string(opt.port);
  const std::string threads = std::to_string(kServerThreads);
  const std::string timeout = std::to_string(kRequestTimeoutMs);
  // clang-format off
  const char* options[] = {"listening_ports", ports.c_str(),
                           "num_threads", threads.c_str(),
                           "request_timeout_ms", timeout.c_str(),
                           "enable_keep_alive", "no",
                           nullptr};
  // clang-format on
  mg_callbacks callbacks{};
  callbacks.init_connection = init_connection_cb;
  callbacks.connection_close = connection_close_cb;
  callbacks.http_error = http_error_cb;
  callbacks.init_context = init_context_cb;
  ctx_ = mg_start(&callbacks, this, options);
  if (ctx_ == nullptr) throw std::runtime_error("cannot listen on " + ports);
}

Server::~Server() {
  hub_.stop();  // every WebSocket's thread returns to civetweb, which then stops
  mg_stop(ctx_);
}

void Server::on_open(const mg_connection* c) {
  guard_.opened(c);
}

int Server::on_http_error(mg_connection* c, int status, const char* msg) {
  guard_.request_read(c);
  respond(c, status, "text/plain; charset=utf-8", std::to_string(status) + ": " + msg + "\n");
  return 0;  // answered here, with the security headers
}

int Server::check_login(mg_connection* c, const std::string& client) {
  if (!hosts_.origin_ok(mg_get_header(c, "Origin"), mg_get_header(c, "Host"))) {
    guard_.request_read(c);
    return respond(c, 403, "text/plain; charset=utf-8",
                   "403: the login form must come from this console's own page (Origin, Host)\n");
  }
  const std::int64_t wait = limiter_.wait_ms(client);
  if (wait > 0) {
    guard_.request_read(c);
    return respond(c, 429, "text/plain; charset=utf-8",
                   "429: too many wrong tokens from this address: try again later\n",
                   "Retry-After: " + std::to_string((wait + 999) / 1000) + "\r\n");
  }
  return 0;
}

int Server::login(mg_connection* c) {
  const mg_request_info* ri = mg_get_request_info(c);
  const std::string client = ri->remote_addr;
  const std::string page = read_file(opt_.www_dir + "/login.html");
  if (const int refused = check_login(c, client); refused != 0) return refused;
  char body[512] = {};
  const int n = mg_read(c, body, sizeof body - 1);
  guard_.request_read(c);
  char token[256] = {};
  if (n <= 0 || mg_get_var(body, static_cast<size_t>(n), "token", token, sizeof token) < 0) {
    return respond(c, 400, "text/plain", "the login form needs a token\n");
  }
  const std::string id = auth_.login(token);
  if (id.empty()) {
    limiter_.failed(client);
    return respond(c, 401, "text/html; charset=utf-8", page);
  }
  limiter_.succeeded(client);
  std::fprintf(stderr, "stepmod-web: login from %s: a session opened\n", client.c_str());
  return respond(c, 303, "text/plain", "logged in\n",
                 std::string("Set-Cookie: ") + Auth::kCookie + "=" + id +
                     "; HttpOnly; SameSite=Strict; Path=/\r\nLocation: /\r\n");
}

// The page's Log out: a form posted from the console's own page ends its session. (The page's
// WebSocket closes as the browser leaves the page: a lease it held is no longer renewed.)
int Server::logout(mg_connection* c) {
  if (!hosts_.origin_ok(mg_get_header(c, "Origin"), mg_get_header(c, "Host"))) {
    return respond(c, 403, "text/plain; charset=utf-8",
                   "403: log out from this console's own page (Origin, Host)\n");
  }
  if (auth_.logout(mg_get_header(c, "Cookie"))) {
    std::fprintf(stderr, "stepmod-web: logout from %s: the session closed\n",
                 mg_get_request_info(c)->remote_addr);
  }
  return respond(c, 303, "text/plain", "logged out\n",
                 std::string("Set-Cookie: ") + Auth::kCookie +
                     "=; Max-Age=0; HttpOnly; SameSite=Strict; Path=/\r\nLocation: /login\r\n");
}

int Server::serve_file(mg_connection* c, const std::string& uri) {
  static const std::set<std::string> kFiles = {
      "/index.html", "/console.js", "/plot.js",   "/style.css",    "/reasons.js",
      "/path.js",    "/inputs.js",  "/config.js", "/picture.html", "/picture.js"};
  const std::string path = uri == "/" ? "/index.html" : uri;
  if (kFiles.count(path) == 0) return respond(c, 404, "text/plain", "not found\n");
  return respond(c, 200, mime_of(path), read_file(opt_.www_dir + path));
}

int Server::on_http(mg_connection* c) {
  const mg_request_info* ri = mg_get_request_info(c);
  const std::string uri = ri->local_uri != nullptr ? ri->local_uri : "/";
  if (uri == "/login" && std::string(ri->request_method) == "POST") return login(c);
  guard_.request_read(c);
  if (uri == "/logout" && std::string(ri->request_method) == "POST") return logout(c);
  if (!hosts_.host_ok(mg_get_header(c, "Host"))) {
    return respond(c, 421, "text/plain; charset=utf-8",
                   "421: this console is not served under that name (Host header; see "
                   "stepmod-web --allow-host)\n");
  }
  if (uri == "/login")
    return respond(c, 200, "text/html; charset=utf-8", read_file(opt_.www_dir + "/login.html"));
  if (uri == "/style.css") return serve_file(c, uri);  // the login page's look: no secret
  if (!auth_.valid(mg_get_header(c, "Cookie"))) {
    // The page itself answers 401 with the login form, so a browser shows it.
    if (uri == "/" || uri == "/index.html") {
      return respond(c, 401, "text/html; charset=utf-8", read_file(opt_.www_dir + "/login.html"));
    }
    return respond(c, 401, "text/plain", "401: log in first (/login)\n");
  }
  if (uri == "/api/hello") return respond(c, 200, "application/json", hello_);
  if (uri == "/reasons") return respond(c, 200, "text/html; charset=utf-8", opt_.reasons_page);
  return serve_file(c, uri);
}

int Server::on_ws_connect(const mg_connection* c) {
  guard_.request_read(c);
  const mg_request_info* ri = mg_get_request_info(c);
  const char* why = nullptr;
  if (!hosts_.origin_ok(mg_get_header(c, "Origin"), mg_get_header(c, "Host"))) {
    why = "not from this console's own page (Origin, Host)";
  } else if (!auth_.valid(mg_get_header(c, "Cookie"))) {
    why = "no session";
  }
  if (why == nullptr) return 0;
  if (unsigned skipped = 0; refusals_.pass(skipped)) {
    const std::string more =
        skipped > 0 ? " (and " + std::to_string(skipped) + " more not logged)" : "";
    std::fprintf(stderr, "stepmod-web: WebSocket from %s (Origin %s) refused: %s%s\n",
                 peer_of(ri).c_str(), printable(mg_get_header(c, "Origin")).c_str(), why,
                 more.c_str());
  }
  return 1;  // nonzero: civetweb closes it without the handshake
}

void Server::on_ws_ready(mg_connection* c) {
  const mg_request_info* ri = mg_get_request_info(c);
  const int fd = socket_of_connection(c);
  if (fd < 0) {
    std::fprintf(stderr, "stepmod-web: WebSocket from %s: its socket not found, closed\n",
                 peer_of(ri).c_str());
    return;
  }
  hub_.serve(fd, reinterpret_cast<std::uintptr_t>(c), peer_of(ri), hello_);
}

void Server::on_ws_close(const mg_connection* c) {
  commander_.disconnected(reinterpret_cast<std::uintptr_t>(c));
}

}  // namespace stepmod::web
