#pragma once
// The parts of OpenPLC v3's runtime (webserver/core: glueVars.cpp, main.cpp, utils.cpp,
// modbus.cpp) that a hardware layer meets, modelled on their code as it is (OpenPLC_v3 commit
// bb35f69): the buffers, bufferLock, mapUnusedIO() and disableOutputs(), and main.cpp's order of
// calls -- start, scan, stop. Definitions live in openplc_runtime.cpp (one per test binary).
#include <functional>
#include <string>

#include "tests/openplc/ladder.h"

// OpenPLC's Modbus slave registers (modbus.cpp): what mapUnusedIO() binds unused %IW/%QW to.
// MAX_INP_REGS = 1024 input registers; holding registers 0..1023 back %QW0..%QW1023.
extern IEC_UINT mb_input_regs[1024];
extern IEC_UINT mb_holding_regs[8192];

namespace openplc {

// main.cpp before the main loop: glueVars() (the program's bindings, `bind`), then
// initializeHardware(), one updateBuffersIn() and updateBuffersOut(), then mapUnusedIO().
void start(const std::function<void()>& bind);
// One pass of main.cpp's main loop: updateBuffersIn(); lock bufferLock; the program; unlock;
// updateBuffersOut().
void scan(const std::function<void()>& program);
// main.cpp after the loop: disableOutputs(); updateBuffersOut(); finalizeHardware().
void stop();
// Every pointer back to NULL and the Modbus registers to 0 (between tests).
void reset();
// What the layer logged through utils.cpp's openplc_log() (clear it at will).
std::string& log();

}  // namespace openplc
