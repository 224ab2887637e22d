// The rack file (docs/interface.md section 7): its module files read as their own daemons would,
// the rack's [rt] given to each, and one test per error between modules (each names the files and
// keys; stepmodd exits 2 on every ConfigError).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "config/rack_config.hpp"

namespace stepmod::tools {
namespace {

namespace fs = std::filesystem;

class ConfigRack : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "stepmod-rack-XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  // A 3601 module file named `name`; `extra` is appended (more tables).
  std::string module(const std::string& file, const std::string& name, unsigned step = 17,
                     const std::string& extra = "", const std::string& backend = "sim") const {
    return write(file, "[module]\ntype = \"3601\"\nname = \"" + name + "\"\n[gpio]\nbackend = \"" +
                           backend + "\"\n[[axis]]\nstep = " + std::to_string(step) +
                           "\ndir = " + std::to_string(step + 1) + "\n" + extra);
  }
  std::string rack(const std::string& body) const { return write("rack.toml", body); }
  std::string error_of(const std::string& path) const {
    try {
      load_rack(path);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "(accepted)";
  }

  fs::path dir_;
};

TEST_F(ConfigRack, ModuleFileIsRackOfOne) {
  const std::string path = module("one.toml", "one");
  const RackConfig r = load_rack(path);
  EXPECT_FALSE(r.rack_file);
  ASSERT_EQ(r.modules.size(), 1u);
  EXPECT_EQ(r.modules[0].name, "one");
}

TEST_F(ConfigRack, ModulesInOrderWithTheRacksRt) {
  module("x.toml", "x");
  fs::create_directory(dir_ / "sub");
  module("sub/y.toml", "y");
  const std::string abs = module("z.toml", "z", 5);
  const RackConfig r = load_rack(rack("[rack]\nmodules = [\"x.toml\", \"sub/y.toml\", \"" + abs +
                                      "\"]\n[rt]\npriority = 70\ncpu = 1\nlate_limit_us = 500\n"));
  EXPECT_TRUE(r.rack_file);
  ASSERT_EQ(r.modules.size(), 3u);
  EXPECT_EQ(r.modules[0].name, "x");
  EXPECT_EQ(r.modules[1].name, "y");
  EXPECT_EQ(r.modules[2].name, "z");
  for (const Config& m : r.modules) {
    EXPECT_EQ(m.rt_priority, 70);
    EXPECT_EQ(m.rt_cpu, 1);
    EXPECT_EQ(m.late_limit_ns, 500 * kNsPerUs);
  }
}

TEST_F(ConfigRack, RtTableInAModuleFileNamesBothFiles) {
  const std::string x = module("x.toml", "x", 17, "[rt]\n");
  const std::string e = error_of(rack("[rack]\nmodules = [\"x.toml\"]\n"));
  EXPECT_NE(e.find(x + ":9: key 'rt'"), std::string::npos) << e;
  EXPECT_NE(e.find((dir_ / "rack.toml").string()), std::string::npos) << e;
}

TEST_F(ConfigRack, DuplicateNames) {
  const std::string x = module("x.toml", "same");
  const std::string y = module("y.toml", "same");
  const std::string e = error_of(rack("[rack]\nmodules = [\"x.toml\", \"y.toml\"]\n"));
  EXPECT_NE(e.find("key 'module.name'"), std::string::npos) << e;
  EXPECT_NE(e.find(x), std::string::npos) << e;
  EXPECT_NE(e.find(y), std::string::npos) << e;
}

TEST_F(ConfigRack, GpiodLineUsedByTwoModules) {
  module("x.toml", "x", 17, "", "gpiod");
  module("y.toml", "y", 18, "", "gpiod");  // y's step is x's dir
  const std::string e = error_of(rack("[rack]\nmodules = [\"x.toml\", \"y.toml\"]\n"));
  EXPECT_NE(e.find("key 'axis[1].step' of module 'y'"), std::string::npos) << e;
  EXPECT_NE(e.find("line 18 of chip 'gpiochip0'"), std::string::npos) << e;
  EXPECT_NE(e.find("key 'axis[1].dir' of module 'x'"), std::string::npos) << e;
}

TEST_F(ConfigRack, SimulatedMachinesMayRepeatOffsets) {
  module("x.toml", "x");
  module("y.toml", "y");
  EXPECT_EQ(load_rack(rack("[rack]\nmodules = [\"x.toml\", \"y.toml\"]\n")).modules.size(), 2u);
}

TEST_F(ConfigRack, SharedModbusAddressNeedsDistinctUnitIds) {
  const std::string mb = "[modbus]\nenabled = true\nunit_id = 3\n";
  module("x.toml", "x", 17, mb);
  module("y.toml", "y", 17, mb);
  const std::string e = error_of(rack("[rack]\nmodules = [\"x.toml\", \"y.toml\"]\n"));
  EXPECT_NE(e.find("key 'modbus.unit_id'"), std::string::npos) << e;
  EXPECT_NE(e.find("127.0.0.1:1502"), std::string::npos) << e;
  // Other addresses: separate servers, equal unit ids are fine.
  module("y.toml", "y", 17, mb + "listen = \"127.0.0.1:1503\"\n");
  EXPECT_EQ(error_of(dir_ / "rack.toml"), "(accepted)");
}

TEST_F(ConfigRack, SharedModbusServerKeysMustAgree) {
  module("x.toml", "x", 17, "[modbus]\nenabled = true\nunit_id = 1\n");
  module("y.toml", "y", 17, "[modbus]\nenabled = true\nunit_id = 2\nmax_clients = 9\n");
  const std::string e = error_of(rack("[rack]\nmodules = [\"x.toml\", \"y.toml\"]\n"));
  EXPECT_NE(e.find("modbus.max_clients"), std::string::npos) << e;
}

// docs/ethernetip-design.md: each module's adapter on an address of its own (its I/O is on UDP
// 2222 of it, so another port of the same address clashes too).
TEST_F(ConfigRack, TwoAdaptersOnOneAddressAreAnError) {
  const std::string ei = "[ethernetip]\nenabled = true\n";
  module("x.toml", "x", 17, ei);
  module("y.toml", "y", 17, ei + "listen = \"127.0.0.1:44819\"\n");
  const std::string e = error_of(rack("[rack]\nmodules = [\"x.toml\", \"y.toml\"]\n"));
  EXPECT_NE(e.find("key 'ethernetip.listen'"), std::string::npos) << e;
  EXPECT_NE(e.find("'x'"), std::string::npos) << e;
  EXPECT_NE(e.find("y.toml"), std::string::npos) << e;
  EXPECT_NE(e.find("own address"), std::string::npos) << e;
  module("y.toml", "y", 17, ei + "listen = \"127.0.0.2:44818\"\n");
  EXPECT_EQ(error_of(dir_ / "rack.toml"), "(accepted)");
  module("y.toml", "y", 17, "[ethernetip]\nenabled = false\n");  // off: no address taken
  EXPECT_EQ(error_of(dir_ / "rack.toml"), "(accepted)");
}

TEST_F(ConfigRack, RackAndModuleInOneFile) {
  module("x.toml", "x");
  const std::string e =
      error_of(rack("[rack]\nmodules = [\"x.toml\"]\n[module]\ntype = \"3601\"\n"));
  EXPECT_NE(e.find("rack.toml:3: key 'module'"), std::string::npos) << e;
}

TEST_F(ConfigRack, BadModulesLists) {
  EXPECT_NE(error_of(rack("[rack]\n")).find("key 'rack.modules': required"), std::string::npos);
  EXPECT_NE(error_of(rack("[rack]\nmodules = []\n")).find("key 'rack.modules'"),
            std::string::npos);
  EXPECT_NE(error_of(rack("[rack]\nmodules = [3]\n")).find("key 'rack.modules'"),
            std::string::npos);
  EXPECT_NE(error_of(rack("[rack]\nmodules = [\"x.toml\"]\nmodbus = 1\n")).find("unknown key"),
            std::string::npos);
  // A missing module file: its own message, and which rack names it.
  const std::string e = error_of(rack("[rack]\nmodules = [\"nope.toml\"]\n"));
  EXPECT_NE(e.find("nope.toml: cannot read"), std::string::npos) << e;
  EXPECT_NE(e.find("rack.toml"), std::string::npos) << e;
}

TEST_F(ConfigRack, ARackIsNoModuleFile) {
  module("x.toml", "x");
  const std::string r = rack("[rack]\nmodules = [\"x.toml\"]\n");
  try {
    load_config(r);
    FAIL() << "a rack file read as a module file";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("key 'rack'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace stepmod::tools
