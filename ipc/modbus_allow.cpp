#include "ipc/modbus_allow.hpp"

#include <arpa/inet.h>

namespace stepmod::ipc {

std::optional<AllowNet> parse_allow_net(const std::string& text) {
  const auto slash = text.find('/');
  const std::string host = text.substr(0, slash);
  in_addr a{};
  if (::inet_pton(AF_INET, host.c_str(), &a) != 1) return std::nullopt;
  unsigned prefix = 32;
  if (slash != std::string::npos) {
    const std::string p = text.substr(slash + 1);
    if (p.empty() || p.size() > 2 || p.find_first_not_of("0123456789") != std::string::npos) {
      return std::nullopt;
    }
    prefix = static_cast<unsigned>(std::stoul(p));
    if (prefix > 32) return std::nullopt;
  }
  const std::uint32_t mask = prefix == 0 ? 0u : ~std::uint32_t{0} << (32 - prefix);
  return AllowNet{ntohl(a.s_addr) & mask, mask};
}

bool address_allowed(std::span<const AllowNet> nets, std::uint32_t address_be) noexcept {
  if (nets.empty()) return true;
  const std::uint32_t a = ntohl(address_be);
  for (const AllowNet& n : nets) {
    if ((a & n.mask) == n.network) return true;
  }
  return false;
}

}  // namespace stepmod::ipc
