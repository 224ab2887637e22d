#pragma once
// Turns the spools a daemon left behind (killed, or stopped on a full disk) into a VCD:
// `stepmodctl trace recover --output FILE.vcd SPOOL...`.
#include <cstdint>
#include <string>
#include <vector>

namespace stepmod::gpio {

struct RecoverResult {
  std::uint64_t changes = 0;  // line changes written to the VCD
  std::uint64_t late = 0;     // written later than their time (beyond the reorder window)
};

// Reads every spool (regular files with a stepmod spool header, all from the same run: same #0
// and wires), merges their records in time order and writes `vcd_path` (created new and renamed
// into place, like the daemon's). The VCD says TRACE INCOMPLETE: a daemon that did not stop lost
// the records it had not yet written (up to TraceWriter::kFlushPeriod plus its rings). Throws
// std::runtime_error naming the file on any problem; `vcd_path` is then left as it was.
RecoverResult recover_trace(const std::vector<std::string>& spools, const std::string& vcd_path);

}  // namespace stepmod::gpio
