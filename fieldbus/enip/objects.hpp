#pragma once
// The object table behind the message router: which (class, service) pairs are served and by
// which handler (Identity 0x01, Assembly 0x04, Connection Manager 0x06, TCP/IP Interface 0xF5,
// Ethernet Link 0xF6). A handler writes its
// reply data to `data` and returns the status; the router writes the status, then the data.
#include <cstdint>
#include <span>

#include "fieldbus/enip/cip_status.hpp"
#include "fieldbus/enip/message_router.hpp"
#include "fieldbus/enip/wire.hpp"

namespace stepmod::enip {

using ServiceHandler = CipStatus (*)(const MrRequest& req, RouterContext& ctx, Writer& data);

struct ServiceRow {
  std::uint32_t class_id;
  std::uint8_t service;
  ServiceHandler handler;
};

std::span<const ServiceRow> service_table() noexcept;

// The handler of `req`, or the status of its absence: 0x05 (no such class) or 0x08 (the class
// has no such service).
CipStatus dispatch(const MrRequest& req, RouterContext& ctx, Writer& data) noexcept;

}  // namespace stepmod::enip
