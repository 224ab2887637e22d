#include "gpio/vcd_trace.hpp"

#include "core/version.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cstring>
#include <ctime>
#include <stdexcept>

#include "gpio/trace_file.hpp"

namespace stepmod::gpio {
namespace {

constexpr int kLineSlots = 16;

// VCD identifier codes: printable ASCII '!'..'~', base 94.
std::string vcd_id(std::size_t n) {
  std::string s;
  do {
    s.push_back(static_cast<char>('!' + n % 94));
    n /= 94;
  } while (n > 0);
  return s;
}

}  // namespace

TraceWire enable_trace_wire(unsigned axis, bool active_low) {
  return {static_cast<std::uint8_t>(axis), false, kEnableTraceLine, false, active_low};
}

TraceWire charge_pump_trace_wire(unsigned first_axis, bool active_low) {
  return {static_cast<std::uint8_t>(first_axis), false, kChargePumpTraceLine, false, active_low};
}

std::string wire_name(const TraceWire& w, std::span<const std::string> axis_names) {
  if (!w.is_input && w.line == kChargePumpTraceLine) {
    constexpr std::string_view kPump = "charge_pump";
    if (w.axis < axis_names.size()) {
      const std::string& a = axis_names[w.axis];  // "x.axis1": the module's name before the dot
      return a.substr(0, a.rfind('.') + 1) + std::string(kPump);
    }
    if (w.axis == 0) return std::string(kPump);
    return "axis" + std::to_string(unsigned{w.axis} + 1) + "." + std::string(kPump);
  }
  const std::string_view key = w.is_input ? input_key(static_cast<InputLine>(w.line))
                               : w.line == kEnableTraceLine
                                   ? std::string_view("enable")
                                   : output_key(static_cast<OutputLine>(w.line));
  if (w.axis < axis_names.size()) return axis_names[w.axis] + "." + std::string(key);
  return "axis" + std::to_string(unsigned{w.axis} + 1) + "." + std::string(key);
}

std::vector<TraceWire> trace_wires(Backend& backend) {
  std::vector<TraceWire> wires;
  for (unsigned a = 0; a < backend.axes(); ++a) {
    for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
      if (backend.has_output(a, static_cast<OutputLine>(l))) {
        wires.push_back({static_cast<std::uint8_t>(a), false, static_cast<std::uint8_t>(l), false,
                         backend.line_options(a, false, l).active_low});
      }
    }
    for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
      const auto line = static_cast<InputLine>(l);
      if (backend.has_input(a, line)) {
        wires.push_back({static_cast<std::uint8_t>(a), true, static_cast<std::uint8_t>(l),
                         backend.read(a, line), backend.line_options(a, true, l).active_low});
      }
    }
  }
  return wires;
}

// ---- VcdTrace -----------------------------------------------------------------------------------

