// Accuracy classes of a run that reached T, by its error over time e (the largest displacement
// error over steps and particles) against the amplitude A of its solution (docs/studies.md,
// "Accuracy classes"): accurate below kAccurateFraction A, inaccurate from there up to A, and
// meaningless from A on (run.cpp's meaningless flag: the answer is as large as the solution).
#pragma once

#include <string_view>

namespace mpmstab {

inline constexpr double kAccurateFraction = 0.1;

enum class Accuracy { accurate, inaccurate, meaningless };

inline std::string_view to_string(Accuracy a) {
  switch (a) {
    case Accuracy::accurate:
      return "accurate";
    case Accuracy::inaccurate:
      return "inaccurate";
    case Accuracy::meaningless:
      return "meaningless";
  }
  return "";
}

inline Accuracy accuracy_class(double error_over_time, double A) {
  if (error_over_time > 0 && error_over_time >= A) return Accuracy::meaningless;
  if (error_over_time >= kAccurateFraction * A) return Accuracy::inaccurate;
  return Accuracy::accurate;
}

}  // namespace mpmstab
