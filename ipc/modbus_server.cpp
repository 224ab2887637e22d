#include "ipc/modbus_server.hpp"

#include <spdlog/spdlog.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <list>
#include <vector>

#include "ipc/log_throttle.hpp"
#include "ipc/mbap.hpp"
#include "ipc/modbus_map.hpp"
#include "ipc/shm_object.hpp"
#include "ipc/wake_join.hpp"

namespace stepmod::ipc {

namespace {
// Unanswered bytes a client may let pile up (it sends and never reads): then it is closed.
constexpr std::size_t kMaxPendingOut = std::size_t{64} * 1024;
// Bytes read per recv(): whole frames of a pipelining client at once.
constexpr std::size_t kReadChunk = 4096;

using Connection = ModbusConnection;

std::string peer_name(const sockaddr_in& a) {
  char host[INET_ADDRSTRLEN] = "?";
  ::inet_ntop(AF_INET, &a.sin_addr, host, sizeof host);
  return std::string(host) + ":" + std::to_string(ntohs(a.sin_port));
}
}  // namespace

struct ModbusServer::Impl {
  // A module served: its unit id, its image mapped, its registers.
  struct Unit {
    std::uint8_t id = 0;
    ShmMapping map;
    std::unique_ptr<ModbusMap> regs;
  };
  std::vector<Unit> units;
  int listen_fd = -1;
  int wake_fd = -1;
  std::list<Connection> clients;
  LogThrottle refused_log{kLogPeriod};
  LogThrottle evicted_log{kLogPeriod};
  LogThrottle idle_log{kLogPeriod};

  ~Impl() {
    for (Connection& c : clients) ::close(c.fd);
    if (listen_fd >= 0) ::close(listen_fd);
    if (wake_fd >= 0) ::close(wake_fd);
  }
  void accept_one(const ModbusOptions& o);
  void make_room(const std::string& newcomer, Nanos now);
  void add_unit(const ModbusUnit& u);
  ModbusMap* unit(std::uint8_t id) noexcept;
  bool serve(Connection& c, short revents);
  bool receive(Connection& c);
  bool answer(Connection& c);
  bool send_pending(Connection& c);
  bool timed_out(const Connection& c, Nanos now, Nanos idle_timeout);
  int poll_timeout_ms(Nanos now, Nanos idle_timeout) const;
};

namespace {
int listen_on(const ModbusOptions& o) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(o.port);
  if (::inet_pton(AF_INET, o.address.c_str(), &a.sin_addr) != 1) {
    throw IpcError("modbus: '" + o.address + "' is not a numeric IPv4 address");
  }
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd < 0) throw IpcError(std::string("modbus: socket: ") + std::strerror(errno));
  const int one = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) != 0 || ::listen(fd, 16) != 0) {
    const std::string why = std::strerror(errno);
    ::close(fd);
    throw IpcError("modbus: cannot listen on " + o.address + ":" + std::to_string(o.port) + ": " +
                   why);
  }
  return fd;
}
}  // namespace

ModbusServer::ModbusServer(std::span<const ModbusUnit> units)
    : impl_(std::make_unique<Impl>()),
      options_(units.empty() ? ModbusOptions{} : units.front().options) {
  Impl& d = *impl_;
  if (units.empty()) throw IpcError("modbus: a server needs a module to serve");
  for (const ModbusUnit& u : units) d.add_unit(u);
  d.listen_fd = listen_on(options_);
  d.wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (d.wake_fd < 0) throw IpcError(std::string("modbus: eventfd: ") + std::strerror(errno));
  thread_ = std::thread([this] { run(); });
}

void ModbusServer::Impl::add_unit(const ModbusUnit& u) {
  check_name(u.name);
  if (unit(u.options.unit_id) != nullptr) {
    throw IpcError("modbus: unit id " + std::to_string(u.options.unit_id) + " twice");
  }
  Unit& n = units.emplace_back();
  n.id = u.options.unit_id;
  n.map = ShmMapping::open(image_object(u.name), STEPMOD_IMAGE_SIZE);
  auto* img = static_cast<stepmod_image_t*>(n.map.data());
  if (!n.map.writable() || !stepmod_magic_is(img->magic, STEPMOD_IMAGE_MAGIC)) {
    throw IpcError("modbus: the image of module '" + u.name + "' is not a writable stepmod image");
  }
  n.regs = std::make_unique<ModbusMap>(*img, u.options.writes);
}

