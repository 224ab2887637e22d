#include "doctor/doctor.hpp"

#include <unistd.h>

#include <cmath>

#include "doctor/advice.hpp"
#include "doctor/board_facts.hpp"
#include "doctor/fitness.hpp"
#include "doctor/report.hpp"
#include "doctor/wake_probe.hpp"
#include "gpio/backend.hpp"
#include "config/config.hpp"

namespace stepmod::doctor {

namespace {

tools::Config config_of(const DoctorOptions& o) {
  if (!o.config.empty()) return tools::load_config(o.config);
  tools::Config c;
  c.axes.resize(1);
  return c;
}

std::string check_lines(const tools::Config& c, const std::vector<gpio::GpioChipInfo>& chips,
                        std::vector<LineCheck>& lines) {
  if (c.backend != tools::Config::Backend::kGpiod) return "backend sim: no line to check";
  const gpio::GpioChipInfo* chip = gpio::find_gpio_chip(chips, c.chip);
  if (chip == nullptr) return "chip '" + c.chip + "' NOT FOUND";
  for (unsigned a = 0; a < c.axes.size(); ++a) {
    const auto& ax = c.axes[a];
    const auto check = [&](std::string key, const std::optional<unsigned>& offset) {
      if (offset) lines.push_back({std::move(key), *offset, gpio::gpio_line_use(chip->path, *offset)});
    };
    const std::string axis = "axis" + std::to_string(a + 1) + ".";
    for (unsigned l = 0; l < kOutputLinesPerAxis; ++l) {
      check(axis + std::string(gpio::output_key(static_cast<OutputLine>(l))), ax.out[l]);
    }
    for (unsigned l = 0; l < kInputLinesPerAxis; ++l) {
      check(axis + std::string(gpio::input_key(static_cast<InputLine>(l))), ax.in[l]);
    }
    check(axis + "enable", ax.enable);
  }
  return "chip '" + c.chip + "' (" + chip->name + "), " + std::to_string(lines.size()) +
         " configured lines";
}

bool options_valid(const DoctorOptions& o, std::ostream& err) {
  if (!(o.seconds > 0 && o.seconds <= 3600)) {
    err << "stepmodctl doctor: --seconds must be > 0 and <= 3600\n";
    return false;
  }
  if (!(o.interval_us >= 10 && o.interval_us <= 1e6)) {
    err << "stepmodctl doctor: --interval-us must be 10 .. 1000000\n";
    return false;
  }
  if (!(o.speed >= 0 && std::isfinite(o.speed))) {
    err << "stepmodctl doctor: --speed must be >= 0\n";
    return false;
  }
  return true;
}

}  // namespace

int run_doctor(const DoctorOptions& o, std::ostream& out, std::ostream& err) {
  if (!options_valid(o, err)) return kUsage;
  tools::Config c;
  try {
    c = config_of(o);
  } catch (const tools::ConfigError& e) {
    err << "stepmodctl doctor: " << e.what() << "\n";
    return kUsage;
  }
  const SysRoot root(o.root);
  out << "stepmod doctor: " << (o.config.empty() ? "no --config (the defaults, one axis)" : o.config)
      << ", " << c.axes.size() << " axes, [rt] priority " << c.rt_priority << ", cpu " << c.rt_cpu
      << "\n";
  const BoardFacts facts = probe_board(root, c.rt_cpu, static_cast<int>(getpid()),
                                       static_cast<int>(getuid()));
  print_board(facts, c.rt_priority, out);
  const auto chips = gpio::list_gpio_chips(root.path("/dev"));
  std::vector<LineCheck> lines;
  const std::string lines_note = check_lines(c, chips, lines);
  print_gpio(chips, lines_note, lines, out);
  out << std::flush;

  WakeProbeOptions wo;
  wo.thread.priority = c.rt_priority;
  wo.thread.cpu = c.rt_cpu;
  wo.duration = static_cast<Nanos>(o.seconds * 1e9);
  wo.interval = static_cast<Nanos>(o.interval_us * 1e3);
  const WakeProbeResult wake = run_wake_probe(wo);
  print_wake(wake, wo, out);

  std::vector<std::uint32_t> lag_limits;
  for (const auto& a : c.axes) lag_limits.push_back(a.lag_limit_steps);
  const Fitness fit = judge_fitness(wake.late.worst(), c.late_limit_ns, lag_limits, o.speed);
  print_fitness(fit, advise({facts, c.rt_priority, wake.status, !fit.within_late_limit}), out);
  return fit.fit ? kFit : kNotFit;
}

}  // namespace stepmod::doctor
