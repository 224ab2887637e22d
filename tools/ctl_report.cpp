#include "tools/ctl_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

#include "tools/ctl_summary.hpp"

namespace stepmod::tools::ctl {

namespace {

std::string unit_name(const ipc::Client& c, unsigned u) {
  return std::string(c.shape().unit_noun) + " " + std::to_string(u + 1);
}

std::string json_string(const std::string& s) {
  std::string o = "\"";
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') {
      o += '\\';
      o += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char b[8];
      std::snprintf(b, sizeof b, "\\u%04x", static_cast<unsigned>(ch));
      o += b;
    } else {
      o += ch;
    }
  }
  return o + "\"";
}

std::string json_strings(const std::vector<std::string>& list) {
  std::string o = "[";
  for (const std::string& s : list) {
    if (o.size() > 1) o += ',';
    o += json_string(s);
  }
  o += ']';
  return o;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::optional<Snapshot> take_snapshot(const ipc::Client& client,
                                      std::chrono::milliseconds interval) {
  Snapshot s;
  ImageWords first;
  const std::uint64_t scan0 = client.scan_counter();
  client.read_inputs(first);
  const auto t0 = std::chrono::steady_clock::now();
  std::this_thread::sleep_for(interval);
  if (client.scan_counter() == scan0 && !client.wait_scans(1, std::chrono::seconds(1))) {
    return std::nullopt;
  }
  client.read_inputs(s.in);
  const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  s.scan = client.scan_counter();
  s.health = client.read_health();
  const auto a = summarize(client.type(), first);
  const auto b = summarize(client.type(), s.in);
  for (unsigned u = 0; u < b.size(); ++u) {
    s.speed.push_back(dt > 0 ? std::fabs(static_cast<double>(b[u].position - a[u].position)) / dt
                             : 0.0);
    s.reasons.push_back(client.read_reason(u));
  }
  return s;
}

std::string brief_text(const std::string& name, const ipc::Client& client, const Snapshot& s) {
  const auto axes = summarize(client.type(), s.in);
  std::string out;
  for (unsigned u = 0; u < axes.size(); ++u) {
    const AxisSummary& a = axes[u];
    char line[160];
    std::snprintf(line, sizeof line, "%s %u %s: %-13s position %-11lld speed %-8.0f", name.c_str(),
                  static_cast<unsigned>(client.type()), unit_name(client, u).c_str(),
                  a.state().c_str(), static_cast<long long>(a.position), s.speed[u]);
    out += line;
    const std::string errors = a.error_names();
    out += errors.empty() ? "errors: none" : "errors: " + errors;
    // The reason of a bit that is still set (an older reason belongs to a cleared bit).
    const unsigned list = s.reasons[u].item / 100u % 100u;
    if (s.reasons[u].seq != 0 && a.has_list(list)) out += " (" + reason_text(s.reasons[u]) + ")";
    out += "\n";
  }
  if (s.health.flags != 0)
    out += name + " health: " + ipc::health_flag_names(s.health.flags) + "\n";
  return out;
}

std::string json_text(const std::string& name, const ipc::Client& client, const Snapshot& s) {
  const auto axes = summarize(client.type(), s.in);
  std::string o = "{\"schema\":" + std::to_string(kStatusJsonSchema) + ",\"module\":";
  o += json_string(name);
  o += ",\"type\":" + std::to_string(static_cast<unsigned>(client.type()));
  o += ",\"scan\":" + std::to_string(s.scan);
  o += ",\"health\":{\"flags\":" + std::to_string(s.health.flags);
  o += ",\"names\":" + json_strings(ipc::health_flag_list(s.health.flags));
  o += ",\"late_faults\":" + std::to_string(s.health.late_faults);
  o += "},\"axes\":[";
  for (unsigned u = 0; u < axes.size(); ++u) {
    const AxisSummary& a = axes[u];
    char head[160];
    std::snprintf(head, sizeof head,
                  "%s{\"unit\":%u,\"position\":%lld,\"speed\":%.0f,\"reason_seq\":%u,"
                  "\"reason_item\":%u,",
                  u ? "," : "", u + 1, static_cast<long long>(a.position), s.speed[u],
                  s.reasons[u].seq, s.reasons[u].item);
    o += head;
    o += "\"state\":" + json_string(a.state());
    o += ",\"errors\":" + json_strings(a.error_list());
    o += ",\"reason\":" + json_string(reason_text(s.reasons[u]));
    o += "}";
  }
  o += "]}\n";
  return o;
}

std::string json_error_text(const std::string& name, const std::string& error) {
  return "{\"schema\":" + std::to_string(kStatusJsonSchema) + ",\"module\":" + json_string(name) +
         ",\"error\":" + json_string(error) + "}\n";
}

std::string reason_lines(const ipc::Client& client) {
  std::string out;
  for (unsigned u = 0; u < client.shape().axes; ++u) {
    const stepmod_reason_t r = client.read_reason(u);
    if (r.seq != 0) out += unit_name(client, u) + " last error reason: " + reason_text(r) + "\n";
  }
  return out;
}

std::string closest_command(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_d = 3;  // at most two edits away
  for (const std::string& n : names) {
    const std::size_t d = edit_distance(word, n);
    if (d < best_d || (d == best_d && !best.empty() && n.size() < best.size())) {
      if (d < best_d) best_d = d;
      best = n;
    }
  }
  // One edit for short words, two from four letters on ("moov" -> "move").
  return best_d <= (word.size() <= 3 ? 1u : 2u) ? best : std::string();
}

}  // namespace stepmod::tools::ctl
