#pragma once
// Readiness and status notifications to systemd (Type=notify units). Without NOTIFY_SOCKET (not
// started by systemd) every call is a no-op.
#include <string>

namespace stepmod::systemd {

void notify_ready(const std::string& status);
void notify_stopping();
void notify_status(const std::string& status);

}  // namespace stepmod::systemd
