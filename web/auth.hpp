#pragma once
// Access to the console: the token file (generated at package install, readable by root and the
// stepmod group) is what the login page asks for; a correct token makes a session, carried by an
// HttpOnly, SameSite=Strict cookie. Every other request needs a valid session.
#include <chrono>
#include <mutex>
#include <string>
#include <unordered_map>

namespace stepmod::web {

class Auth {
 public:
  static constexpr const char* kCookie = "stepmod_web";

  // Reads the token (first line, surrounding white space removed). Throws std::runtime_error
  // when the file cannot be read or holds fewer than 16 characters.
  explicit Auth(const std::string& token_file,
                std::chrono::hours session_life = std::chrono::hours(12));

  // A new session id if `token` is the token; empty otherwise (compared in constant time).
  std::string login(const std::string& token);
  // Whether the Cookie header carries a live session.
  bool valid(const char* cookie_header);
  // Ends the session the Cookie header carries (the page's logout); false when it had none.
  bool logout(const char* cookie_header);

 private:
  std::string token_;
  std::chrono::hours life_;
  std::mutex m_;
  std::unordered_map<std::string, std::chrono::steady_clock::time_point> sessions_;
};

// The session cookie's value in a Cookie header ("a=1; stepmod_web=xyz"), or empty.
std::string cookie_value(const char* header, const std::string& name);

}  // namespace stepmod::web
