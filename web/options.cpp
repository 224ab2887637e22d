#include "web/options.hpp"

#include <stdexcept>

namespace stepmod::web {

unsigned default_port(const std::string& name) {
  std::size_t i = name.size();
  while (i > 0 && name[i - 1] >= '0' && name[i - 1] <= '9') --i;
  const std::string digits = name.substr(i);
  if (digits.empty()) return kBasePort;
  if (digits.size() > 3) {
    throw std::invalid_argument("module name '" + name +
                                "' ends in more than 3 digits: give the port with --port");
  }
  return kBasePort + static_cast<unsigned>(std::stoul(digits));
}

}  // namespace stepmod::web