ModbusMap* ModbusServer::Impl::unit(std::uint8_t id) noexcept {
  for (Unit& u : units) {
    if (u.id == id) return u.regs.get();
  }
  return nullptr;
}

ModbusServer::~ModbusServer() {
  stop();
}

void ModbusServer::stop() noexcept {
  wake_and_join(impl_->wake_fd, thread_);
}

std::string ModbusServer::endpoint() const {
  return options_.address + ":" + std::to_string(options_.port);
}

void ModbusServer::Impl::accept_one(const ModbusOptions& o) {
  sockaddr_in a{};
  socklen_t len = sizeof a;
  const int fd =
      ::accept4(listen_fd, reinterpret_cast<sockaddr*>(&a), &len, SOCK_NONBLOCK | SOCK_CLOEXEC);
  if (fd < 0) return;
  const std::string peer = peer_name(a);
  const Nanos now = monotonic_now();
  std::uint64_t since = 0;
  if (!address_allowed(o.allow, a.sin_addr.s_addr)) {
    if (refused_log.count(now, since)) {
      spdlog::warn(
          "modbus: connection from {} refused (not in [modbus] allow); {} refused since the last "
          "such line",
          peer, since);
    }
    ::close(fd);
    return;
  }
  if (clients.size() >= o.max_clients) make_room(peer, now);
  Connection c;
  c.fd = fd;
  c.peer = peer;
  c.last_heard = now;
  clients.push_back(std::move(c));
}

// [modbus] max_clients are connected and `newcomer` comes: the longest-idle connection
// (eviction_choice) is closed for it. Refusing the newcomer instead let sockets that never ask
// anything keep a reconnecting PLC out until they went away.
void ModbusServer::Impl::make_room(const std::string& newcomer, Nanos now) {
  const auto victim = eviction_choice(clients);
  std::uint64_t since = 0;
  if (evicted_log.count(now, since)) {
    spdlog::warn(
        "modbus: {} closed to make room for {} (max_clients reached; it had {} for {} ms); {} "
        "closed so since the last such line",
        victim->peer, newcomer, victim->served ? "been idle" : "asked nothing",
        (now - victim->last_heard) / kNsPerMs, since);
  }
  ::close(victim->fd);
  clients.erase(victim);
}

// One connection's turn after poll(); false: close it.
bool ModbusServer::Impl::serve(Connection& c, short revents) {
  if ((revents & POLLOUT) && !send_pending(c)) return false;
  if ((revents & (POLLIN | POLLHUP | POLLERR)) && !receive(c)) return false;
  // After a malformed frame: closed once the answers owed to the frames before it are sent.
  return c.closing_since == 0 || !c.out.empty();
}

// Reads what the socket has; false: the connection is to be closed.
bool ModbusServer::Impl::receive(Connection& c) {
  // A bounded number of reads per round: a client that sends without pause gets its turn like
  // every other, not the whole thread.
  for (int round = 0; round < 16; ++round) {
    std::uint8_t buf[kReadChunk];
    const ssize_t n = ::recv(c.fd, buf, sizeof buf, MSG_DONTWAIT);
    if (n == 0) return false;  // the peer closed
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno == EAGAIN || errno == EWOULDBLOCK;
    }
    // After a malformed frame what follows is read and dropped: closing a socket with unread
    // bytes sends a reset, which may cost the client the answers still on their way.
    if (c.closing_since != 0) continue;
    const Nanos now = monotonic_now();
    c.last_heard = now;
    if (c.in.empty()) c.frame_start = now;
    c.in.insert(c.in.end(), buf, buf + n);
    if (!answer(c)) {
      c.closing_since = now;
      c.in.clear();
      c.frame_start = 0;
    }
    if (!send_pending(c)) return false;
    if (c.out.size() > kMaxPendingOut) return false;  // sends, never reads its answers
  }
  return true;
}

