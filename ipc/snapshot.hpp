#pragma once
// One consistent seqlock snapshot of image words into ImageWords (docs/interface.md 3.1),
// shared by the module's side (ShmImage) and the PLC's side (Client).
#include "core/module_shape.hpp"
#include "ipc/stepmod_image.h"

namespace stepmod::ipc {

// `out` is left as it was when every one of `tries` attempts overlapped a write.
inline bool read_snapshot(const std::uint32_t* seq, const stepmod_words_t* words,
                          unsigned word_bytes, unsigned n, unsigned tries,
                          ImageWords& out) noexcept {
  ImageWords tmp;
  if (!stepmod_seq_read(seq, words, word_bytes, n, tmp.w.data(), tries)) return false;
  out = tmp;
  return true;
}

}  // namespace stepmod::ipc
