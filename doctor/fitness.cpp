#include "doctor/fitness.hpp"

#include <algorithm>

namespace stepmod::doctor {

Fitness judge_fitness(Nanos worst_pause, Nanos late_limit, std::span<const std::uint32_t> lag_limits,
                      double needed_rate) {
  Fitness f;
  f.worst_pause = worst_pause;
  f.late_limit = late_limit;
  f.needed_rate = needed_rate;
  f.within_late_limit = late_limit <= 0 || worst_pause <= late_limit;
  f.fit = f.within_late_limit;
  // A wake-up on time still takes the clock's resolution: never divide by less than 1 us.
  const double pause_s = static_cast<double>(std::max<Nanos>(worst_pause, kNsPerUs)) / 1e9;
  for (std::size_t i = 0; i < lag_limits.size(); ++i) {
    AxisRate r{static_cast<unsigned>(i + 1), lag_limits[i], 0};
    r.safe_rate = f.within_late_limit ? lag_limits[i] / pause_s : 0;
    if (r.safe_rate < needed_rate) f.fit = false;
    f.axes.push_back(r);
  }
  return f;
}

}  // namespace stepmod::doctor
