#pragma once
// The last error reason of an axis/channel (image offset 448 + 64 x unit, under the input
// seqlock): sequence, checklist item code and the sentence. A daemon that does not write reasons
// leaves the block zero: sequence 0, empty text.
#include <cstdint>
#include <nlohmann/json.hpp>

#include "ipc/stepmod_image.h"

namespace stepmod::web {

// {"seq": n, "item": code, "text": "3601-CE-05: ...", "cut": the sentence filled the image's
// field (the daemon's log has it whole)}; an empty object when no consistent read. Rates in the
// sentence are given in the form's unit (`accel_word_unit` 1000: steps/ms/s; reason_help.hpp).
nlohmann::json reason_json(const stepmod_image_t& img, unsigned unit,
                           std::int64_t accel_word_unit = 1);

}  // namespace stepmod::web
