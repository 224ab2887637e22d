// The trace's files against a hostile or full directory (docs/hardening.md): links and FIFOs
// planted under the trace's names (and its old temporary names), the new file unnamed or
// randomly named, a trace path used again, a full disk, a killed daemon's spools recovered, and
// records of several lines collected out of order put back at their times.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "gpio/trace_file.hpp"
#include "gpio/trace_recover.hpp"
#include "gpio/vcd_trace.hpp"

namespace stepmod::gpio {
namespace {

namespace fs = std::filesystem;

const std::vector<TraceWire> kWires = {
    {0, false, static_cast<std::uint8_t>(OutputLine::kStep), false},
    {0, true, static_cast<std::uint8_t>(InputLine::kHome), false},
    {1, false, static_cast<std::uint8_t>(OutputLine::kStep), false},
    {1, true, static_cast<std::uint8_t>(InputLine::kHome), false},
};

TraceRecord rec(Nanos t, unsigned axis, bool input, bool level) {
  const auto line = input ? static_cast<std::uint8_t>(InputLine::kHome)
                          : static_cast<std::uint8_t>(OutputLine::kStep);
  return {t, static_cast<std::uint8_t>(axis), line, static_cast<std::uint8_t>(level),
          static_cast<std::uint8_t>(input ? 1 : 0)};
}

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void put(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// The times of a VCD's changes, in file order, and whether they never go back.
struct Times {
  std::vector<std::int64_t> t;
  bool monotonic = true;
};
Times times_of(const std::string& text) {
  Times r;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) {
    if (tok.size() > 1 && tok[0] == '#') {
      const std::int64_t t = std::stoll(tok.substr(1));
      if (!r.t.empty() && t < r.t.back()) r.monotonic = false;
      r.t.push_back(t);
    }
  }
  return r;
}

class TraceFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("stepmod_trace_files_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (mounted_) ::umount2(dir_.c_str(), MNT_DETACH);
    fs::remove_all(dir_);
  }
  std::string at(const std::string& name) const { return (dir_ / name).string(); }
  // The directory's entries (what a test left there).
  std::vector<std::string> entries() const {
    std::vector<std::string> v;
    for (const auto& e : fs::directory_iterator(dir_)) v.push_back(e.path().filename().string());
    std::sort(v.begin(), v.end());
    return v;
  }
  // Expects the writer on `path` to be refused at construction, naming `named`.
  void expect_refused(const std::string& path, const std::string& named, const std::string& why) {
    SpscRing<TraceRecord> outs(8), ins(8);
    try {
      TraceWriter w(path, kWires, 0, outs, ins);
      ADD_FAILURE() << "expected " << path << " to be refused";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(named), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  }
  fs::path dir_;
  bool mounted_ = false;
};

TEST_F(TraceFiles, SymlinkAtTheTracePathIsRefusedAndItsTargetUntouched) {
  put(at("victim"), "precious\n");
  fs::create_symlink(at("victim"), at("a.vcd"));
  expect_refused(at("a.vcd"), at("a.vcd"), "a symbolic link");
  EXPECT_EQ(slurp(at("victim")), "precious\n");
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.vcd", "victim"})) << "no spool left behind";
}

TEST_F(TraceFiles, DanglingSymlinkIsRefusedAndItsTargetNotCreated) {
  fs::create_symlink(at("created-by-the-trace"), at("a.vcd"));
  expect_refused(at("a.vcd"), at("a.vcd"), "a symbolic link");
  EXPECT_FALSE(fs::exists(at("created-by-the-trace")));
}

TEST_F(TraceFiles, FifoAtTheTracePathIsRefused) {
  ASSERT_EQ(::mkfifo(at("a.vcd").c_str(), 0600), 0);
  expect_refused(at("a.vcd"), at("a.vcd"), "a FIFO");
}

TEST_F(TraceFiles, LinksAndFifosAtTheSpoolNamesAreRefusedWithoutBlocking) {
  put(at("victim"), "precious\n");
  ASSERT_EQ(::mkfifo(at("a.vcd.out.spool").c_str(), 0600), 0);
  expect_refused(at("a.vcd"), at("a.vcd.out.spool"), "a FIFO");
  fs::remove(at("a.vcd.out.spool"));
  fs::create_symlink(at("victim"), at("a.vcd.in.spool"));
  expect_refused(at("a.vcd"), at("a.vcd.in.spool"), "a symbolic link");
  EXPECT_EQ(slurp(at("victim")), "precious\n");
  // The out spool created before the refusal is removed again; nothing else was touched.
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.vcd.in.spool", "victim"}));
}

TEST_F(TraceFiles, LeftoverSpoolIsNeverOverwrittenAndTheErrorSaysHowToRecover) {
  put(at("a.vcd.out.spool"), "a killed daemon's records");
  expect_refused(at("a.vcd"), at("a.vcd.out.spool"), "stepmodctl trace recover");
  EXPECT_EQ(slurp(at("a.vcd.out.spool")), "a killed daemon's records");
}

TEST_F(TraceFiles, HardLinkedTracePathGetsANewFileAndTheOtherNameKeepsItsContents) {
  put(at("victim"), "precious\n");
  ASSERT_EQ(::link(at("victim").c_str(), at("a.vcd").c_str()), 0);
  SpscRing<TraceRecord> outs(8), ins(8);
  TraceWriter w(at("a.vcd"), kWires, 0, outs, ins);
  outs.try_push(rec(100, 0, false, true));
  EXPECT_TRUE(w.stop().complete);
  EXPECT_EQ(slurp(at("victim")), "precious\n");
  EXPECT_NE(slurp(at("a.vcd")).find("$enddefinitions"), std::string::npos);
}

TEST_F(TraceFiles, FifoPlantedAtTheTracePathWhileRunningIsReplacedNotOpened) {
  SpscRing<TraceRecord> outs(8), ins(8);
  TraceWriter w(at("a.vcd"), kWires, 0, outs, ins, kNsPerMs);
  w.start();
  outs.try_push(rec(100, 0, false, true));
  ASSERT_EQ(::mkfifo(at("a.vcd").c_str(), 0600), 0);
  const TraceOutcome o = w.stop();  // would block forever in an open() of the FIFO
  EXPECT_TRUE(o.complete) << o.problem;
  struct stat st {};
  ASSERT_EQ(::lstat(at("a.vcd").c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode));
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.vcd"}));
}

TEST_F(TraceFiles, TheSameTracePathWorksAgainAndNothingIsLeftBeside) {
  for (int run = 0; run < 2; ++run) {
    SpscRing<TraceRecord> outs(8), ins(8);
    TraceWriter w(at("a.vcd"), kWires, 0, outs, ins);
    outs.try_push(rec(100 + run, 0, false, true));
    EXPECT_TRUE(w.stop().complete);
    EXPECT_NE(slurp(at("a.vcd")).find("#" + std::to_string(100 + run)), std::string::npos);
  }
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.vcd"}));
}

// The VCD was once written to "a.vcd.tmp.<pid>.<n>", n = 0, 1, ... giving up after 100 names
// taken: anyone could plant them and make the trace fail (stepmodd exit 3). Now the new file has
// no name (O_TMPFILE) or a random one; links planted under the old names change nothing, and
// none is followed.
TEST_F(TraceFiles, LinksPlantedUnderTheOldTemporaryNamesNeitherFailTheTraceNorAreFollowed) {
  put(at("victim"), "precious\n");
  const std::string old = at("a.vcd.tmp." + std::to_string(::getpid()) + ".");
  constexpr int kPlanted = 300;
  for (int n = 0; n < kPlanted; ++n) {
    ASSERT_EQ(::symlink(at("victim").c_str(), (old + std::to_string(n)).c_str()), 0);
  }
  SpscRing<TraceRecord> outs(8), ins(8);
  TraceWriter w(at("a.vcd"), kWires, 0, outs, ins);
  outs.try_push(rec(100, 0, false, true));
  const TraceOutcome o = w.stop();
  EXPECT_TRUE(o.complete) << o.problem;
  EXPECT_NE(slurp(at("a.vcd")).find("#100"), std::string::npos);
  EXPECT_EQ(slurp(at("victim")), "precious\n");
  EXPECT_EQ(entries().size(), kPlanted + 2u) << "a.vcd, the victim and the planted links";
  struct stat st {};
  ASSERT_EQ(::lstat(at("a.vcd").c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode));
}

// Where O_TMPFILE works (this test's directory), the file has no name until it is complete.
TEST_F(TraceFiles, NewFileHasNoNameUntilItIsPutInPlace) {
  NewFile f = create_file_beside(at("a.vcd"), "trace file");
  if (!f.path.empty()) {
    discard(f);
    GTEST_SKIP() << "no O_TMPFILE (or no /proc) here: the random-name test covers this";
  }
  ASSERT_EQ(::write(f.fd, "vcd\n", 4), 4);
  EXPECT_TRUE(entries().empty());
  put_in_place(f, at("a.vcd"), "trace file");
  EXPECT_EQ(f.fd, -1);
  EXPECT_EQ(slurp(at("a.vcd")), "vcd\n");
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.vcd"}));
}

// Without O_TMPFILE: a random name (64 bits, no pid, no counter), created new; put in place by a
// rename that replaces a link planted at the trace path rather than following it.
TEST_F(TraceFiles, WithoutTmpfileTheNewFileHasARandomNameAndReplacesALinkAtThePath) {
  put(at("victim"), "precious\n");
  ASSERT_EQ(::symlink(at("victim").c_str(), at("a.vcd").c_str()), 0);
  NewFile f = create_file_beside(at("a.vcd"), "trace file", Naming::kRandomName);
  NewFile g = create_file_beside(at("a.vcd"), "trace file", Naming::kRandomName);
  const std::string prefix = at("a.vcd.tmp.");
  ASSERT_EQ(f.path.rfind(prefix, 0), 0u) << f.path;
  const std::string hex = f.path.substr(prefix.size());
  EXPECT_EQ(hex.size(), 16u) << f.path;
  EXPECT_EQ(hex.find_first_not_of("0123456789abcdef"), std::string::npos) << f.path;
  EXPECT_NE(f.path, g.path);
  discard(g);
  ASSERT_EQ(::write(f.fd, "vcd\n", 4), 4);
  put_in_place(f, at("a.vcd"), "trace file");
  EXPECT_EQ(slurp(at("victim")), "precious\n");
  EXPECT_EQ(slurp(at("a.vcd")), "vcd\n");
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.vcd", "victim"}));
}

// Two axes' inputs, each line in order, collected axis by axis (the sim backend and the gpiod
// reader both do): the input stream is not in time order, the VCD must be.
TEST_F(TraceFiles, InputsOfSeveralAxesCollectedOutOfOrderAreWrittenAtTheirTimes) {
  SpscRing<TraceRecord> outs(64), ins(64);
  TraceWriter w(at("a.vcd"), kWires, 0, outs, ins);
  for (int k = 0; k < 4; ++k) {
    const Nanos base = Nanos{1000} * (k + 1);
    ins.try_push(rec(base + 100, 0, true, k % 2 == 0));  // axis 1 first...
    ins.try_push(rec(base + 50, 1, true, k % 2 == 0));   // ...then axis 2's earlier edge
    outs.try_push(rec(base + 75, 0, false, k % 2 == 0));
    w.step();
  }
  EXPECT_TRUE(w.stop().complete);
  EXPECT_EQ(w.vcd().late(), 0u);
  EXPECT_EQ(w.vcd().changes(), 12u);
  const Times t = times_of(slurp(at("a.vcd")));
  EXPECT_TRUE(t.monotonic);
  EXPECT_NE(slurp(at("a.vcd")).find("late records 0"), std::string::npos);
  EXPECT_NE(slurp(at("a.vcd")).find("#1050"), std::string::npos) << "axis 2's edge at its time";
}

// A killed daemon: its spools stay (with what the thread had written, every kFlushPeriod), and
// the VCD is made from them afterwards.
TEST_F(TraceFiles, KilledWritersSpoolsAreRecoveredIntoAVcdMarkedIncomplete) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    SpscRing<TraceRecord> outs(64), ins(64);
    TraceWriter w(at("a.vcd"), kWires, 0, outs, ins, kNsPerMs);
    for (int i = 0; i < 10; ++i) outs.try_push(rec(Nanos{1000} * (i + 1), 0, false, i % 2 == 0));
    ins.try_push(rec(5500, 1, true, true));
    w.start();
    std::this_thread::sleep_for(std::chrono::milliseconds(400));
    ::_exit(0);  // no destructor, no stop(): as SIGKILL
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(fs::exists(at("a.vcd.out.spool")));
  ASSERT_FALSE(fs::exists(at("a.vcd")));
  const RecoverResult r = recover_trace({at("a.vcd.out.spool"), at("a.vcd.in.spool")}, at("a.vcd"));
  EXPECT_EQ(r.changes, 11u);
  EXPECT_EQ(r.late, 0u);
  const std::string text = slurp(at("a.vcd"));
  EXPECT_NE(text.find("TRACE INCOMPLETE"), std::string::npos);
  EXPECT_NE(text.find("axis2.home"), std::string::npos);
  EXPECT_NE(text.find("#5500"), std::string::npos);
  EXPECT_TRUE(times_of(text).monotonic);
}

TEST_F(TraceFiles, RecoverRefusesSpoolsOfDifferentRunsAndNonSpools) {
  SpscRing<TraceRecord> outs(8), ins(8);
  {
    TraceWriter w1(at("a.vcd"), kWires, 0, outs, ins);
    TraceWriter w2(at("b.vcd"), kWires, 5, outs, ins);
    EXPECT_THROW(recover_trace({at("a.vcd.out.spool"), at("b.vcd.out.spool")}, at("c.vcd")),
                 std::runtime_error);
  }
  put(at("junk"), "not a spool at all, not at all");
  EXPECT_THROW(recover_trace({at("junk")}, at("c.vcd")), std::runtime_error);
  EXPECT_FALSE(fs::exists(at("c.vcd")));
}

// A full disk: a small tmpfs, the rest of it taken by a filler file. Needs root (mount).
class TraceFullDisk : public TraceFiles {
 protected:
  void SetUp() override {
    TraceFiles::SetUp();
    if (::geteuid() != 0) GTEST_SKIP() << "needs root to mount a 256 KiB tmpfs";
    if (::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=256k") != 0) {
      GTEST_SKIP() << "cannot mount a tmpfs: " << std::strerror(errno);
    }
    mounted_ = true;
  }
  // Takes every free byte but `leave`.
  void fill(std::size_t leave) {
    std::ofstream f(at("filler"), std::ios::binary);
    const std::string chunk(4096, 'x');
    while (fs::space(dir_).available > leave + chunk.size()) f << chunk << std::flush;
  }
  // Pushes `n` output records through the running writer until its spool write fails.
  static void push_until_failed(TraceWriter& w, SpscRing<TraceRecord>& outs, int n) {
    for (int i = 0; i < n; ++i) {
      while (!outs.try_push(rec(Nanos{1000} * (i + 1), 0, false, i % 2 == 0))) {
        std::this_thread::yield();
      }
    }
    for (int k = 0; k < 500 && !w.failed(); ++k) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
};

TEST_F(TraceFullDisk, FailedSpoolWriteIsSeenAtOnceAndTheVcdIsMarkedIncomplete) {
  SpscRing<TraceRecord> outs(1024), ins(64);
  TraceWriter w(at("a.vcd"), kWires, 0, outs, ins, kNsPerMs);
  fill(0);
  w.start();
  push_until_failed(w, outs, 20'000);
  EXPECT_TRUE(w.failed()) << "a write failure is seen while running (health bit 4)";
  fs::remove(at("filler"));  // room again for the VCD
  const TraceOutcome o = w.stop();
  EXPECT_FALSE(o.complete);
  EXPECT_TRUE(o.vcd_written) << o.problem;
  EXPECT_NE(slurp(at("a.vcd")).find("TRACE INCOMPLETE"), std::string::npos);
  EXPECT_EQ(entries(), (std::vector<std::string>{"a.vcd"}));
}

TEST_F(TraceFullDisk, VcdThatCannotBeWrittenLeavesTheSpoolsAndTheOldFileInPlace) {
  put(at("a.vcd"), "the previous run's trace\n");
  SpscRing<TraceRecord> outs(1024), ins(64);
  TraceWriter w(at("a.vcd"), kWires, 0, outs, ins, kNsPerMs);
  fill(std::size_t{48} * 1024);  // room for the spools' 20,000 records (320 KB) is not there either
  w.start();
  push_until_failed(w, outs, 20'000);
  const TraceOutcome o = w.stop();
  EXPECT_FALSE(o.complete);
  EXPECT_FALSE(o.vcd_written);
  EXPECT_NE(o.problem.find(at("a.vcd.out.spool")), std::string::npos) << o.problem;
  EXPECT_NE(o.problem.find("stepmodctl trace recover"), std::string::npos) << o.problem;
  EXPECT_EQ(slurp(at("a.vcd")), "the previous run's trace\n");
  EXPECT_EQ(entries(),
            (std::vector<std::string>{"a.vcd", "a.vcd.in.spool", "a.vcd.out.spool", "filler"}));
}

}  // namespace
}  // namespace stepmod::gpio
