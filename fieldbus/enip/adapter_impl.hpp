#pragma once
// The adapter's state, shared by its files (adapter.cpp: lifecycle, poll loop, UDP;
// adapter_tcp.cpp: the TCP connections). Internal to the adapter: nothing outside fieldbus/enip
// includes it.
#include <poll.h>

#include <array>
#include <cstddef>
#include <cstdint>

#include "core/clock.hpp"
#include "fieldbus/enip/adapter.hpp"
#include "fieldbus/enip/adapter_sockets.hpp"
#include "fieldbus/enip/broadcast.hpp"
#include "fieldbus/enip/connection_table.hpp"
#include "fieldbus/enip/encap.hpp"
#include "fieldbus/enip/encap_session.hpp"
#include "fieldbus/enip/image_assemblies.hpp"
#include "fieldbus/enip/net_interface_linux.hpp"
#include "fieldbus/enip/t_to_o_producer.hpp"
#include "fieldbus/enip/xorshift32.hpp"
#include "ipc/log_throttle.hpp"
#include "ipc/shm_object.hpp"

namespace stepmod::enip {

// TCP connections served at once; a new one beyond them closes the longest-idle one, so that
// sockets that ask nothing cannot keep the PLC out (as the Modbus server does).
inline constexpr std::size_t kMaxTcpClients = 8;
// Two whole frames: a frame is at most kEncapMaxFrame bytes, so one always fits behind the
// rest of the one before it.
inline constexpr std::size_t kTcpRxBytes = 2 * kEncapMaxFrame;
// The largest datagram taken: anything longer is not ours and is dropped whole.
inline constexpr std::size_t kMaxDatagram = 1500;
// Datagrams taken per socket per wake-up: a flood cannot starve the TCP connections or the T→O
// production.
inline constexpr int kDatagramsPerWake = 64;

struct TcpClient {
  int fd = -1;
  std::uint32_t id = 0;        // the session table's connection id, never 0
  std::uint32_t ip = 0;        // host byte order
  std::uint32_t local_ip = 0;  // the board's address it connected to
  Nanos last_heard = 0;
  std::size_t rx_size = 0;
  std::array<std::uint8_t, kTcpRxBytes> rx{};
};

struct Adapter::Impl {
  explicit Impl(const Setup& s);
  ~Impl();

  // Fixed poll slots, then one per TCP client.
  enum Slot : std::size_t { kWake, kTimer, kListen, kEncapUdp, kBroadcastUdp, kIo, kFixedSlots };

  Setup setup;
  ipc::ShmMapping map;
  stepmod_image_t* image = nullptr;
  ImageAssemblies assemblies;
  IoConnections connections;
  Xorshift32 answer_spread;  // the broadcast answers' random delays
  TtoProducer producer;
  SessionTable sessions;
  IdentityValues identity;
  LinuxNetworkPort network;
  RouterContext router;
  EncapContext encap;
  AdapterCounters counters;
  ipc::LogThrottle refused_log{10 * kNsPerSec};  // a flood cannot flood the journal
  int wake_fd = -1;
  int timer_fd = -1;
  int listen_fd = -1;
  int udp_fd = -1;
  int broadcast_fd = -1;  // -1: none needed (or it could not be bound)
  int io_fd = -1;
  BroadcastScope broadcasts;  // which broadcast ListIdentity requests are answered
  DelayedReplies delayed;     // their answers, each at its random time
  std::int64_t armed_at = 0;
  std::uint32_t next_client_id = 1;
  std::array<TcpClient, kMaxTcpClients> clients{};
  std::array<pollfd, kFixedSlots + kMaxTcpClients> fds{};
  std::array<std::uint8_t, kMaxDatagram> rx{};
  std::array<std::uint8_t, kEncapMaxFrame + kMaxReplyBytes> tx{};
  std::array<std::uint8_t, kMaxAssemblyBytes> input{};

  // Whether `ip` is in the allow list; else counted and (throttled) logged as `what`.
  bool allowed(std::uint32_t ip_host_order, const char* what) noexcept;
  void publish_deadman() noexcept;
  void rearm() noexcept;
  std::size_t fill_fds() noexcept;
  void on_due(Nanos now) noexcept;
  template <class Take>
  void each_datagram(int fd, const char* what, Take&& take) noexcept;
  void receive_io(Nanos now) noexcept;
  void receive_udp(int fd, Nanos now) noexcept;
  void answer_broadcast(std::span<const std::uint8_t> request, const sockaddr_in& to,
                        Nanos now) noexcept;
  void open_broadcast(const AdapterOptions& o);
  Nanos random_below(Nanos limit) noexcept;
  // adapter_tcp.cpp
  void accept_one(Nanos now) noexcept;
  void serve(TcpClient& c, Nanos now) noexcept;
  bool answer_frames(TcpClient& c, Nanos now) noexcept;
  void close_client(TcpClient& c) noexcept;
};

}  // namespace stepmod::enip