VcdTrace::VcdTrace(const std::string& path, std::span<const TraceWire> wires, Nanos start,
                   bool loss_marker, std::vector<std::string> axis_names)
    : path_(path),
      start_(start),
      wires_(wires.begin(), wires.end()),
      axis_names_(std::move(axis_names)) {
  file_ = create_file_beside(path, "trace file");
  // The stream writes through its own descriptor; file_.fd stays open after fclose(), so that
  // close() can name an unnamed (O_TMPFILE) file once the stream's errors are known.
  const int stream_fd = ::fcntl(file_.fd, F_DUPFD_CLOEXEC, 0);
  f_ = stream_fd >= 0 ? ::fdopen(stream_fd, "w") : nullptr;
  if (f_ == nullptr) {
    const std::string why = std::strerror(errno);
    if (stream_fd >= 0) ::close(stream_fd);
    discard(file_);
    throw std::runtime_error("trace file '" + path + "': " + why);
  }
  unsigned max_axis = 0;
  for (const TraceWire& w : wires_) max_axis = std::max<unsigned>(max_axis, w.axis);
  index_.assign((max_axis + 1) * 2 * kLineSlots, -1);
  for (std::size_t i = 0; i < wires_.size(); ++i) {
    const TraceWire& w = wires_[i];
    index_[(w.axis * 2u + (w.is_input ? 1u : 0u)) * kLineSlots + w.line] = static_cast<int>(i);
    ids_.push_back(vcd_id(i));
    levels_.push_back(w.initial != w.active_low ? 1 : 0);
  }

  char date[64] = "";
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  if (localtime_r(&now, &tm) != nullptr) std::strftime(date, sizeof date, "%Y-%m-%d %H:%M:%S", &tm);
  std::fprintf(
      f_, "$date %s $end\n$version stepmod " STEPMOD_VERSION " $end\n$timescale 1 ns $end\n", date);
  // The wires keep the names of docs/interface.md section 5 verbatim (axis1.step, ...), inside one
  // top-level scope, which some readers require.
  std::fprintf(f_, "$scope module stepmod $end\n");
  for (std::size_t i = 0; i < wires_.size(); ++i) {
    std::fprintf(f_, "$var wire 1 %s %s $end\n", ids_[i].c_str(),
                 wire_name(wires_[i], axis_names_).c_str());
  }
  if (loss_marker) {
    marker_ = static_cast<int>(ids_.size());
    ids_.push_back(vcd_id(ids_.size()));
    levels_.push_back(0);
    std::fprintf(f_, "$var wire 1 %s %s $end\n", ids_.back().c_str(), kLossMarkerWire);
  }
  std::fprintf(f_, "$upscope $end\n$enddefinitions $end\n#0\n$dumpvars\n");
  for (std::size_t i = 0; i < ids_.size(); ++i) {
    std::fprintf(f_, "%c%s\n", levels_[i] ? '1' : '0', ids_[i].c_str());
  }
  std::fprintf(f_, "$end\n");
}

VcdTrace::~VcdTrace() {
  if (f_ == nullptr) return;
  try {
    close(start_ + last_);
  } catch (...) {
    // close() removed the failed file; a destructor cannot report it.
  }
}

void VcdTrace::abandon() noexcept {
  if (f_ == nullptr) return;
  std::fclose(f_);
  f_ = nullptr;
  discard(file_);
}

int VcdTrace::wire_index(const TraceRecord& r) const noexcept {
  if (r.is_input == kLossMarker) return marker_;
  if (r.line >= kLineSlots) return -1;
  const std::size_t k = (r.axis * 2u + (r.is_input ? 1u : 0u)) * kLineSlots + r.line;
  return k < index_.size() ? index_[k] : -1;
}

void VcdTrace::record(const TraceRecord& r) {
  if (f_ == nullptr) return;
  const int i = wire_index(r);
  if (i < 0) {
    ++unknown_;
    return;
  }
  // Wire level: the logical one inverted on an active-low line (the loss marker is not a line).
  const bool inverted = r.is_input != kLossMarker && wires_[static_cast<std::size_t>(i)].active_low;
  const std::uint8_t level = r.level != inverted ? 1 : 0;
  if (levels_[static_cast<std::size_t>(i)] == level) return;
  levels_[static_cast<std::size_t>(i)] = level;
  Nanos t = r.t - start_;
  if (t < 0) t = 0;  // stamped before the start (initial read races): shown at #0
  if (t < last_) {
    ++late_;
    t = last_;
  }
  if (t != last_) {
    std::fprintf(f_, "#%" PRId64 "\n", static_cast<std::int64_t>(t));
    last_ = t;
  }
  std::fprintf(f_, "%c%s\n", level ? '1' : '0', ids_[static_cast<std::size_t>(i)].c_str());
  ++changes_;
}

void VcdTrace::comment(std::string_view text) {
  if (f_ == nullptr) return;
  std::fprintf(f_, "$comment %.*s $end\n", static_cast<int>(text.size()), text.data());
}

void VcdTrace::flush() {
  if (f_ != nullptr) std::fflush(f_);
}

