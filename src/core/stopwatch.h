// Milliseconds between laps: the stage timings of an extraction.
#ifndef ENHANCED_ORB_STOPWATCH_H
#define ENHANCED_ORB_STOPWATCH_H

#include <chrono>

namespace enhanced_orb {

class Stopwatch {
public:
  // Milliseconds since the last call (or construction).
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_STOPWATCH_H
