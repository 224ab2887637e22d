#pragma once
// The error-reason tests' fixture (reasons_XXXX_test.cpp; docs/error-reasons.md): a module's test
// rig and the last error reason the personality keeps for each axis or channel.
#include <string>

#include "module/axis/error_items.hpp"

namespace stepmod::testing {

using module::axis::ErrorReason;

inline std::string text(const ErrorReason& r) {
  return std::string(r.text.data());
}

// `Rig`: the module's fixture (Plc3601, Rig3602, Plc3202).
template <class Rig>
class ReasonsRig : public Rig {
 protected:
  // The last reason of axis/channel `unit` (0-based).
  ErrorReason reason(unsigned unit = 0) { return this->vm_.stack().personality().reason(unit); }
};

}  // namespace stepmod::testing
