#include "systemd/notify.hpp"

#ifdef STEPMOD_HAVE_LIBSYSTEMD
#include <systemd/sd-daemon.h>
#endif

namespace stepmod::systemd {

namespace {
void send([[maybe_unused]] const std::string& state) {
#ifdef STEPMOD_HAVE_LIBSYSTEMD
  sd_notify(0, state.c_str());
#endif
}
}  // namespace

void notify_ready(const std::string& status) {
  send("READY=1\nSTATUS=" + status);
}
void notify_stopping() {
  send("STOPPING=1");
}
void notify_status(const std::string& status) {
  send("STATUS=" + status);
}

}  // namespace stepmod::systemd
