#include "web/auth.hpp"

#include <fstream>
#include <random>
#include <stdexcept>

namespace stepmod::web {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

bool same(const std::string& a, const std::string& b) {
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff |= static_cast<unsigned char>(a[i] ^ (i < b.size() ? b[i] : 0));
  }
  return diff == 0;
}

std::string random_id() {
  std::random_device rd;  // /dev/urandom on Linux
  static constexpr char kHex[] = "0123456789abcdef";
  std::string id;
  for (int i = 0; i < 8; ++i) {
    const std::uint32_t v = rd();
    for (int n = 0; n < 8; ++n) id.push_back(kHex[(v >> (4 * n)) & 0xF]);
  }
  return id;
}

}  // namespace

Auth::Auth(const std::string& token_file, std::chrono::hours session_life) : life_(session_life) {
  std::ifstream f(token_file);
  std::string line;
  if (!f || !std::getline(f, line)) {
    throw std::runtime_error("cannot read the access token file " + token_file);
  }
  token_ = trim(line);
  if (token_.size() < 16) {
    throw std::runtime_error("the access token in " + token_file +
                             " is shorter than 16 characters");
  }
}

std::string Auth::login(const std::string& token) {
  if (!same(trim(token), token_)) return "";
  std::string id = random_id();
  std::lock_guard lock(m_);
  sessions_[id] = std::chrono::steady_clock::now() + life_;
  return id;
}

bool Auth::valid(const char* cookie_header) {
  const std::string id = cookie_value(cookie_header, kCookie);
  if (id.empty()) return false;
  std::lock_guard lock(m_);
  const auto it = sessions_.find(id);
  if (it == sessions_.end()) return false;
  if (std::chrono::steady_clock::now() > it->second) {
    sessions_.erase(it);
    return false;
  }
  return true;
}

bool Auth::logout(const char* cookie_header) {
  const std::string id = cookie_value(cookie_header, kCookie);
  if (id.empty()) return false;
  std::lock_guard lock(m_);
  return sessions_.erase(id) > 0;
}

std::string cookie_value(const char* header, const std::string& name) {
  if (header == nullptr) return "";
  const std::string h(header);
  std::size_t pos = 0;
  while (pos < h.size()) {
    const auto end = h.find(';', pos);
    const std::string part = trim(h.substr(pos, end == std::string::npos ? end : end - pos));
    if (part.rfind(name + "=", 0) == 0) return part.substr(name.size() + 1);
    if (end == std::string::npos) break;
    pos = end + 1;
  }
  return "";
}

}  // namespace stepmod::web
