#pragma once
// The doctor's report, one section per line group, each starting with its name ("kernel:",
// "cpus:", "pulse cpu:", "rt throttling:", "cpu governor:", "rtprio:", "gpio chips:",
// "gpio lines:", "wake-up:", "safe rate:", "verdict:", "to raise it:").
#include <ostream>
#include <vector>

#include "doctor/board_facts.hpp"
#include "doctor/fitness.hpp"
#include "doctor/wake_probe.hpp"
#include "gpio/chip_survey.hpp"

namespace stepmod::doctor {

// A configured line and what the chip says of it.
struct LineCheck {
  std::string key;  // "axis1.step"
  unsigned offset = 0;
  gpio::GpioLineUse use;
};

void print_board(const BoardFacts& f, int priority, std::ostream& out);
void print_gpio(const std::vector<gpio::GpioChipInfo>& chips, const std::string& lines_note,
                const std::vector<LineCheck>& lines, std::ostream& out);
void print_wake(const WakeProbeResult& r, const WakeProbeOptions& o, std::ostream& out);
void print_fitness(const Fitness& f, const std::vector<std::string>& advice, std::ostream& out);

}  // namespace stepmod::doctor
