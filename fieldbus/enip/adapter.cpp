#include "fieldbus/enip/adapter.hpp"

#include <arpa/inet.h>
#include <pthread.h>
#include <sched.h>
#include <spdlog/spdlog.h>
#include <sys/eventfd.h>
#include <sys/random.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>

#include "fieldbus/enip/adapter_impl.hpp"
#include "fieldbus/enip/adapter_sockets.hpp"
#include "ipc/wake_join.hpp"

namespace stepmod::enip {

namespace {
ipc::ShmMapping map_image(const std::string& name) {
  ipc::check_name(name);
  ipc::ShmMapping m = ipc::ShmMapping::open(ipc::image_object(name), STEPMOD_IMAGE_SIZE);
  const auto* img = static_cast<const stepmod_image_t*>(m.data());
  if (!m.writable() || !stepmod_magic_is(img->magic, STEPMOD_IMAGE_MAGIC)) {
    throw ipc::IpcError("ethernetip: the image of module '" + name +
                        "' is not a writable stepmod image");
  }
  return m;
}

// The O→T ids start somewhere no one can guess (docs/ethernetip-design.md, "Connection Manager").
std::uint32_t random_seed() noexcept {
  std::uint32_t seed = 0;
  if (::getrandom(&seed, sizeof seed, 0) != static_cast<ssize_t>(sizeof seed)) {
    seed = static_cast<std::uint32_t>(monotonic_now());
  }
  return seed;
}
}  // namespace

Adapter::Impl::Impl(const Setup& s)
    : setup(s),
      map(map_image(s.module_name)),
      image(static_cast<stepmod_image_t*>(map.data())),
      assemblies(*image),
      connections(random_seed()),
      answer_spread(random_seed()),
      identity(identity_for(image->module_type, s.serial)),
      router{identity,
             assemblies.layout(),
             AdapterLimits{s.options.rpi_min_us, s.options.rpi_max_us},
             assemblies,
             connections,
             network,
             RequestOrigin{}},
      encap{sessions, identity, SocketAddress{parse_ipv4(s.options.address), s.options.port},
            router} {
  const AdapterOptions& o = s.options;
  wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (wake_fd < 0) throw ipc::IpcError("ethernetip: eventfd: " + std::string(std::strerror(errno)));
  timer_fd = open_timer();
  listen_fd = open_bound_socket(SOCK_STREAM, o.address, o.port);
  udp_fd = open_bound_socket(SOCK_DGRAM, o.address, o.port);
  want_packet_info(udp_fd);  // listening on 0.0.0.0, broadcasts arrive here too
  io_fd = open_bound_socket(SOCK_DGRAM, o.address, kIoPort);
  open_broadcast(o);
}

// Broadcast ListIdentity (docs/ethernetip-design.md, "Encapsulation"): answered on the interface
// that holds the listen address. A socket bound to that address does not receive broadcasts, so
// a second one on 0.0.0.0 does; when it cannot be bound (another program holds the port without
// SO_REUSEADDR) the adapter runs without it and says so.
void Adapter::Impl::open_broadcast(const AdapterOptions& o) {
  broadcasts = BroadcastScope::for_listen(parse_ipv4(o.address), interface_addresses());
  if (!broadcasts.needs_own_socket()) return;
  std::string why;
  broadcast_fd = open_broadcast_socket(o.port, why);
  if (broadcast_fd < 0) {
    spdlog::warn("ethernetip: {}: broadcast ListIdentity will not be answered ({})", o.address,
                 why);
  }
}

Adapter::Impl::~Impl() {
  for (TcpClient& c : clients) {
    if (c.fd >= 0) ::close(c.fd);
  }
  for (const int fd : {io_fd, broadcast_fd, udp_fd, listen_fd, timer_fd, wake_fd}) {
    if (fd >= 0) ::close(fd);
  }
}

Adapter::Adapter(const Setup& setup)
    : impl_(std::make_unique<Impl>(setup)),
      endpoint_(setup.options.address + ":" + std::to_string(setup.options.port)) {
  thread_ = std::thread([this] { run(); });
}

std::string Adapter::endpoint() const {
  return endpoint_;
}

const AdapterCounters& Adapter::counters() const noexcept {
  return impl_->counters;
}

void Adapter::stop() noexcept {
  ipc::wake_and_join(impl_->wake_fd, thread_);
}

Adapter::~Adapter() {
  stop();
}

bool Adapter::Impl::allowed(std::uint32_t ip_host_order, const char* what) noexcept {
  if (ipc::address_allowed(setup.options.allow, htonl(ip_host_order))) return true;
  counters.refused.fetch_add(1, std::memory_order_relaxed);
  std::uint64_t since = 0;
  if (refused_log.count(monotonic_now(), since)) {
    const in_addr a{htonl(ip_host_order)};
    char host[INET_ADDRSTRLEN] = "?";
    ::inet_ntop(AF_INET, &a, host, sizeof host);
    spdlog::warn(
        "ethernetip: {} from {} dropped (not in [ethernetip] allow); {} dropped since the last "
        "such line",
        what, host, since);
  }
  return false;
}

void Adapter::Impl::publish_deadman() noexcept {
  if (setup.plc_not_in_run != nullptr) {
    setup.plc_not_in_run->store(connections.plc_left_run(), std::memory_order_release);
  }
  identity.status = connections.identity_status();
}

void Adapter::Impl::rearm() noexcept {
  const std::int64_t due = std::min(connections.next_due_ns(), delayed.next_due());
  if (due == armed_at) return;
  arm_timer(timer_fd, due);
  armed_at = due;
}

std::size_t Adapter::Impl::fill_fds() noexcept {
  fds[kWake] = {wake_fd, POLLIN, 0};
  fds[kTimer] = {timer_fd, POLLIN, 0};
  fds[kListen] = {listen_fd, POLLIN, 0};
  fds[kEncapUdp] = {udp_fd, POLLIN, 0};
  fds[kBroadcastUdp] = {broadcast_fd, POLLIN, 0};  // fd -1: poll skips it
  fds[kIo] = {io_fd, POLLIN, 0};
  std::size_t n = kFixedSlots;
  for (const TcpClient& c : clients) fds[n++] = {c.fd, POLLIN, 0};  // fd -1: poll skips it
  return n;
}

// Timeouts first (a silent owner is the PLC leaving Run), then every T→O that is due, each from
// one read of the input words; the answers to broadcasts whose delay has passed.
void Adapter::Impl::on_due(Nanos now) noexcept {
  connections.expire(now);
  delayed.send_due(now, [this](const sockaddr_in& to, std::span<const std::uint8_t> reply) {
    ::sendto(udp_fd, reply.data(), reply.size(), MSG_DONTWAIT,
             reinterpret_cast<const sockaddr*>(&to), sizeof to);
  });
  const std::span<std::uint8_t> in(input.data(), assemblies.layout().input_bytes);
  bool read = false;
  const std::span<IoConnection> slots = connections.slots();
  for (std::size_t i = 0; i < slots.size(); ++i) {
    IoConnection& c = slots[i];
    if (!IoConnections::to_due(c, now)) continue;
    if (!read) assemblies.read(kInputInstance, in);
    read = true;
    const std::size_t n = producer.produce(i, c, in, now, tx);
    const sockaddr_in to = ipv4_address(c.originator_ip, kIoPort);
    if (n > 0 && ::sendto(io_fd, tx.data(), n, MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&to),
                          sizeof to) == static_cast<ssize_t>(n)) {
      counters.to_sent.fetch_add(1, std::memory_order_relaxed);
    }
  }
  publish_deadman();
}