void VcdTrace::close(Nanos end) {
  if (f_ == nullptr) return;
  const Nanos t = end - start_;
  if (t > last_) {
    std::fprintf(f_, "#%" PRId64 "\n", static_cast<std::int64_t>(t));
    last_ = t;
  }
  const bool flushed = std::fflush(f_) == 0;
  const int flush_errno = errno;
  const bool bad = !flushed || std::ferror(f_) != 0;
  const int rc = std::fclose(f_);
  const int close_errno = errno;
  f_ = nullptr;
  if (bad || rc != 0) {
    discard(file_);
    throw std::runtime_error("trace file '" + path_ + "': write failed: " +
                             std::strerror(!flushed ? flush_errno : close_errno));
  }
  // Replaces the name, never what a link there points to.
  put_in_place(file_, path_, "trace file");
}

void write_merged(std::span<OrderedReader* const> readers, VcdTrace& vcd) {
  std::vector<const TraceRecord*> heads;
  heads.reserve(readers.size());
  for (OrderedReader* r : readers) heads.push_back(r->next());
  for (;;) {
    std::size_t best = heads.size();
    for (std::size_t k = 0; k < heads.size(); ++k) {
      if (heads[k] != nullptr && (best == heads.size() || heads[k]->t < heads[best]->t)) best = k;
    }
    if (best == heads.size()) return;
    vcd.record(*heads[best]);
    heads[best] = readers[best]->next();
  }
}

// ---- TraceWriter --------------------------------------------------------------------------------

namespace {
// The trace file's path, refused at the start if something other than a regular file is there.
std::string checked_path(const std::string& path) {
  refuse_special_file(path, "trace file");
  return path;
}

SpoolInfo spool_info(Nanos start, std::span<const TraceWire> wires) {
  return SpoolInfo{start, std::vector<TraceWire>(wires.begin(), wires.end())};
}
}  // namespace

TraceWriter::TraceWriter(const std::string& path, std::span<const TraceWire> wires, Nanos start,
                         SpscRing<TraceRecord>& outputs, SpscRing<TraceRecord>& inputs,
                         Nanos period)
    : path_(checked_path(path)),
      wires_(wires.begin(), wires.end()),
      start_(start),
      outputs_(outputs),
      inputs_(inputs),
      period_(period),
      out_spool_(path + ".out.spool", spool_info(start, wires)),
      in_spool_(path + ".in.spool", spool_info(start, wires)) {}

TraceWriter::~TraceWriter() {
  try {
    stop();
  } catch (...) {
    // A destructor cannot report; stop() was the place to see the error.
  }
}

void TraceWriter::start(int fifo_priority) {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this, fifo_priority] {
    if (fifo_priority > 0) {
      sched_param sp{};
      sp.sched_priority = fifo_priority;
      fifo_.store(pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp) == 0,
                  std::memory_order_release);
    }
    run();
  });
  pthread_setname_np(thread_.native_handle(), "stepmod-trace");
}

void TraceWriter::drain(SpscRing<TraceRecord>& ring, TraceSpool& spool,
                        const std::atomic<std::uint64_t>* lost, std::uint64_t& lost_seen,
                        Nanos& last_t) {
  // The loss counter first: records lost before this read were lost after everything now in
  // the ring was pushed, so the marker goes after the last record drained below.
  const std::uint64_t lost_now = lost != nullptr ? lost->load(std::memory_order_acquire) : 0;
  TraceRecord r;
  std::uint64_t n = 0;
  while (ring.try_pop(r)) {
    spool.append(r);
    last_t = r.t;
    ++n;
  }
  if (lost_now != lost_seen) {
    lost_seen = lost_now;
    // A pulse on the marker wire, 1 ns long, right after the last record kept.
    spool.append(TraceRecord{last_t + 1, 0, 0, 1, kLossMarker});
    spool.append(TraceRecord{last_t + 2, 0, 0, 0, kLossMarker});
    ++markers_;
  }
  spooled_.store(spooled_.load(std::memory_order_relaxed) + n, std::memory_order_relaxed);
}

void TraceWriter::step() {
  drain(outputs_, out_spool_, lost_outputs_, lost_outputs_seen_, last_output_t_);
  drain(inputs_, in_spool_, lost_inputs_, lost_inputs_seen_, last_input_t_);
}

