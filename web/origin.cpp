#include "web/origin.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>

#include <algorithm>
#include <cctype>

namespace stepmod::web {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

bool wildcard(const std::string& listen) {
  return listen.empty() || listen == "0.0.0.0" || listen == "::" || listen == "[::]";
}

// Every address of the machine's interfaces (IPv6 ones in brackets, as a URL writes them).
std::vector<std::string> interface_addresses() {
  std::vector<std::string> out;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return out;
  for (const ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
    if (a->ifa_addr == nullptr) continue;
    char text[INET6_ADDRSTRLEN] = {};
    if (a->ifa_addr->sa_family == AF_INET) {
      const auto* in = reinterpret_cast<const sockaddr_in*>(a->ifa_addr);
      if (inet_ntop(AF_INET, &in->sin_addr, text, sizeof text)) out.emplace_back(text);
    } else if (a->ifa_addr->sa_family == AF_INET6) {
      const auto* in6 = reinterpret_cast<const sockaddr_in6*>(a->ifa_addr);
      if (IN6_IS_ADDR_LINKLOCAL(&in6->sin6_addr)) continue;  // needs a zone: no URL uses it
      if (inet_ntop(AF_INET6, &in6->sin6_addr, text, sizeof text)) {
        std::string bracketed(1, '[');
        out.push_back(bracketed.append(text).append("]"));
      }
    }
  }
  freeifaddrs(list);
  return out;
}

}  // namespace

HostPolicy::HostPolicy(const std::string& listen, unsigned port,
                       const std::vector<std::string>& extra) {
  for (const char* h : {"127.0.0.1", "localhost", "[::1]"}) add(h, port);
  if (wildcard(listen)) {
    for (const std::string& a : interface_addresses()) add(a, port);
  } else {
    add(listen, port);
  }
  for (const std::string& h : extra) add(h, port);
}

void HostPolicy::add(const std::string& host, unsigned port) {
  if (host.empty()) return;
  std::string h;
  bool has_port = false;
  if (host.front() == '[') {  // [v6] or [v6]:port
    h = host;
    has_port = host.find("]:") != std::string::npos;
  } else if (std::count(host.begin(), host.end(), ':') > 1) {  // a bare IPv6 address
    h.append("[").append(host).append("]");
  } else {  // name or name:port
    h = host;
    has_port = host.find(':') != std::string::npos;
  }
  if (!has_port) h.append(":").append(std::to_string(port));
  hosts_.insert(lower(h));
}

bool HostPolicy::host_ok(const char* host) const {
  return host != nullptr && hosts_.count(lower(host)) != 0;
}

bool HostPolicy::origin_ok(const char* origin, const char* host) const {
  return origin != nullptr && host_ok(host) && lower(origin) == "http://" + lower(host);
}

}  // namespace stepmod::web
