#pragma once
// The last error reason of an axis/channel (image offset 448 + 64 x unit, under the input
// seqlock): sequence, checklist item code and the sentence. A daemon that does not write reasons
// leaves the block zero: sequence 0, empty text.
#include <nlohmann/json.hpp>

#include "ipc/stepmod_image.h"

namespace stepmod::web {

// {"seq": n, "item": code, "text": "3601-CE-05: ..."}; an empty object when no consistent read.
nlohmann::json reason_json(const stepmod_image_t& img, unsigned unit);

}  // namespace stepmod::web