// Up to kDatagramsPerWake datagrams waiting on `fd`, each from an allowed sender handed to
// `take(ip, bytes, arrival)`; a datagram longer than the buffer is not ours and is dropped.
template <class Take>
void Adapter::Impl::each_datagram(int fd, const char* what, Take&& take) noexcept {
  for (int k = 0; k < kDatagramsPerWake; ++k) {
    Arrival a;
    const long n = receive_datagram(fd, rx, a);
    if (n < 0) break;
    const std::uint32_t ip = ntohl(a.from.sin_addr.s_addr);
    if (static_cast<std::size_t>(n) > rx.size() || !allowed(ip, what)) continue;
    take(ip, std::span<const std::uint8_t>(rx.data(), static_cast<std::size_t>(n)), a);
  }
}

// Class 1 O→T: a Run packet with new data is one seqlock write of the output words; every Run
// packet is a PLC heartbeat.
void Adapter::Impl::receive_io(Nanos now) noexcept {
  each_datagram(io_fd, "an I/O packet",
                [&](std::uint32_t ip, std::span<const std::uint8_t> d, const Arrival&) {
                  const OtResult r = connections.on_o_to_t(ip, d, now);
                  if (r.outcome == OtOutcome::kRunWrite) {
                    assemblies.write_output(r.data);
                    counters.run_writes.fetch_add(1, std::memory_order_relaxed);
                  } else if (r.outcome == OtOutcome::kRunRepeat) {
                    assemblies.beat();
                  } else if (r.outcome == OtOutcome::kDropped) {
                    counters.io_dropped.fetch_add(1, std::memory_order_relaxed);
                  }
                });
  publish_deadman();
}

