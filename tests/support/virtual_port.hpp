#pragma once
// The PLC port (plc/port.hpp) over the virtual-time test machine: the PLC-side library drives the
// module stack exactly as over shared memory, but a "wait" runs virtual time instead of sleeping,
// so a test is deterministic and a 2-second homing pause costs nothing.
#include "plc/port.hpp"
#include "tests/support/virtual_machine.hpp"

namespace stepmod::testing {

class VirtualPort final : public plc::Port {
 public:
  explicit VirtualPort(VirtualMachine& vm) : vm_(vm) {}

  ModuleType type() const override { return vm_.type(); }
  ImageWords outputs() const override { return vm_.plc_out(); }
  void write_outputs(const ImageWords& out) override { vm_.plc_out() = out; }
  void update_outputs(const std::function<void(ImageWords&)>& edit) override {
    edit(vm_.plc_out());
  }
  bool read_inputs(ImageWords& in) const override {
    in = vm_.plc_in();
    return true;
  }
  // The machine always scans: n scan periods of virtual time.
  bool wait_scans(unsigned n) override {
    vm_.scans(n);
    return true;
  }
  void pass(std::chrono::nanoseconds d) override { vm_.run_for(d.count()); }
  bool wait_inputs(const std::function<bool(const ImageWords&)>& done,
                   std::chrono::nanoseconds limit) override {
    return vm_.run_until_true([&] { return done(vm_.plc_in()); }, limit.count());
  }

 private:
  VirtualMachine& vm_;
};

}  // namespace stepmod::testing
