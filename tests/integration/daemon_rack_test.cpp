// End to end: the real stepmodd as a rack (docs/interface.md section 7) of a 3602 and two 3601s
// on the simulated machine, every module driven through its own image at once by the PLC-side
// library: exact counts from the one VCD whose wires carry the modules' names, a stale PLC on one
// module stopping only that module's axis, one Modbus address serving the three by unit id
// (mbpoll), one pulse thread (SCHED_FIFO where the system grants it) and one planner thread, and
// stepmodd --check on the rack's configuration errors.
#include <gtest/gtest.h>

#include <dirent.h>
#include <sched.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <thread>

#include "ipc/client.hpp"
#include "ipc/sim_panel.hpp"
#include "module_types/m3601/plc_3601.hpp"
#include "module_types/m3601/words_3601.hpp"
#include "module_types/m3602/plc_3602.hpp"
#include "module_types/m3602/words_3602.hpp"
#include "plc/shm_port.hpp"
#include "tests/support/daemon_process.hpp"
#include "tests/support/shell.hpp"
#include "tests/support/sim_config.hpp"
#include "tests/support/vcd_reader.hpp"

namespace stepmod::testing {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr plc::Sequencing kSeq{
    .hold_scans = 3, .release_scans = 2, .config_scans = 3, .release_stale_bits = false};
constexpr plc::Profile kProfile{.speed = 5'000, .accel = 100, .decel = 100};
constexpr int kStaleMs = 300;  // module a's [module] plc_timeout_ms

// The module files of the rack, in a directory of their own: a 3602 ("c", unit 1) and two 3601s
// ("a", unit 2, whose PLC goes stale; "b", unit 3), all serving Modbus on one address.
class RackFiles {
 public:
  RackFiles() {
    std::string tmpl = (fs::temp_directory_path() / "stepmod-rack-it-XXXXXX").string();
    if (::mkdtemp(tmpl.data()) != nullptr) dir_ = tmpl;
    prefix_ = "rk" + std::to_string(::getpid()) + "-";
    port_ = free_port();
  }
  ~RackFiles() { fs::remove_all(dir_); }
  RackFiles(const RackFiles&) = delete;
  RackFiles& operator=(const RackFiles&) = delete;

  std::string name(const std::string& m) const { return prefix_ + m; }
  int port() const { return port_; }
  std::string write(const std::string& file, const std::string& text) const {
    std::ofstream(dir_ / file) << text;
    return (dir_ / file).string();
  }
  // Module `m` of `type`, with `axes` ([[axis]] tables) and `extra` [module] keys.
  std::string module(const std::string& m, const std::string& type, const std::string& axes,
                     unsigned unit, const std::string& extra = "") const {
    return write(m + ".toml", "[module]\ntype = \"" + type + "\"\nname = \"" + name(m) +
                                  "\"\nscan_us = 1000\n" + extra +
                                  "\n[gpio]\nbackend = \"sim\"\n\n[modbus]\nenabled = true\n"
                                  "listen = \"127.0.0.1:" +
                                  std::to_string(port_) + "\"\nunit_id = " + std::to_string(unit) +
                                  "\n" + axes);
  }
  void write_modules() const {
    const std::string far = "cw_limit_at = 1000000\nccw_limit_at = -1000000\n";
    std::string c_axes;
    for (const unsigned first : {1u, 11u}) {
      c_axes += sim_axis(numbered_lines(first, {"step", "dir", "cw_limit", "ccw_limit"}), far);
    }
    module("c", "3602", c_axes, 1);
    // The 3601s carry a charge pump each (docs/safety.md): a's stops with its PLC, b's runs on.
    const std::string axis_3601 =
        sim_axis(numbered_lines(1, {"step", "dir", "home", "cw_limit", "ccw_limit"}), far) +
        "\n[charge_pump]\nline = 6\nfrequency_hz = 100\n";
    module("a", "3601", axis_3601, 2, "plc_timeout_ms = " + std::to_string(kStaleMs) + "\n");
    module("b", "3601", axis_3601, 3);
  }
  std::string rack_text() const {
    return "[rack]\nmodules = [\"" + (dir_ / "c.toml").string() + "\", \"" +
           (dir_ / "a.toml").string() + "\", \"" + (dir_ / "b.toml").string() +
           "\"]\n\n[rt]\npriority = 80\n" + kRelaxedLateLimit;
  }
  const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
  std::string prefix_;
  int port_ = -1;
};

// The names of a process' threads, counted.
std::map<std::string, int> thread_names(pid_t pid, std::map<std::string, pid_t>* tid_of = nullptr) {
  std::map<std::string, int> names;
  const fs::path task = "/proc/" + std::to_string(pid) + "/task";
  for (const auto& e : fs::directory_iterator(task)) {
    std::string comm;
    std::getline(std::ifstream(e.path() / "comm"), comm);
    ++names[comm];
    if (tid_of != nullptr) (*tid_of)[comm] = std::stoi(e.path().filename().string());
  }
  return names;
}

class DaemonRack : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_GT(files_.port(), 0);
    files_.write_modules();
    DaemonOptions o;
    o.name = files_.name("c");  // wait_ready() waits for the first module's image
    daemon_ = std::make_unique<DaemonProcess>(files_.rack_text(), o);
    ASSERT_TRUE(daemon_->wait_ready()) << daemon_->log();
    for (const char* m : {"c", "a", "b"}) {
      clients_[m] = std::make_unique<ipc::Client>(files_.name(m));
      ASSERT_TRUE(clients_[m]->wait_scans(2, milliseconds(5000))) << m << "\n" << daemon_->log();
      ports_[m] = std::make_unique<plc::ShmPort>(*clients_[m], milliseconds(2000));
    }
    c_ = std::make_unique<plc::Plc3602>(*ports_["c"], milliseconds(2000), kSeq);
    a_ = std::make_unique<plc::Plc3601>(*ports_["a"], milliseconds(2000), kSeq);
    b_ = std::make_unique<plc::Plc3601>(*ports_["b"], milliseconds(2000), kSeq);
  }
  void TearDown() override {
    if (daemon_ && daemon_->pid() > 0) daemon_->terminate();
  }
  Vcd stop_and_read_trace() {
    c_.reset();
    a_.reset();
    b_.reset();
    ports_.clear();
    clients_.clear();
    EXPECT_EQ(daemon_->terminate(), 0) << daemon_->log();
    return read_vcd(daemon_->trace_path());
  }
  std::string wire(const std::string& m, unsigned axis, const std::string& key) const {
    return files_.name(m) + ".axis" + std::to_string(axis) + "." + key;
  }
  void configure_all() {
    namespace c2 = words::m3602::cfg_msw;
    constexpr std::uint16_t kCfg3602 = (c2::kFunctionLimit << c2::kCwFunctionShift) |
                                       (c2::kFunctionLimit << c2::kCcwFunctionShift) |
                                       c2::kStepDirOutput;
    ASSERT_TRUE(c_->configure(0, kCfg3602, 0x1F, 1'000).ok);
    ASSERT_TRUE(c_->configure(1, kCfg3602, 0x1F, 1'000).ok);
    // A 3601 needs a way to home and an end limit (3601-CFG-02, CFG-03).
    namespace c1 = words::m3601::cfg_msw;
    constexpr std::uint16_t kCfg3601 =
        c1::kHomeUsed | c1::kCwLimitUsed | c1::kCcwLimitUsed | c1::kStepDirOutput;
    const plc::Outcome ob = b_->configure(kCfg3601, 0x3F, 1'000);
    ASSERT_TRUE(ob.ok) << ob.message;
    ASSERT_TRUE(a_->configure(kCfg3601, 0x3F, 1'000).ok);
  }

  RackFiles files_;
  std::unique_ptr<DaemonProcess> daemon_;
  std::map<std::string, std::unique_ptr<ipc::Client>> clients_;
  std::map<std::string, std::unique_ptr<plc::ShmPort>> ports_;
  std::unique_ptr<plc::Plc3602> c_;
  std::unique_ptr<plc::Plc3601> a_;
  std::unique_ptr<plc::Plc3601> b_;
};

TEST_F(DaemonRack, EveryModuleAtOnceExactCountsAndOneStaleModuleStopsAlone) {
  configure_all();
  ASSERT_TRUE(c_->move(0, false, 8'000, kProfile).ok);
  ASSERT_TRUE(c_->move(1, false, -6'000, kProfile).ok);
  ASSERT_TRUE(b_->move(false, 7'000, kProfile).ok);
  // Module a's PLC commands a long move, then falls silent: its heartbeat goes stale after
  // kStaleMs and a stops as a PLC leaving Run mode, while c and b move on.
  ASSERT_TRUE(a_->move(false, 100'000, kProfile).ok);
  ASSERT_TRUE(c_->wait_idle(0, seconds(30)).ok);
  ASSERT_TRUE(c_->wait_idle(1, seconds(30)).ok);
  ASSERT_TRUE(b_->wait_idle(seconds(30)).ok);
  ImageWords in;
  ASSERT_TRUE(ports_["c"]->read_inputs(in));
  EXPECT_EQ(plc::m3602::decode_status(in, 0).position, 8'000) << daemon_->log();
  EXPECT_EQ(plc::m3602::decode_status(in, 1).position, -6'000);
  const ipc::Health ha = clients_["a"]->read_health();
  EXPECT_NE(ha.flags & STEPMOD_HEALTH_PLC_STALE, 0u) << daemon_->log();
  // The log says whose PLC it was (a rack's module threads log under their module's name).
  EXPECT_NE(daemon_->log().find("[" + files_.name("a") + "] PLC heartbeat unchanged"),
            std::string::npos)
      << daemon_->log();
  EXPECT_EQ(clients_["b"]->read_health().flags & STEPMOD_HEALTH_PLC_STALE, 0u);
  EXPECT_EQ(clients_["c"]->read_health().flags & STEPMOD_HEALTH_PLC_STALE, 0u);
  ipc::SimPanelClient panel_a(files_.name("a"));
  const std::int64_t a_stopped_at = panel_a.read(0).position;
  EXPECT_GT(a_stopped_at, 0);
  EXPECT_LT(a_stopped_at, 100'000);

  const Vcd vcd = stop_and_read_trace();
  EXPECT_EQ(vcd.rising(wire("c", 1, "step")).size(), 8'000u);
  EXPECT_EQ(vcd.rising(wire("c", 2, "step")).size(), 6'000u);
  EXPECT_EQ(vcd.rising(wire("b", 1, "step")).size(), 7'000u);
  EXPECT_EQ(static_cast<std::int64_t>(vcd.rising(wire("a", 1, "step")).size()), a_stopped_at);
  EXPECT_TRUE(vcd.wires.contains(wire("c", 2, "cw_limit")));
  EXPECT_FALSE(vcd.wires.contains("axis1.step"));  // every wire carries its module's name
  // The charge pumps, `<module>.charge_pump`: a's stopped with its stale PLC while b's went on.
  const auto pump_a = vcd.rising(files_.name("a") + ".charge_pump");
  const auto pump_b = vcd.rising(files_.name("b") + ".charge_pump");
  ASSERT_GT(pump_b.size(), 50u) << "b's pump toggles at 100 Hz through the run";
  ASSERT_FALSE(pump_a.empty()) << "a's pump ran until its PLC went stale";
  EXPECT_LT(pump_a.back() + 500'000'000, pump_b.back()) << "a's pump stopped long before b's";
}

TEST_F(DaemonRack, OnePulseThreadAndOnePlannerThread) {
  std::map<std::string, pid_t> tid;
  const std::map<std::string, int> names = thread_names(daemon_->pid(), &tid);
  EXPECT_EQ(names.count("stepmod-pulse") ? names.at("stepmod-pulse") : 0, 1);
  EXPECT_EQ(names.count("stepmod-plan") ? names.at("stepmod-plan") : 0, 1);
  EXPECT_EQ(names.count("stepmod-ctl") ? names.at("stepmod-ctl") : 0, 2);  // modules 2 and 3
  // SCHED_FIFO where the system grants it; an unprivileged run says it was refused.
  const int policy = ::sched_getscheduler(tid["stepmod-pulse"]);
  // Every thread's policy and priority, from /proc: one thread runs at the pulse priority (the
  // planner and the trace writer are SCHED_FIFO too, below it: docs/ARCHITECTURE.md "Threads").
  int at_pulse_priority = 0;
  for (const auto& e :
       fs::directory_iterator("/proc/" + std::to_string(daemon_->pid()) + "/task")) {
    const pid_t t = std::stoi(e.path().filename().string());
    sched_param sp{};
    const bool fifo = ::sched_getscheduler(t) == SCHED_FIFO && ::sched_getparam(t, &sp) == 0;
    at_pulse_priority += fifo && sp.sched_priority == 80 ? 1 : 0;
  }
  if (daemon_->log().find("SCHED_FIFO priority 80 refused") == std::string::npos) {
    EXPECT_EQ(policy, SCHED_FIFO) << daemon_->log();
    EXPECT_EQ(at_pulse_priority, 1) << "exactly one SCHED_FIFO pulse thread";
  } else {
    EXPECT_NE(policy, SCHED_FIFO);
    EXPECT_EQ(at_pulse_priority, 0);
  }
}

TEST_F(DaemonRack, OneModbusAddressServesEveryModuleByUnitId) {
  if (run_shell("sh -c 'command -v mbpoll'") != 0) GTEST_SKIP() << "mbpoll is not installed";
  const std::string base =
      "mbpoll -m tcp -0 -1 -o 2 -t 3 -r 1000 -c 1 -p " + std::to_string(files_.port()) + " -a ";
  const std::map<int, std::string> types = {{1, "3602"}, {2, "3601"}, {3, "3601"}};
  for (const auto& [unit, type] : types) {
    std::string out;
    ASSERT_EQ(run_shell(base + std::to_string(unit) + " 127.0.0.1", &out), 0) << out;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(out, m, std::regex(R"(\[1000\]:\s+(\d+))"))) << out;
    EXPECT_EQ(m[1].str(), type) << out;
  }
  std::string out;
  EXPECT_NE(run_shell(base + "9 127.0.0.1", &out), 0) << out;  // no such unit: exception 0B
}

// stepmodd --check on the rack's configuration errors: exit status 2, the files and keys named.
TEST(DaemonRackCheck, ConfigurationErrorsExitTwo) {
  RackFiles f;
  f.write_modules();
  const std::string rack = f.write("rack.toml", f.rack_text());
  std::string err;
  EXPECT_EQ(DaemonProcess::run_to_exit("--check --config " + rack, &err), 0) << err;
  const std::string b_toml = (f.dir() / "b.toml").string();
  std::ifstream in(b_toml);
  const std::string b_text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  f.write("b.toml", b_text + "\n[rt]\n");
  EXPECT_EQ(DaemonProcess::run_to_exit("--check --config " + rack, &err), 2);
  EXPECT_NE(err.find("key 'rt'"), std::string::npos) << err;
  f.module("b", "3601", "\n[[axis]]\nstep = 1\ndir = 2\n", 2);  // a's unit id
  EXPECT_EQ(DaemonProcess::run_to_exit("--check --config " + rack, &err), 2);
  EXPECT_NE(err.find("key 'modbus.unit_id'"), std::string::npos) << err;
}

}  // namespace
}  // namespace stepmod::testing
