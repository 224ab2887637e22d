#pragma once
// The stepmodctl row of module type `T` (tools/ctl_dialects.hpp), the same for every type: its
// functions are CtlOf<T>'s, which the type's folder defines (module_types/mXXXX/ctl_XXXX.cpp: the
// dialect; ctl_status_XXXX.cpp: status and summary; as `template <> plc::Outcome
// CtlOf<ModuleType::kXXXX>::run_command(...)`). A module type adds no row of its own:
// module_types/CMakeLists.txt lists kCtlRowOf<T> for every type, and includes the type's
// module_types/mXXXX/ctl_XXXX.hpp, which declares those definitions (STEPMOD_DECLARE_CTL_OF).
#include <chrono>
#include <sstream>
#include <vector>

#include "tools/ctl_dialects.hpp"

namespace stepmod::tools::ctl {

template <ModuleType T>
struct CtlOf {
  // A type without messages leaves `client` unused.
  static plc::Outcome run_command(const CtlRequest& c, plc::Port& port, ipc::Client& client,
                                  std::chrono::milliseconds timeout);
  static void format_status(std::ostringstream& o, const ImageWords& in);
  static std::vector<AxisSummary> summarize(const ImageWords& in);
};

// Declares the explicit specializations of CtlOf<T>'s functions that type T's folder defines. An
// explicit specialization must be declared before its first use in every translation unit that
// uses it (kCtlRowOf<T> below), or the program is ill-formed: each type's ctl_XXXX.hpp says this
// once, and its .cpp files include that header too, so that the definitions are checked against it.
#define STEPMOD_DECLARE_CTL_OF(T)                                                 \
  template <>                                                                     \
  plc::Outcome CtlOf<T>::run_command(const CtlRequest&, plc::Port&, ipc::Client&, \
                                     std::chrono::milliseconds);                  \
  template <>                                                                     \
  void CtlOf<T>::format_status(std::ostringstream&, const ImageWords&);           \
  template <>                                                                     \
  std::vector<AxisSummary> CtlOf<T>::summarize(const ImageWords&)

template <ModuleType T>
inline constexpr CtlRow kCtlRowOf{
    .type = T,
    .run_command = CtlOf<T>::run_command,
    .format_status = CtlOf<T>::format_status,
    .summarize = CtlOf<T>::summarize,
};

}  // namespace stepmod::tools::ctl
