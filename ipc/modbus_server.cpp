#include "ipc/modbus_server.hpp"

#include <modbus/modbus.h>
#include <spdlog/spdlog.h>

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <signal.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <span>
#include <vector>

#include "ipc/modbus_map.hpp"
#include "ipc/shm_object.hpp"

namespace stepmod::ipc {

namespace {
// A request arrives in at most a few TCP segments on loopback or a LAN; a client that stops in
// the middle of one holds this thread (never a scan) for at most this long per byte wait.
constexpr std::uint32_t kByteTimeoutUs = 100'000;
}  // namespace

struct ModbusServer::Impl {
  ShmMapping map;
  std::unique_ptr<ModbusMap> regs;
  modbus_t* ctx = nullptr;
  modbus_mapping_t* mapping = nullptr;  // reply buffers for modbus_reply()
  int listen_fd = -1;
  int wake_fd = -1;
  std::vector<int> clients;

  ~Impl() {
    for (int fd : clients) ::close(fd);
    if (listen_fd >= 0) ::close(listen_fd);
    if (wake_fd >= 0) ::close(wake_fd);
    if (mapping != nullptr) modbus_mapping_free(mapping);
    if (ctx != nullptr) modbus_free(ctx);
  }
};

ModbusServer::ModbusServer(const std::string& name, const ModbusOptions& options)
    : impl_(std::make_unique<Impl>()), options_(options) {
  Impl& d = *impl_;
  check_name(name);
  d.map = ShmMapping::open(image_object(name), STEPMOD_IMAGE_SIZE);
  auto* img = static_cast<stepmod_image_t*>(d.map.data());
  if (!d.map.writable() || !stepmod_magic_is(img->magic, STEPMOD_IMAGE_MAGIC)) {
    throw IpcError("modbus: the image of module '" + name + "' is not a writable stepmod image");
  }
  d.regs = std::make_unique<ModbusMap>(*img, options.writes);

  d.ctx = modbus_new_tcp(options.address.c_str(), options.port);
  if (d.ctx == nullptr) throw IpcError(std::string("modbus: ") + modbus_strerror(errno));
  modbus_set_byte_timeout(d.ctx, 0, kByteTimeoutUs);
  d.mapping = modbus_mapping_new_start_address(0, 0, 0, 0, 0, d.regs->holding_registers(), 0,
                                               kHeaderBase + kHeaderRegisters);
  if (d.mapping == nullptr) throw IpcError("modbus: out of memory");
  d.listen_fd = modbus_tcp_listen(d.ctx, static_cast<int>(options.max_clients));
  if (d.listen_fd < 0) {
    throw IpcError("modbus: cannot listen on " + endpoint() + ": " + std::strerror(errno));
  }
  ::fcntl(d.listen_fd, F_SETFD, FD_CLOEXEC);
  d.wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (d.wake_fd < 0) throw IpcError(std::string("modbus: eventfd: ") + std::strerror(errno));
  thread_ = std::thread([this] { run(); });
}

ModbusServer::~ModbusServer() {
  stop();
}

void ModbusServer::stop() noexcept {
  if (!thread_.joinable()) return;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t n = ::write(impl_->wake_fd, &one, sizeof one);
  thread_.join();
}

std::string ModbusServer::endpoint() const {
  return options_.address + ":" + std::to_string(options_.port);
}

void ModbusServer::run() noexcept {
  Impl& d = *impl_;
  // Normal priority whatever the creating thread had: Modbus never competes with the pulse or
  // control thread. A peer that closed its socket must not kill the daemon with SIGPIPE.
  sched_param sp{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &sp);
  sigset_t pipe_set;
  sigemptyset(&pipe_set);
  sigaddset(&pipe_set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_set, nullptr);

  std::vector<pollfd> fds;
  std::uint8_t req[MODBUS_TCP_MAX_ADU_LENGTH];
  for (;;) {
    fds.clear();
    fds.push_back({d.wake_fd, POLLIN, 0});
    fds.push_back({d.listen_fd, POLLIN, 0});
    for (int fd : d.clients) fds.push_back({fd, POLLIN, 0});
    if (::poll(fds.data(), fds.size(), -1) < 0) {
      if (errno == EINTR) continue;
      spdlog::error("modbus: poll: {}; server stopped", std::strerror(errno));
      return;
    }
    if (fds[0].revents != 0) return;  // stop()

    std::vector<int> closed;
    for (std::size_t i = 2; i < fds.size(); ++i) {
      if (fds[i].revents == 0) continue;
      modbus_set_socket(d.ctx, fds[i].fd);
      const int len = modbus_receive(d.ctx, req);
      if (len < 0) {  // peer closed, reset, or sent a frame libmodbus cannot parse
        closed.push_back(fds[i].fd);
        continue;
      }
      if (len == 0) continue;
      const int header = modbus_get_header_length(d.ctx);
      const std::uint8_t unit = req[header - 1];
      if (unit != options_.unit_id) {
        // Addressed to another unit behind this "gateway": there is none.
        modbus_reply_exception(d.ctx, req, MODBUS_EXCEPTION_GATEWAY_TARGET);
        continue;
      }
      const ModbusResult r = d.regs->handle(
          std::span<const std::uint8_t>(req + header, static_cast<std::size_t>(len - header)));
      if (r.exception != ModbusException::kNone) {
        modbus_reply_exception(d.ctx, req, static_cast<unsigned>(r.exception));
        continue;
      }
      // modbus_reply() builds the answer from its mapping: put the values read in the window.
      std::uint16_t* table = r.function == modbus_fc::kReadInput ? d.mapping->tab_input_registers
                                                                 : d.mapping->tab_registers;
      for (unsigned k = 0; k < r.count; ++k) table[r.address + k] = r.values[k];
      modbus_reply(d.ctx, req, len, d.mapping);
    }
    for (int fd : closed) {
      ::close(fd);
      std::erase(d.clients, fd);
    }

    if (fds[1].revents != 0) {
      const int fd = ::accept4(d.listen_fd, nullptr, nullptr, SOCK_CLOEXEC);
      if (fd < 0) continue;
      if (d.clients.size() >= options_.max_clients) {
        // Over [modbus] max_clients: the connection is closed at once.
        spdlog::warn("modbus: connection refused, {} clients already connected", d.clients.size());
        ::close(fd);
      } else {
        d.clients.push_back(fd);
      }
    }
  }
}

}  // namespace stepmod::ipc
