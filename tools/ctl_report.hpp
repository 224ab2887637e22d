#pragma once
// stepmodctl's compact forms: `status --brief` / `watch --brief` (one line per axis: state,
// position, speed, errors and the module's reason) and `status --json`; and the suggestion for
// a mistyped sub-command.
#include <optional>
#include <string>
#include <vector>

#include "ipc/client.hpp"

namespace stepmod::tools::ctl {

// Two readings of the image `interval` apart: the speed is the position change over it.
struct Snapshot {
  std::uint64_t scan = 0;
  ImageWords in;
  std::vector<double> speed;  // steps/s per axis (0 when not measured)
  ipc::Health health;
  std::vector<stepmod_reason_t> reasons;
};
// nullopt: the daemon did not scan within `interval` + 1 s (stopped, hung).
std::optional<Snapshot> take_snapshot(const ipc::Client& client,
                                      std::chrono::milliseconds interval);

std::string brief_text(const std::string& name, const ipc::Client& client, const Snapshot& s);
// `status --json`: one object whose shape is docs/status.schema.json (docs/interface.md 1),
// versioned by its "schema" member; a change of a member's name, type or meaning raises it.
inline constexpr unsigned kStatusJsonSchema = 1;
std::string json_text(const std::string& name, const ipc::Client& client, const Snapshot& s);
// The same schema's error object, printed instead when the module cannot be read (exit 3).
std::string json_error_text(const std::string& name, const std::string& error);
// The reason lines under the full status: "axis 1 reason: 3601-CE-05: ..." (none: empty).
std::string reason_lines(const ipc::Client& client);

// The closest of `names` to `word` when it is close enough to be a typo ("moov" -> "move"),
// else empty.
std::string closest_command(const std::string& word, const std::vector<std::string>& names);

}  // namespace stepmod::tools::ctl