// UDP encapsulation: ListIdentity, ListServices, ListInterfaces, answered to the sender at once;
// a broadcast ListIdentity after its random delay. The broadcast socket also receives what is
// not ours (another address's datagrams, another interface's broadcasts): dropped.
void Adapter::Impl::receive_udp(int fd, Nanos now) noexcept {
  each_datagram(fd, "a UDP request",
                [&](std::uint32_t ip, std::span<const std::uint8_t> d, const Arrival& a) {
                  const bool broadcast = broadcasts.accepts(a.ifindex, a.destination);
                  if (broadcast) return answer_broadcast(d, a.from, now);
                  if (fd != udp_fd) return;
                  router.origin = RequestOrigin{ip, now, 0};
                  const std::size_t size = handle_udp(d, encap, tx);
                  if (size > 0) {
                    ::sendto(udp_fd, tx.data(), size, MSG_DONTWAIT,
                             reinterpret_cast<const sockaddr*>(&a.from), sizeof a.from);
                  }
                });
}

// Only ListIdentity is answered to a broadcast, from the unicast socket (so from the listen
// address), at a random time within the delay its sender allows; when every slot waits already,
// not at all (docs/ethernetip-design.md, "Encapsulation").
void Adapter::Impl::answer_broadcast(std::span<const std::uint8_t> request, const sockaddr_in& to,
                                     Nanos now) noexcept {
  const std::optional<Nanos> max_delay = list_identity_max_delay(request);
  if (!max_delay) return;
  const std::size_t size = handle_udp(request, encap, tx);
  if (size == 0) return;
  delayed.add(now + random_below(*max_delay + 1), to, std::span(tx.data(), size));
}

// Two draws make the 64 bits a delay of up to 65.5 s in ns needs.
Nanos Adapter::Impl::random_below(Nanos limit) noexcept {
  const std::uint64_t high = answer_spread.next();
  const std::uint64_t r = (high << 32) | answer_spread.next();
  return static_cast<Nanos>(r % static_cast<std::uint64_t>(limit));
}

void Adapter::run() noexcept {
  Impl& d = *impl_;
  // Normal priority whatever the creating thread had: the adapter never competes with the
  // pulse or control thread.
  sched_param sp{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
  pthread_setname_np(pthread_self(), "stepmod-enip");
  d.publish_deadman();
  for (;;) {
    d.rearm();
    const std::size_t n = d.fill_fds();
    if (::poll(d.fds.data(), n, -1) < 0) {
      if (errno == EINTR) continue;
      return;
    }
    if (d.fds[Impl::kWake].revents != 0) return;
    const Nanos now = monotonic_now();
    if (d.fds[Impl::kTimer].revents != 0) {
      std::uint64_t expirations = 0;
      [[maybe_unused]] const ssize_t r = ::read(d.timer_fd, &expirations, sizeof expirations);
      d.armed_at = 0;  // fired: arm again whatever the next time is
    }
    if (d.fds[Impl::kIo].revents != 0) d.receive_io(now);
    if (d.fds[Impl::kEncapUdp].revents != 0) d.receive_udp(d.udp_fd, now);
    if (d.fds[Impl::kBroadcastUdp].revents != 0) d.receive_udp(d.broadcast_fd, now);
    for (std::size_t i = 0; i < kMaxTcpClients; ++i) {
      if (d.fds[Impl::kFixedSlots + i].revents != 0) d.serve(d.clients[i], now);
    }
    if (d.fds[Impl::kListen].revents != 0) d.accept_one(now);
    d.on_due(monotonic_now());
  }
}

}  // namespace stepmod::enip
