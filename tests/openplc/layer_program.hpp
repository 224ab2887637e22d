#pragma once
// What the OpenPLC layer tests share: a PLC program's located variables, and a module image
// without a daemon whose scans the test makes one by one.
#include <functional>
#include <string>

#include <unistd.h>

#include "core/module_shape.hpp"
#include "ipc/shm_image.hpp"
#include "registry/module_registry.hpp"
#include "tests/openplc/ladder.h"
#include "tests/openplc/openplc_runtime.hpp"

namespace stepmod::testing {

// The PLC program's located variables, bound as glueVars() binds them. Some addresses are left
// unbound on purpose: mapUnusedIO() puts OpenPLC's Modbus registers behind them.
struct Program {
  IEC_UINT iw[48] = {};
  IEC_UINT qw[32] = {};
  unsigned qw_first = 0;  // the %QW the program declares: qw_first .. qw_end-1
  unsigned qw_end = 8;
  std::function<void()> bind() {
    return [this] {
      for (unsigned i = 0; i < 6; ++i) int_input[i] = &iw[i];  // %IW6, %IW7 (capture): unused
      for (unsigned i = 32; i < 48; ++i) int_input[i] = &iw[i];
      for (unsigned i = qw_first; i < qw_end; ++i) int_output[i] = &qw[i];
    };
  }
  bool linked() const { return iw[42] == 1; }
  ~Program() { openplc::reset(); }
};

// A module image without a daemon: the test is the module, and publishes (scans) when it wants.
struct ImageRig {
  explicit ImageRig(ModuleType type = ModuleType::k3601, const std::string& tag = "rig")
      : name("openplc-" + tag + "-" + std::to_string(::getpid())), image(name, shape_of(type)) {}
  std::string name;
  ipc::ShmImage image;
  Program prog;
  ImageWords in{};
  ipc::Health health{};
  // One module scan: the input words published, the scan counter advanced.
  void publish() { image.publish_inputs(in, health); }
  void publish(std::int32_t w0) {
    in.w[0] = w0;
    publish();
  }
  // The scan counter advanced without a publication (a module that is scanning while the test
  // holds its input sequence).
  void tick() { __atomic_fetch_add(&raw().scan_counter, 1u, __ATOMIC_RELEASE); }
  // A module scan, then a runtime scan.
  void scan(const std::function<void()>& logic = [] {}) {
    publish();
    openplc::scan(logic);
  }
  stepmod_image_t& raw() { return const_cast<stepmod_image_t&>(image.raw()); }
};

}  // namespace stepmod::testing
