// The text summary of one run, as `mpmstab run` prints it and README.md's generated example
// shows it: the verdict (with its accuracy class and error over time / A where it is stable),
// then every measured quantity, and last the wall time (which no generated document shows).
#pragma once

#include <string>

#include "base/result.hpp"

namespace mpmstab {

// "%.4g" of v.
std::string fmt(double v);
// The summary; without `with_timing`, the lines of the wall time and ns per particle-step are
// left out (they vary from run to run).
std::string text_summary(const RunResult& r, bool with_timing = true);

}  // namespace mpmstab
