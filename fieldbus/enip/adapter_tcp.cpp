// The adapter's TCP connections (encapsulation on the listen address): accepted only from the
// allow list, each with its own fixed receive buffer; frames answered in order; a connection the
// session layer closes (UnRegisterSession, a frame whose end cannot be trusted), that does not
// take its replies, or that is the longest idle when a new one needs its place is closed. Its
// session goes with it; its I/O connections do not (a Logix PLC closes the explicit session once
// the I/O connection stands).
#include <arpa/inet.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>

#include "fieldbus/enip/adapter_impl.hpp"
#include "fieldbus/enip/adapter_sockets.hpp"

namespace stepmod::enip {

void Adapter::Impl::close_client(TcpClient& c) noexcept {
  if (c.fd < 0) return;
  ::close(c.fd);
  sessions.remove(c.id);
  c.fd = -1;
  c.rx_size = 0;
}

namespace {
// The board's address a connection came in on (host byte order; 0 when not known): listening on
// 0.0.0.0, it says which interface the TCP/IP Interface object describes.
std::uint32_t local_address(int fd) noexcept {
  sockaddr_in a{};
  socklen_t len = sizeof a;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) return 0;
  return ntohl(a.sin_addr.s_addr);
}
}  // namespace

void Adapter::Impl::accept_one(Nanos now) noexcept {
  sockaddr_in a{};
  socklen_t len = sizeof a;
  const int fd =
      ::accept4(listen_fd, reinterpret_cast<sockaddr*>(&a), &len, SOCK_NONBLOCK | SOCK_CLOEXEC);
  if (fd < 0) return;
  const std::uint32_t ip = ntohl(a.sin_addr.s_addr);
  if (!allowed(ip, "a TCP connection")) {
    ::close(fd);
    return;
  }
  auto slot =
      std::find_if(clients.begin(), clients.end(), [](const TcpClient& c) { return c.fd < 0; });
  if (slot == clients.end()) {
    slot = std::min_element(clients.begin(), clients.end(), [](const auto& x, const auto& y) {
      return x.last_heard < y.last_heard;
    });
    close_client(*slot);
  }
  slot->fd = fd;
  slot->id = next_client_id++;
  if (next_client_id == 0) next_client_id = 1;  // 0 is "no connection" to the session table
  slot->ip = ip;
  slot->local_ip = local_address(fd);
  slot->last_heard = now;
  slot->rx_size = 0;
}

// Every whole frame at the front of the buffer, in order; false: close the connection.
bool Adapter::Impl::answer_frames(TcpClient& c, Nanos now) noexcept {
  std::size_t used = 0;
  router.origin = RequestOrigin{c.ip, now, c.local_ip};
  for (;;) {
    const SessionStep s =
        handle_tcp(std::span(c.rx.data() + used, c.rx_size - used), c.id, encap, tx);
    publish_deadman();  // a Forward_Close of the owner is the PLC leaving Run
    if (s.action == SessionAction::kClose) return false;
    if (s.action == SessionAction::kReply &&
        !send_whole(c.fd, std::span(tx.data(), s.reply_size))) {
      return false;
    }
    if (s.consumed == 0) break;
    used += s.consumed;
  }
  std::memmove(c.rx.data(), c.rx.data() + used, c.rx_size - used);
  c.rx_size -= used;
  return true;
}

void Adapter::Impl::serve(TcpClient& c, Nanos now) noexcept {
  if (c.fd < 0) return;
  const ssize_t n = ::recv(c.fd, c.rx.data() + c.rx_size, c.rx.size() - c.rx_size, MSG_DONTWAIT);
  if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) return;
  if (n <= 0) {
    close_client(c);
    return;
  }
  c.rx_size += static_cast<std::size_t>(n);
  c.last_heard = now;
  // A full buffer holds a whole frame (kTcpRxBytes is two of the largest), so the session layer
  // has answered or closed it: one left full cannot happen, and would be closed.
  if (!answer_frames(c, now) || c.rx_size == c.rx.size()) close_client(c);
}

}  // namespace stepmod::enip