void TraceWriter::run() {
  Nanos flushed = monotonic_now();
  while (running_.load(std::memory_order_acquire)) {
    const Nanos now = monotonic_now();
    step();
    // What a killed daemon leaves in its spools: all but the last kFlushPeriod.
    if (now - flushed >= kFlushPeriod) {
      out_spool_.flush();
      in_spool_.flush();
      flushed = now;
    }
    sleep_until(now + period_);
  }
}

TraceOutcome TraceWriter::stop(std::uint64_t dropped_outputs, std::uint64_t dropped_inputs) {
  if (closed_) return outcome_;
  running_.store(false, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
  closed_ = true;
  step();
  outcome_ = finish(dropped_outputs, dropped_inputs);
  return outcome_;
}

// The VCD from the spools; on failure the spools are kept beside the VCD's path.
TraceOutcome TraceWriter::finish(std::uint64_t dropped_outputs, std::uint64_t dropped_inputs) {
  TraceOutcome o;
  out_spool_.flush();
  in_spool_.flush();
  try {
    write_vcd(dropped_outputs, dropped_inputs);
  } catch (const std::exception& e) {
    out_spool_.keep();
    in_spool_.keep();
    o.complete = false;
    o.vcd_written = false;
    o.problem = std::string(e.what()) + "; the spools " + out_spool_.path() + " and " +
                in_spool_.path() +
                " are kept (make room, then: stepmodctl trace recover --output " + path_ + " " +
                out_spool_.path() + " " + in_spool_.path() + ")";
    return o;
  }
  out_spool_.remove();
  in_spool_.remove();
  if (failed()) {
    const int err = out_spool_.failed() ? out_spool_.error() : in_spool_.error();
    o.complete = false;
    o.problem = "trace spool write failed (" + std::string(std::strerror(err)) + "): the VCD " +
                path_ + " is marked TRACE INCOMPLETE";
  } else if (dropped_outputs + dropped_inputs > 0 || markers_ > 0) {
    o.complete = false;
    o.problem = "trace records lost (ring full): the VCD " + path_ + " is marked TRACE INCOMPLETE";
  }
  return o;
}

void TraceWriter::write_vcd(std::uint64_t dropped_outputs, std::uint64_t dropped_inputs) {
  const bool spool_failed = failed();
  const bool lost = dropped_outputs + dropped_inputs > 0 || markers_ > 0 || spool_failed;
  vcd_ = std::make_unique<VcdTrace>(path_, wires_, start_, lost, axis_names_);
  try {
    // Outputs first on equal times.
    SpoolReader out_file(out_spool_.fd(), out_spool_.path());
    SpoolReader in_file(in_spool_.fd(), in_spool_.path());
    OrderedReader outs(out_file);
    OrderedReader ins(in_file);
    OrderedReader* const readers[] = {&outs, &ins};
    write_merged(readers, *vcd_);
    if (lost && markers_ == 0) {
      // Counted by a producer but never seen by the thread, or a spool that stopped being
      // written: mark the end of what there is, so the wire still shows it.
      const Nanos t = vcd_->last_time();
      vcd_->record(TraceRecord{t + 1, 0, 0, 1, kLossMarker});
      vcd_->record(TraceRecord{t + 2, 0, 0, 0, kLossMarker});
    }
    // Always written, zeros included, so that a script can tell a complete trace from one whose
    // rings overflowed without guessing.
    vcd_->comment("stepmod: dropped records: outputs " + std::to_string(dropped_outputs) +
                  ", inputs " + std::to_string(dropped_inputs) + "; late records " +
                  std::to_string(vcd_->late()) + "; unknown lines " +
                  std::to_string(vcd_->unknown()));
    if (spool_failed) {
      vcd_->comment(
          "stepmod: TRACE INCOMPLETE: a trace spool could not be written (disk full?); "
          "the records after the wire " +
          std::string(kLossMarkerWire) + " pulses are missing");
    } else if (lost) {
      vcd_->comment(
          "stepmod: TRACE INCOMPLETE: " + std::to_string(dropped_outputs + dropped_inputs) +
          " records were lost (a trace ring was full); the wire " + kLossMarkerWire +
          " pulses where");
    }
    vcd_->close(monotonic_now());
  } catch (...) {
    vcd_->abandon();
    throw;
  }
}

}  // namespace stepmod::gpio
