// Stand-in for OpenPLC v3's webserver/core/ladder.h (stepmod's own file): the declarations a
// hardware layer compiles against, with OpenPLC's names, types and signatures, so that
// openplc/stepmod_hardware_layer.cpp is built here exactly as inside an OpenPLC tree. The
// definitions (buffers, lock, log) come from the test driver, as glueVars.cpp and main.cpp
// provide them in OpenPLC.
#ifndef STEPMOD_OPENPLC_LADDER_STANDIN_H
#define STEPMOD_OPENPLC_LADDER_STANDIN_H

#include <pthread.h>
#include <stdint.h>
#include <time.h>

#define BUFFER_SIZE 1024

typedef uint8_t IEC_BOOL;
typedef int8_t IEC_SINT;
typedef int16_t IEC_INT;
typedef int32_t IEC_DINT;
typedef int64_t IEC_LINT;
typedef uint8_t IEC_USINT;
typedef uint16_t IEC_UINT;
typedef uint32_t IEC_UDINT;
typedef uint64_t IEC_ULINT;
typedef uint8_t IEC_BYTE;
typedef uint16_t IEC_WORD;
typedef uint32_t IEC_DWORD;
typedef uint64_t IEC_LWORD;
typedef float IEC_REAL;
typedef double IEC_LREAL;

// Located variables: a NULL entry is an address the PLC program does not use.
extern IEC_BOOL* bool_input[BUFFER_SIZE][8];
extern IEC_BOOL* bool_output[BUFFER_SIZE][8];
extern IEC_BYTE* byte_input[BUFFER_SIZE];
extern IEC_BYTE* byte_output[BUFFER_SIZE];
extern IEC_UINT* int_input[BUFFER_SIZE];   // %IW
extern IEC_UINT* int_output[BUFFER_SIZE];  // %QW
extern IEC_UDINT* dint_input[BUFFER_SIZE];
extern IEC_UDINT* dint_output[BUFFER_SIZE];
extern IEC_ULINT* lint_input[BUFFER_SIZE];
extern IEC_ULINT* lint_output[BUFFER_SIZE];
extern IEC_UINT* int_memory[BUFFER_SIZE];
extern IEC_UDINT* dint_memory[BUFFER_SIZE];
extern IEC_ULINT* lint_memory[BUFFER_SIZE];
extern IEC_ULINT* special_functions[BUFFER_SIZE];

// Guards the buffers against the runtime's other threads (Modbus slave, web server...).
extern pthread_mutex_t bufferLock;
extern unsigned long long common_ticktime__;

// glueVars.cpp: binds the program's located variables (the driver's Program does it).
void glueVars();

// The hardware layer's four functions (main.cpp calls them; see openplc_runtime.hpp).
void initializeHardware();
void finalizeHardware();
void updateBuffersIn();
void updateBuffersOut();

// utils.cpp: every non-NULL output pointer set to 0 (main.cpp at stop, then updateBuffersOut()).
void disableOutputs();

// modbus.cpp: every NULL %IX/%QX/%IW/%QW/%MW pointer pointed at OpenPLC's own Modbus slave
// registers (main.cpp, after the first updateBuffersIn/Out), which its Modbus clients read and
// write under bufferLock.
void mapUnusedIO();

// utils.cpp
extern "C" void openplc_log(char* logmsg);

#endif
