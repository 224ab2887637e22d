#pragma once
// Which names the console is served under, for the checks against cross-site requests. A page of
// another site (another port of 127.0.0.1 counts as the same *site*, so the SameSite=Strict cookie
// goes along) could otherwise open the console's WebSocket with the operator's session and move
// the axes (cross-site WebSocket hijacking), and a name that resolves to 127.0.0.1 (DNS
// rebinding) could read its pages. So every request must name the console in its Host header,
// and a WebSocket and every state-changing request must come from the console's own page: an
// Origin header equal to http://<Host> (docs/hardening.md).
#include <set>
#include <string>
#include <vector>

namespace stepmod::web {

class HostPolicy {
 public:
  // The names: 127.0.0.1, localhost and [::1]; the --listen address (for a wildcard one, 0.0.0.0
  // or ::, every address of the machine's interfaces at start); and `extra` (--allow-host:
  // "name", "name:port", "[v6]" or "[v6]:port"), each with `port` where it gives none.
  HostPolicy(const std::string& listen, unsigned port, const std::vector<std::string>& extra);

  // Whether the Host header names this console (name:port, compared without case).
  bool host_ok(const char* host) const;
  // Whether a request from a page is the console's own: Host is one of the names and Origin is
  // exactly http://<Host>. A missing header is no.
  bool origin_ok(const char* origin, const char* host) const;
  const std::set<std::string>& hosts() const { return hosts_; }

 private:
  void add(const std::string& host, unsigned port);
  std::set<std::string> hosts_;
};

}  // namespace stepmod::web
