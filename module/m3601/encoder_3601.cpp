// 3601 encoder functions: encoder move, preset encoder, diagnostic feedback and the encoder
// follower (3601 manual Ch.4 "Encoder Move", "Preset Encoder Position", "Diagnostic Feedback",
// "Encoder Follower"; digest 7.12).
#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"

namespace stepmod::module::m3601 {

void Personality3601::command_encoder_move(const ImageWords& /*out*/, bool /*absolute*/) {
  reject();
}

void Personality3601::command_preset_encoder(const ImageWords& /*out*/) { reject(); }

void Personality3601::command_follower(const ImageWords& /*out*/, planner::Direction /*dir*/) {
  reject();
}

void Personality3601::encoder_scan(const ImageWords& /*out*/) {}

void Personality3601::encoder_changed(Nanos /*t*/) {}

}  // namespace stepmod::module::m3601
