// The VCD trace (docs/interface.md section 5): file format, spooled merge, loss marker, parse-back.
#include "gpio/vcd_trace.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "gpio/sim_backend.hpp"

namespace stepmod::gpio {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() /
          ("stepmod_gpio_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct Change {
  std::int64_t t;
  std::string name;
  int level;
  bool operator==(const Change&) const = default;
};
std::ostream& operator<<(std::ostream& o, const Change& c) {
  return o << "#" << c.t << " " << c.name << "=" << c.level;
}

// A small, strict reader of the subset of VCD the writer uses: what a script would do.
struct Parsed {
  std::string timescale;
  std::vector<std::string> names;      // declaration order
  std::map<std::string, int> initial;  // from $dumpvars at #0
  std::vector<Change> changes;         // after #0's dump
  std::vector<std::string> comments;
  bool monotonic = true;
  std::int64_t last_time = 0;
};

Parsed parse_vcd(const std::string& text) {
  Parsed p;
  std::istringstream in(text);
  std::map<std::string, std::string> id_name;
  std::string tok;
  bool defs = true, dumpvars = false;
  std::int64_t t = -1;
  while (in >> tok) {
    if (tok == "$comment") {
      std::string w, c;
      while (in >> w && w != "$end") c += (c.empty() ? "" : " ") + w;
      p.comments.push_back(c);
    } else if (defs) {
      if (tok == "$timescale") {
        std::string a, b;
        in >> a >> b;
        if (b != "$end") {
          p.timescale = a + " " + b;
          in >> b;
        } else {
          p.timescale = a;
        }
      } else if (tok == "$var") {
        std::string type, size, id, name, end;
        in >> type >> size >> id >> name >> end;
        EXPECT_EQ(type, "wire");
        EXPECT_EQ(size, "1");
        EXPECT_EQ(end, "$end");
        id_name[id] = name;
        p.names.push_back(name);
      } else if (tok == "$enddefinitions") {
        in >> tok;
        defs = false;
      }
    } else if (tok == "$dumpvars") {
      dumpvars = true;
    } else if (tok == "$end") {
      dumpvars = false;
    } else if (tok[0] == '#') {
      const std::int64_t nt = std::stoll(tok.substr(1));
      if (nt < t) p.monotonic = false;
      t = nt;
      p.last_time = t;
    } else if (tok[0] == '0' || tok[0] == '1') {
      const std::string id = tok.substr(1);
      EXPECT_TRUE(id_name.count(id)) << "undeclared id " << id;
      const int level = tok[0] - '0';
      if (dumpvars) {
        EXPECT_EQ(t, 0);
        p.initial[id_name[id]] = level;
      } else {
        p.changes.push_back({t, id_name[id], level});
      }
    } else {
      ADD_FAILURE() << "unexpected token " << tok;
    }
  }
  return p;
}

TraceRecord out_rec(Nanos t, unsigned axis, OutputLine l, bool level) {
  return {t, static_cast<std::uint8_t>(axis), static_cast<std::uint8_t>(l),
          static_cast<std::uint8_t>(level), 0};
}
TraceRecord in_rec(Nanos t, unsigned axis, InputLine l, bool level) {
  return {t, static_cast<std::uint8_t>(axis), static_cast<std::uint8_t>(l),
          static_cast<std::uint8_t>(level), 1};
}

const std::vector<TraceWire> kWires = {
    {0, false, static_cast<std::uint8_t>(OutputLine::kStep), false},
    {0, false, static_cast<std::uint8_t>(OutputLine::kDir), false},
    {0, true, static_cast<std::uint8_t>(InputLine::kHome), true},
    {1, false, static_cast<std::uint8_t>(OutputLine::kStep), false},
    {1, true, static_cast<std::uint8_t>(InputLine::kCwLimit), false},
};

TEST(GpioVcdTrace, HeaderTimescaleWireNamesAndInitialValues) {
  const std::string path = temp_path("header.vcd");
  {
    VcdTrace v(path, kWires, 1000);
    v.close(1000);
  }
  const std::string text = slurp(path);
  EXPECT_NE(text.find("$timescale 1 ns $end"), std::string::npos);
  EXPECT_NE(text.find(" axis1.step $end"), std::string::npos);
  EXPECT_NE(text.find(" axis2.cw_limit $end"), std::string::npos);
  const Parsed p = parse_vcd(text);
  EXPECT_EQ(p.timescale, "1 ns");
  const std::vector<std::string> names = {"axis1.step", "axis1.dir", "axis1.home", "axis2.step",
                                          "axis2.cw_limit"};
  EXPECT_EQ(p.names, names);
  EXPECT_EQ(p.initial.at("axis1.home"), 1);
  EXPECT_EQ(p.initial.at("axis1.step"), 0);
  EXPECT_EQ(p.initial.size(), 5u);
  EXPECT_TRUE(p.changes.empty());
  std::filesystem::remove(path);
}

TEST(GpioVcdTrace, UnopenableFileIsAnErrorNamingIt) {
  try {
    VcdTrace v("/nonexistent-dir/x.vcd", kWires, 0);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.vcd"), std::string::npos);
  }
}

TEST(GpioVcdTrace, ChangesRelativeToStartSkippingNoChangeAndUnknownLines) {
  const std::string path = temp_path("changes.vcd");
  {
    VcdTrace v(path, kWires, 1'000'000);
    v.record(out_rec(1'000'500, 0, OutputLine::kStep, true));
    v.record(out_rec(1'000'500, 0, OutputLine::kDir, false));  // no change: nothing
    v.record(in_rec(1'000'600, 0, InputLine::kHome, false));
    v.record(out_rec(1'000'700, 1, OutputLine::kGpo, true));  // not configured
    v.record(out_rec(1'000'800, 0, OutputLine::kStep, false));
    v.record(out_rec(1'000'700, 1, OutputLine::kStep, true));  // late: written at 800
    EXPECT_EQ(v.unknown(), 1u);
    EXPECT_EQ(v.late(), 1u);
    EXPECT_EQ(v.changes(), 4u);
    v.close(1'002'000);
  }
  const Parsed p = parse_vcd(slurp(path));
  const std::vector<Change> want = {{500, "axis1.step", 1},
                                    {600, "axis1.home", 0},
                                    {800, "axis1.step", 0},
                                    {800, "axis2.step", 1}};
  EXPECT_EQ(p.changes, want);
  EXPECT_TRUE(p.monotonic);
  EXPECT_EQ(p.last_time, 2000) << "the end time closes the file";
  std::filesystem::remove(path);
}

TEST(GpioTraceWriter, MergesTheTwoRingsInTimeOrderAndParsesBack) {
  const std::string path = temp_path("merge.vcd");
  SpscRing<TraceRecord> outs(64), ins(64);
  const Nanos start = 10 * kNsPerSec;
  const Nanos ms = kNsPerMs;
  {
    TraceWriter w(path, kWires, start, outs, ins);
    outs.try_push(out_rec(start + 1 * ms, 0, OutputLine::kStep, true));
    outs.try_push(out_rec(start + 3 * ms, 0, OutputLine::kStep, false));
    outs.try_push(out_rec(start + 70 * ms, 0, OutputLine::kStep, true));
    w.step();
    EXPECT_EQ(w.spooled(), 3u);
    EXPECT_TRUE(outs.empty());
    // The input ring is behind: its edge at 2 ms arrives after outputs up to 70 ms were spooled.
    ins.try_push(in_rec(start + 2 * ms, 0, InputLine::kHome, false));
    ins.try_push(in_rec(start + 60 * ms, 1, InputLine::kCwLimit, true));
    w.stop(0, 0);
  }
  const std::string text = slurp(path);
  const Parsed p = parse_vcd(text);
  const std::vector<Change> want = {{1'000'000, "axis1.step", 1},
                                    {2'000'000, "axis1.home", 0},
                                    {3'000'000, "axis1.step", 0},
                                    {60'000'000, "axis2.cw_limit", 1},
                                    {70'000'000, "axis1.step", 1}};
  EXPECT_EQ(p.changes, want);
  EXPECT_TRUE(p.monotonic);
  ASSERT_EQ(p.comments.size(), 1u);
  EXPECT_NE(p.comments[0].find("outputs 0, inputs 0"), std::string::npos);
  // A complete trace has no loss marker wire, and its spools are gone.
  EXPECT_EQ(std::count(p.names.begin(), p.names.end(), kLossMarkerWire), 0);
  EXPECT_FALSE(std::filesystem::exists(path + ".out.spool"));
  EXPECT_FALSE(std::filesystem::exists(path + ".in.spool"));
  std::filesystem::remove(path);
}

TEST(GpioTraceWriter, LostRecordsAreMarkedWhereTheyWentMissingAndInAComment) {
  const std::string path = temp_path("loss.vcd");
  SpscRing<TraceRecord> outs(4), ins(4);
  std::atomic<std::uint64_t> lost_outputs{0};
  const Nanos start = 0;
  {
    TraceWriter w(path, kWires, start, outs, ins);
    w.watch_losses(&lost_outputs, nullptr);
    // The producer fills the ring and loses two records (as the pulse thread counts them).
    std::uint64_t lost = 0;
    for (int i = 0; i < 6; ++i) {
      if (!outs.try_push(out_rec(1'000 * (i + 1), 0, OutputLine::kStep, i % 2 == 0))) ++lost;
    }
    lost_outputs.store(lost);
    ASSERT_EQ(lost, 2u);
    w.step();
    outs.try_push(out_rec(100'000, 0, OutputLine::kStep, true));
    w.stop(lost, 0);
  }
  const Parsed p = parse_vcd(slurp(path));
  ASSERT_EQ(std::count(p.names.begin(), p.names.end(), kLossMarkerWire), 1);
  // The marker pulses right after the last record kept before the loss (4 us).
  std::vector<Change> marker;
  for (const Change& c : p.changes) {
    if (c.name == kLossMarkerWire) marker.push_back(c);
  }
  ASSERT_EQ(marker.size(), 2u);
  EXPECT_EQ(marker[0], (Change{4'001, kLossMarkerWire, 1}));
  EXPECT_EQ(marker[1], (Change{4'002, kLossMarkerWire, 0}));
  ASSERT_EQ(p.comments.size(), 2u);
  EXPECT_NE(p.comments[0].find("outputs 2, inputs 0"), std::string::npos) << p.comments[0];
  EXPECT_NE(p.comments[1].find("TRACE INCOMPLETE"), std::string::npos) << p.comments[1];
  std::filesystem::remove(path);
}

TEST(GpioTraceWriter, UnwritablePathFailsAtConstructionNamingTheFile) {
  SpscRing<TraceRecord> outs(4), ins(4);
  try {
    TraceWriter w("/nonexistent-dir/x.vcd", kWires, 0, outs, ins);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.vcd"), std::string::npos);
  }
}

TEST(GpioTraceWriter, DestructorFinishesTheFileWithZeroDropCounts) {
  const std::string path = temp_path("nodrop.vcd");
  SpscRing<TraceRecord> outs(8), ins(8);
  {
    TraceWriter w(path, kWires, 0, outs, ins);
    outs.try_push(out_rec(5, 0, OutputLine::kDir, true));
  }  // the destructor finishes the file
  const Parsed p = parse_vcd(slurp(path));
  ASSERT_EQ(p.comments.size(), 1u);
  EXPECT_NE(p.comments[0].find("outputs 0, inputs 0"), std::string::npos) << p.comments[0];
  ASSERT_EQ(p.changes.size(), 1u);
  EXPECT_EQ(p.changes[0], (Change{5, "axis1.dir", 1}));
  std::filesystem::remove(path);
}

TEST(GpioTraceWires, FromTheBackendsConfiguredLinesWithInputLevels) {
  SimAxisSetup s;
  s.lines.out[0] = 1;
  s.lines.out[1] = 2;
  s.lines.in[static_cast<unsigned>(InputLine::kHome)] = 3;
  s.lines.in[static_cast<unsigned>(InputLine::kCcwLimit)] = 4;
  s.sim.ccw_limit_at = 0;  // actuated at start
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  const auto wires = trace_wires(b);
  ASSERT_EQ(wires.size(), 4u);
  EXPECT_EQ(wire_name(wires[0]), "axis1.step");
  EXPECT_EQ(wire_name(wires[1]), "axis1.dir");
  EXPECT_EQ(wire_name(wires[2]), "axis1.home");
  EXPECT_FALSE(wires[2].initial);
  EXPECT_EQ(wire_name(wires[3]), "axis1.ccw_limit");
  EXPECT_TRUE(wires[3].initial);
}

// The charge pump is the module's, not an axis': "charge_pump", in a rack "x.charge_pump" (on its
// module's first axis), and without the rack's names on a later module "axis3.charge_pump".
TEST(GpioTraceWires, TheChargePumpIsNamedAfterItsModule) {
  EXPECT_EQ(wire_name(charge_pump_trace_wire(0, false)), "charge_pump");
  const std::vector<std::string> rack = {"x.axis1", "y.axis1", "y.axis2"};
  EXPECT_EQ(wire_name(charge_pump_trace_wire(0, false), rack), "x.charge_pump");
  EXPECT_EQ(wire_name(charge_pump_trace_wire(1, false), rack), "y.charge_pump");
  EXPECT_EQ(wire_name(charge_pump_trace_wire(2, false)), "axis3.charge_pump");
  EXPECT_EQ(wire_name(enable_trace_wire(1, false), rack), "y.axis1.enable");
}

TEST(GpioVcdTrace, ActiveLowWiresShowTheInvertedLevel) {
  const std::string path = temp_path("active_low.vcd");
  const TraceWire wires[] = {
      {0, false, static_cast<std::uint8_t>(OutputLine::kStep), false, true},
      {0, true, static_cast<std::uint8_t>(InputLine::kHome), true, true},
  };
  {
    VcdTrace v(path, wires, 0);
    v.record(out_rec(100, 0, OutputLine::kStep, true));  // logical high: the wire goes low
    v.record(in_rec(200, 0, InputLine::kHome, false));   // logical low: the wire goes high
    v.close(1000);
  }
  const Parsed p = parse_vcd(slurp(path));
  EXPECT_EQ(p.initial.at("axis1.step"), 1) << "idle (logical low) is a high wire";
  EXPECT_EQ(p.initial.at("axis1.home"), 0);
  const std::vector<Change> want = {{100, "axis1.step", 0}, {200, "axis1.home", 1}};
  EXPECT_EQ(p.changes, want);
  std::filesystem::remove(path);
}

TEST(GpioTraceWires, CarryTheBackendsActiveLowOption) {
  SimAxisSetup s;
  s.lines.out[0] = 1;
  s.lines.out[1] = 2;
  s.lines.out_opt[0].active_low = true;
  s.lines.in[static_cast<unsigned>(InputLine::kHome)] = 3;
  s.lines.in_opt[static_cast<unsigned>(InputLine::kHome)].active_low = true;
  const std::vector<SimAxisSetup> axes = {s};
  SimBackend b(axes);
  const auto wires = trace_wires(b);
  ASSERT_EQ(wires.size(), 3u);
  EXPECT_TRUE(wires[0].active_low);
  EXPECT_FALSE(wires[1].active_low);
  EXPECT_TRUE(wires[2].active_low);
}

TEST(GpioVcdTrace, ManyWiresGetDistinctIds) {
  std::vector<TraceWire> wires;
  for (unsigned a = 0; a < 20; ++a) {
    for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
      wires.push_back({static_cast<std::uint8_t>(a), true, static_cast<std::uint8_t>(l), false});
    }
  }
  const std::string path = temp_path("ids.vcd");
  {
    VcdTrace v(path, wires, 0);
    v.record(in_rec(10, 19, InputLine::kEncZ, true));
    v.close(10);
  }
  const Parsed p = parse_vcd(slurp(path));
  EXPECT_EQ(p.names.size(), 180u);
  ASSERT_EQ(p.changes.size(), 1u);
  EXPECT_EQ(p.changes[0].name, "axis20.enc_z");
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace stepmod::gpio
