// 3601 blend moves: the block-by-block programming handshake and Run Blend (3601 manual Ch.4
// "Blend Move", Ch.5 "Blend Move Programming"; digest 3.8, 7.10).
#include "module/m3601/params_3601.hpp"
#include "module/m3601/personality_3601.hpp"

namespace stepmod::module::m3601 {

void Personality3601::blend_programming_scan(const ImageWords& /*out*/) {}

void Personality3601::command_run_blend(const ImageWords& /*out*/, planner::Direction /*dir*/) {
  reject();  // 3601-CE-20: no profile stored
}

std::uint16_t Personality3601::blend_status_lsw() const noexcept { return 0; }

}  // namespace stepmod::module::m3601
