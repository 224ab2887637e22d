#include "fieldbus/enip/connection_table.hpp"

#include <algorithm>
#include <limits>

#include "fieldbus/enip/cpf.hpp"
#include "fieldbus/enip/identity.hpp"

namespace stepmod::enip {

namespace {
constexpr std::int64_t kNsPerUs = 1000;

// The connection id of an O→T packet, read before the packet is judged against its connection.
bool peek_connection_id(std::span<const std::uint8_t> datagram, std::uint32_t& id) noexcept {
  Cpf cpf;
  if (parse_cpf(datagram, cpf) != CpfParse::kOk ||
      cpf.items[0].type != cpf_item::kSequencedAddress) {
    return false;
  }
  Reader r(cpf.items[0].data);
  id = r.u32();
  return r.ok();
}
}  // namespace

bool IoConnections::owner_open() const noexcept {
  for (const IoConnection& c : slots_) {
    if (c.open && c.kind == ConnectionKind::kExclusiveOwner) return true;
  }
  return false;
}

bool IoConnections::triad_open(const ConnectionTriad& triad) const noexcept {
  for (const IoConnection& c : slots_) {
    if (c.open && c.triad == triad) return true;
  }
  return false;
}

IoConnection* IoConnections::find_ot(std::uint32_t ot_id) noexcept {
  for (IoConnection& c : slots_) {
    if (c.open && c.ot_id == ot_id) return &c;
  }
  return nullptr;
}

// Ids that a peer cannot guess from the last one (fieldbus/enip/xorshift32.hpp); never 0, never
// one in use.
std::uint32_t IoConnections::new_id() noexcept {
  for (;;) {
    const std::uint32_t id = ids_.next();
    if (id != 0 && find_ot(id) == nullptr) return id;
  }
}

CipStatus IoConnections::open(const ForwardOpen& fo, const AcceptedOpen& accepted,
                              const RequestOrigin& origin, std::uint32_t& ot_id) noexcept {
  OpenConnections state;
  state.triad_open = triad_open(fo.triad);
  for (const IoConnection& c : slots_) {
    state.owner = state.owner || (c.open && c.kind == ConnectionKind::kExclusiveOwner);
    state.input_only = state.input_only || (c.open && c.kind == ConnectionKind::kInputOnly);
    state.free_slots += c.open ? 0 : 1;
  }
  if (CipStatus st = check_ownership(accepted.kind, state); !st.ok()) return st;
  for (IoConnection& c : slots_) {
    if (c.open) continue;
    const bool owner = accepted.kind == ConnectionKind::kExclusiveOwner;
    c = IoConnection{};
    c.open = true;
    c.kind = accepted.kind;
    c.triad = fo.triad;
    c.ot_id = new_id();
    c.to_id = fo.to_id;
    c.originator_ip = origin.ip;
    c.ot_shape = IoShape{owner, owner ? static_cast<std::size_t>(fo.ot.size - 6) : 0};
    c.to_rpi_ns = static_cast<std::int64_t>(fo.to_rpi_us) * kNsPerUs;
    c.timeout_ns = static_cast<std::int64_t>(accepted.timeout_us) * kNsPerUs;
    c.last_ot_ns = origin.now_ns;
    c.next_to_ns = origin.now_ns;  // the first T→O at once: st-ethernet-ip waits for it
    ot_id = c.ot_id;
    return {};
  }
  return CipStatus::connection(cm_status::kOutOfConnections);  // not reached: slots were free
}

void IoConnections::close_slot(IoConnection& c) noexcept {
  if (c.open && c.kind == ConnectionKind::kExclusiveOwner) left_run_ = true;
  c = IoConnection{};
}

// Listen-only connections listen to an owner's or an input-only connection's data.
void IoConnections::close_orphaned_listeners() noexcept {
  for (const IoConnection& c : slots_) {
    if (c.open && c.kind != ConnectionKind::kListenOnly) return;
  }
  for (IoConnection& c : slots_) close_slot(c);
}

CipStatus IoConnections::close(const ConnectionTriad& triad) noexcept {
  for (IoConnection& c : slots_) {
    if (!c.open || !(c.triad == triad)) continue;
    close_slot(c);
    close_orphaned_listeners();
    return {};
  }
  return CipStatus::connection(cm_status::kConnectionNotFound);
}

OtResult IoConnections::on_o_to_t(std::uint32_t from_ip, std::span<const std::uint8_t> datagram,
                                  std::int64_t now_ns) noexcept {
  std::uint32_t id = 0;
  if (!peek_connection_id(datagram, id)) return {};
  IoConnection* c = find_ot(id);
  if (c == nullptr || c->originator_ip != from_ip) return {};
  IoPacket p;
  if (parse_o_to_t(datagram, c->ot_shape, p) != IoParse::kOk) return {};
  if (c->ot_seen && !sequence_newer(p.encap_sequence, c->ot_encap_sequence)) return {};
  const bool new_data = !c->ot_seen || p.cip_sequence != c->ot_cip_sequence;
  c->ot_seen = true;
  c->ot_encap_sequence = p.encap_sequence;
  c->ot_cip_sequence = p.cip_sequence;
  c->last_ot_ns = now_ns;
  if (c->kind != ConnectionKind::kExclusiveOwner) return {OtOutcome::kRefresh, {}};
  c->run = p.run;
  if (!p.run) {
    left_run_ = true;
    return {OtOutcome::kIdle, {}};
  }
  left_run_ = false;
  return new_data ? OtResult{OtOutcome::kRunWrite, p.data} : OtResult{OtOutcome::kRunRepeat, {}};
}

bool IoConnections::expire(std::int64_t now_ns) noexcept {
  bool owner_expired = false;
  bool any = false;
  for (IoConnection& c : slots_) {
    if (!c.open || now_ns - c.last_ot_ns < c.timeout_ns) continue;
    owner_expired = owner_expired || c.kind == ConnectionKind::kExclusiveOwner;
    close_slot(c);
    any = true;
  }
  if (any) close_orphaned_listeners();
  return owner_expired;
}

std::int64_t IoConnections::next_due_ns() const noexcept {
  std::int64_t due = std::numeric_limits<std::int64_t>::max();
  for (const IoConnection& c : slots_) {
    if (!c.open) continue;
    due = std::min({due, c.next_to_ns, c.last_ot_ns + c.timeout_ns});
  }
  return due;
}

void IoConnections::advance(IoConnection& c, std::int64_t now_ns) noexcept {
  ++c.to_encap_sequence;
  c.next_to_ns += c.to_rpi_ns;
  // Late by more than an interval (a loaded machine): the schedule restarts from now rather
  // than sending a burst to catch up.
  if (c.next_to_ns <= now_ns) c.next_to_ns = now_ns + c.to_rpi_ns;
}

std::uint16_t IoConnections::identity_status() const noexcept {
  unsigned open = 0;
  bool any_run = false;
  for (const IoConnection& c : slots_) {
    open += c.open ? 1 : 0;
    any_run = any_run || (c.open && c.run);
  }
  return identity_status_word(owner_open(), open, any_run);
}

}  // namespace stepmod::enip
