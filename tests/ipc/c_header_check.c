/* Compiled as C: proves ipc/stepmod_image.h is a valid C11 header for soft PLCs, and gives the
 * C++ tests a C-compiled user of the seqlock functions. */
#include "ipc/stepmod_image.h"

int stepmod_c_read_inputs(const stepmod_image_t* im, int32_t* out) {
  return stepmod_read_inputs(im, out);
}

void stepmod_c_write_outputs(stepmod_image_t* im, const int32_t* in) {
  stepmod_write_outputs(im, in);
}

void stepmod_c_heartbeat(stepmod_image_t* im) {
  stepmod_heartbeat(im);
}

unsigned stepmod_c_offset_of_input_image(void) {
  return (unsigned)offsetof(stepmod_image_t, input_image);
}

unsigned stepmod_c_panel_size(void) {
  return (unsigned)sizeof(stepmod_panel_t);
}
