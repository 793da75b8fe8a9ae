// Accuracy classes of a run that reached T, by its error over time e (the largest displacement
// error over steps and particles) against the amplitude A of its solution (docs/design.md,
// "Accuracy classes"): accurate below kAccurateFraction A, inaccurate from there up to A, and
// meaningless from A on (run.cpp's meaningless flag: the answer is as large as the solution).
#pragma once

namespace mpmstab {

inline constexpr double kAccurateFraction = 0.1;

enum class Accuracy { accurate, inaccurate, meaningless };

inline Accuracy accuracy_class(double error_over_time, double A) {
  if (error_over_time > 0 && error_over_time >= A) return Accuracy::meaningless;
  if (error_over_time >= kAccurateFraction * A) return Accuracy::inaccurate;
  return Accuracy::accurate;
}

}  // namespace mpmstab
