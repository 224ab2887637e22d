#include "fieldbus/enip/message_router.hpp"

#include <array>

#include "fieldbus/enip/objects.hpp"

namespace stepmod::enip {

std::uint8_t parse_mr_request(std::span<const std::uint8_t> message, MrRequest& out) noexcept {
  Reader r(message);
  out = MrRequest{};
  out.service = r.u8();
  const std::size_t words = r.u8();
  const auto path = r.bytes(2 * words);
  if (!r.ok()) return cip_general::kNotEnoughData;
  if (!parse_request_path(path, out.path)) return cip_general::kPathSegmentError;
  out.data = r.rest();
  return cip_general::kSuccess;
}

namespace {
// Unconnected_Send's route to us: none, or port 1 (the backplane npm clients and Logix name)
// with link 0.
bool routes_to_us(std::span<const std::uint8_t> route) noexcept {
  if (route.empty()) return true;
  EpathReader reader(route);
  Segment s;
  if (!reader.next(s) || s.kind != SegmentKind::kPort) return false;
  const bool us = s.value == 1 && s.data.size() == 1 && s.data[0] == 0;
  return us && !reader.next(s) && !reader.failed();
}

void route(std::span<const std::uint8_t> message, RouterContext& ctx, Writer& w,
           bool embedded) noexcept;

// timeout tick u8, ticks u8, message size u16, message, pad to even, route size u8 (words),
// reserved u8, route.
void unconnected_send(const MrRequest& req, RouterContext& ctx, Writer& w) noexcept {
  Reader r(req.data);
  r.skip(2);
  const std::size_t size = r.u16();
  const auto embedded = r.bytes(size);
  if (size % 2 != 0) r.skip(1);
  const std::size_t route_words = r.u8();
  r.skip(1);
  const auto route_path = r.bytes(2 * route_words);
  if (!r.ok() || r.remaining() != 0) {
    put_reply_status(
        w, req.service,
        CipStatus::general_only(r.ok() ? cip_general::kTooMuchData : cip_general::kNotEnoughData));
    return;
  }
  if (!routes_to_us(route_path)) {
    put_reply_status(w, req.service, CipStatus::connection(cm_status::kPortNotAvailable));
    w.u8(static_cast<std::uint8_t>(route_words));  // remaining path size: none was used
    return;
  }
  route(embedded, ctx, w, true);  // the embedded request's reply is the reply
}

void route(std::span<const std::uint8_t> message, RouterContext& ctx, Writer& w,
           bool embedded) noexcept {
  MrRequest req;
  const std::uint8_t general = parse_mr_request(message, req);
  if (general != cip_general::kSuccess) {
    put_reply_status(w, message.empty() ? 0 : message[0], CipStatus::general_only(general));
    return;
  }
  // One level of Unconnected_Send: an embedded one would route further, which we do not.
  if (req.path.class_id == kConnectionManagerClass && req.service == cm_service::kUnconnectedSend &&
      !embedded) {
    unconnected_send(req, ctx, w);
    return;
  }
  std::array<std::uint8_t, kMaxReplyBytes> data{};
  Writer dw(data);
  CipStatus st = dispatch(req, ctx, dw);
  if (!dw.ok()) st = CipStatus::general_only(cip_general::kReplyDataTooLarge);
  put_reply_status(w, req.service, st);
  if (dw.ok()) w.bytes(dw.written());
}
}  // namespace

void route_message(std::span<const std::uint8_t> message, RouterContext& ctx, Writer& w) noexcept {
  route(message, ctx, w, false);
}

}  // namespace stepmod::enip
