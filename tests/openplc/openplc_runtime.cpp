#include "tests/openplc/openplc_runtime.hpp"

#include <cstring>

// ---- what OpenPLC's glueVars.cpp, main.cpp, utils.cpp and modbus.cpp define -------------------
IEC_BOOL* bool_input[BUFFER_SIZE][8];
IEC_BOOL* bool_output[BUFFER_SIZE][8];
IEC_BYTE* byte_input[BUFFER_SIZE];
IEC_BYTE* byte_output[BUFFER_SIZE];
IEC_UINT* int_input[BUFFER_SIZE];
IEC_UINT* int_output[BUFFER_SIZE];
IEC_UDINT* dint_input[BUFFER_SIZE];
IEC_UDINT* dint_output[BUFFER_SIZE];
IEC_ULINT* lint_input[BUFFER_SIZE];
IEC_ULINT* lint_output[BUFFER_SIZE];
IEC_UINT* int_memory[BUFFER_SIZE];
IEC_UDINT* dint_memory[BUFFER_SIZE];
IEC_ULINT* lint_memory[BUFFER_SIZE];
IEC_ULINT* special_functions[BUFFER_SIZE];
pthread_mutex_t bufferLock = PTHREAD_MUTEX_INITIALIZER;
unsigned long long common_ticktime__ = 5'000'000;  // 5 ms task

IEC_UINT mb_input_regs[1024];
IEC_UINT mb_holding_regs[8192];

namespace {
std::function<void()> g_bind;
std::string g_log;
}  // namespace

// utils.cpp: OpenPLC's log (here a string the tests read).
extern "C" void openplc_log(char* logmsg) {
  g_log += logmsg;
}

void glueVars() {
  if (g_bind) g_bind();
}

// modbus.cpp, for the word registers (MAX_INP_REGS = 1024; %QW below MIN_16B_RANGE = 1024).
void mapUnusedIO() {
  pthread_mutex_lock(&bufferLock);
  for (int i = 0; i < 1024; i++) {
    if (int_input[i] == nullptr) int_input[i] = &mb_input_regs[i];
  }
  for (int i = 0; i < 1024; i++) {
    if (int_output[i] == nullptr) int_output[i] = &mb_holding_regs[i];
  }
  pthread_mutex_unlock(&bufferLock);
}

// utils.cpp (the word outputs; bool and byte outputs are not modelled).
void disableOutputs() {
  for (int i = 0; i < BUFFER_SIZE; i++) {
    if (int_output[i] != nullptr) *int_output[i] = 0;
  }
}

namespace openplc {

void start(const std::function<void()>& bind) {
  g_bind = bind;
  glueVars();
  initializeHardware();
  updateBuffersIn();
  updateBuffersOut();
  glueVars();
  mapUnusedIO();
}

void scan(const std::function<void()>& program) {
  glueVars();
  updateBuffersIn();
  pthread_mutex_lock(&bufferLock);
  program();
  pthread_mutex_unlock(&bufferLock);
  updateBuffersOut();
}

void stop() {
  disableOutputs();
  updateBuffersOut();
  finalizeHardware();
}

void reset() {
  g_bind = nullptr;
  for (auto& p : int_input) p = nullptr;
  for (auto& p : int_output) p = nullptr;
  std::memset(mb_input_regs, 0, sizeof mb_input_regs);
  std::memset(mb_holding_regs, 0, sizeof mb_holding_regs);
}

std::string& log() {
  return g_log;
}

}  // namespace openplc
