#pragma once
// The socket of a civetweb connection. civetweb 1.15 does not hand it out, and the console needs
// it for two things civetweb cannot do: read a WebSocket's frames itself (every limit checked
// before a byte is buffered, web/ws_hub.hpp) and close a connection that holds a worker thread
// without sending its request (web/http_guard.hpp). A TCP connection is named by its peer's
// address and port and its local port: the descriptor whose getpeername()/getsockname() match
// is the connection's. The descriptor stays the connection's for as long as civetweb has not
// closed it: callers use it only before civetweb's close callback for that connection returns.
#include <string>

namespace stepmod::web {

// The descriptor, or -1 when no socket matches, or more than one does (then the connection is
// not told apart: the caller goes without).
int socket_of(const std::string& peer_addr, unsigned peer_port, unsigned local_port);

}  // namespace stepmod::web
