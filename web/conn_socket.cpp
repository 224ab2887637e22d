#include "web/conn_socket.hpp"

#include <arpa/inet.h>
#include <dirent.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>

#include <cstdlib>
#include <vector>

namespace stepmod::web {
namespace {

// The address and port of `sa` (IPv4 or IPv6), as civetweb writes them (inet_ntop).
bool name_of(const sockaddr_storage& sa, std::string& addr, unsigned& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (sa.ss_family == AF_INET) {
    const auto& in = reinterpret_cast<const sockaddr_in&>(sa);
    if (inet_ntop(AF_INET, &in.sin_addr, text, sizeof text) == nullptr) return false;
    port = ntohs(in.sin_port);
  } else if (sa.ss_family == AF_INET6) {
    const auto& in6 = reinterpret_cast<const sockaddr_in6&>(sa);
    if (inet_ntop(AF_INET6, &in6.sin6_addr, text, sizeof text) == nullptr) return false;
    port = ntohs(in6.sin6_port);
  } else {
    return false;
  }
  addr = text;
  return true;
}

bool matches(int fd, const std::string& peer_addr, unsigned peer_port, unsigned local_port) {
  sockaddr_storage sa{};
  socklen_t len = sizeof sa;
  std::string addr;
  unsigned port = 0;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&sa), &len) != 0) return false;
  if (!name_of(sa, addr, port) || port != local_port) return false;
  len = sizeof sa;
  if (getpeername(fd, reinterpret_cast<sockaddr*>(&sa), &len) != 0) return false;
  return name_of(sa, addr, port) && port == peer_port && addr == peer_addr;
}

// The open descriptors: /proc/self/fd, or every number below the limit where /proc is not there.
std::vector<int> open_fds() {
  std::vector<int> fds;
  if (DIR* d = opendir("/proc/self/fd")) {
    while (const dirent* e = readdir(d)) {
      if (e->d_name[0] >= '0' && e->d_name[0] <= '9') fds.push_back(std::atoi(e->d_name));
    }
    closedir(d);
    return fds;
  }
  rlimit lim{};
  getrlimit(RLIMIT_NOFILE, &lim);
  const rlim_t n = lim.rlim_cur < 65536 ? lim.rlim_cur : 65536;
  for (rlim_t fd = 0; fd < n; ++fd) fds.push_back(static_cast<int>(fd));
  return fds;
}

}  // namespace

int socket_of(const std::string& peer_addr, unsigned peer_port, unsigned local_port) {
  int found = -1;
  for (const int fd : open_fds()) {
    if (!matches(fd, peer_addr, peer_port, local_port)) continue;
    if (found >= 0) return -1;  // two candidates: not told apart
    found = fd;
  }
  return found;
}

}  // namespace stepmod::web