// Puts the answer to every whole frame in c.in into c.out; false on a malformed frame (left
// unanswered: the connection is to be closed once the answers before it are sent).
bool ModbusServer::Impl::answer(Connection& c) {
  std::size_t used = 0;
  bool well_formed = true;
  for (;;) {
    MbapFrame f;
    const MbapStatus s = parse_mbap(std::span<const std::uint8_t>(c.in).subspan(used), f);
    if (s == MbapStatus::kIncomplete) break;
    if (s != MbapStatus::kFrame) {
      well_formed = false;
      break;
    }
    if (ModbusMap* regs = unit(f.unit)) {
      append_response(c.out, f, regs->handle(f.pdu));
    } else {
      // Addressed to another unit behind this "gateway": there is none.
      append_exception(c.out, f, ModbusException::kGatewayTargetFailed);
    }
    c.served = true;
    used += f.size;
  }
  if (used > 0) {
    c.in.erase(c.in.begin(), c.in.begin() + static_cast<std::ptrdiff_t>(used));
    c.frame_start = c.in.empty() ? 0 : monotonic_now();
  }
  return well_formed;
}

// Sends what the socket takes now; false on an error (the peer is gone).
bool ModbusServer::Impl::send_pending(Connection& c) {
  std::size_t sent = 0;
  while (sent < c.out.size()) {
    const ssize_t n =
        ::send(c.fd, c.out.data() + sent, c.out.size() - sent, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) break;
      return false;
    }
    sent += static_cast<std::size_t>(n);
  }
  c.out.erase(c.out.begin(), c.out.begin() + static_cast<std::ptrdiff_t>(sent));
  return true;
}

// Whether `c` is past one of its time-outs (ipc/modbus_connection.hpp) at `now`; logs why.
bool ModbusServer::Impl::timed_out(const Connection& c, Nanos now, Nanos idle_timeout) {
  const ModbusTimeout t = next_timeout(c, idle_timeout);
  if (now < t.at) return false;
  std::uint64_t since = 0;
  if (!t.idle) {
    spdlog::debug("modbus: {}: {}: closed", c.peer, t.why);
  } else if (idle_log.count(now, since)) {
    spdlog::info(
        "modbus: {} closed after {} ms without a byte ([modbus] idle_timeout_ms); {} closed so "
        "since the last such line",
        c.peer, idle_timeout / kNsPerMs, since);
  }
  return true;
}

// Until the earliest time-out of a connection, or -1 (no connection).
int ModbusServer::Impl::poll_timeout_ms(Nanos now, Nanos idle_timeout) const {
  Nanos first = -1;
  for (const Connection& c : clients) {
    const Nanos left = std::max<Nanos>(0, next_timeout(c, idle_timeout).at - now);
    if (first < 0 || left < first) first = left;
  }
  return first < 0 ? -1 : static_cast<int>((first + kNsPerMs - 1) / kNsPerMs);
}

void ModbusServer::run() noexcept {
  Impl& d = *impl_;
  // Normal priority whatever the creating thread had: Modbus never competes with the pulse or
  // control thread.
  sched_param sp{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
  const Nanos idle_timeout = Nanos{options_.idle_timeout_ms} * kNsPerMs;

  std::vector<pollfd> fds;
  std::vector<Connection*> polled;
  for (;;) {
    fds.assign({{d.wake_fd, POLLIN, 0}, {d.listen_fd, POLLIN, 0}});
    polled.clear();
    for (Connection& c : d.clients) {
      fds.push_back({c.fd, static_cast<short>(POLLIN | (c.out.empty() ? 0 : POLLOUT)), 0});
      polled.push_back(&c);
    }
    if (::poll(fds.data(), fds.size(), d.poll_timeout_ms(monotonic_now(), idle_timeout)) < 0) {
      if (errno == EINTR) continue;
      spdlog::error("modbus: poll: {}; server stopped", std::strerror(errno));
      return;
    }
    if (fds[0].revents != 0) return;  // stop()

    const Nanos now = monotonic_now();
    for (std::size_t i = 0; i < polled.size(); ++i) {
      Connection& c = *polled[i];
      if (!d.serve(c, fds[i + 2].revents) || d.timed_out(c, now, idle_timeout)) {
        ::close(c.fd);
        c.fd = -1;
      }
    }
    d.clients.remove_if([](const Connection& c) { return c.fd < 0; });
    if (fds[1].revents != 0) d.accept_one(options_);
  }
}

}  // namespace stepmod::ipc
