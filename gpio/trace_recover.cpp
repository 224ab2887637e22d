#include "gpio/trace_recover.hpp"

#include <memory>
#include <stdexcept>

#include "gpio/trace_file.hpp"
#include "gpio/trace_spool.hpp"
#include "gpio/vcd_trace.hpp"

namespace stepmod::gpio {

RecoverResult recover_trace(const std::vector<std::string>& spools, const std::string& vcd_path) {
  if (spools.empty()) throw std::runtime_error("trace recover: no spool given");
  std::vector<std::unique_ptr<SpoolReader>> files;
  for (const std::string& s : spools) {
    files.push_back(std::make_unique<SpoolReader>(s));
    if (!(files.back()->info() == files.front()->info())) {
      throw std::runtime_error("trace spool '" + s + "': not from the same run as '" +
                               spools.front() + "' (its #0 time or wires differ)");
    }
  }
  std::vector<std::unique_ptr<OrderedReader>> ordered;
  std::vector<OrderedReader*> readers;
  for (auto& f : files) {
    ordered.push_back(std::make_unique<OrderedReader>(*f));
    readers.push_back(ordered.back().get());
  }
  const SpoolInfo& info = files.front()->info();
  // The loss marker is declared: the end of the run is missing, and the daemon may have marked
  // ring overflows in the spools.
  refuse_special_file(vcd_path, "trace file");
  VcdTrace vcd(vcd_path, info.wires, info.start, true);
  try {
    write_merged(readers, vcd);
    const Nanos t = vcd.last_time();
    vcd.record(TraceRecord{t + 1, 0, 0, 1, kLossMarker});
    vcd.record(TraceRecord{t + 2, 0, 0, 0, kLossMarker});
    vcd.comment(
        "stepmod: TRACE INCOMPLETE: recovered from the spools of a daemon that did not "
        "stop; what it had not yet written (its last ~100 ms) is missing after the "
        "last pulse of the wire " +
        std::string(kLossMarkerWire) + "; late records " + std::to_string(vcd.late()) +
        "; unknown lines " + std::to_string(vcd.unknown()));
    vcd.close(t + 2);
  } catch (...) {
    vcd.abandon();
    throw;
  }
  return RecoverResult{vcd.changes() - 2, vcd.late()};
}

}  // namespace stepmod::gpio
