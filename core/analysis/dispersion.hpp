// The dispersion of a scheme: how fast and how damped a Fourier mode of the uniform layout
// travels, from the Bloch symbol (bloch.hpp), and the period of the mode scene measured by a run
// (docs/theory.md, "Dispersion").
//
// The symbol S(theta) maps the state of a Fourier mode s_j = s e^{i j theta} of cell j over one
// step; theta is the phase per cell, so theta = k h for the wavenumber k and the cell size h
// (a wavelength of 2 pi / (k h) cells). The exact wave e^{i (k x -/+ omega t)}, omega = c k, turns
// by omega dt = C kh per step, C = c dt / h. Of the k x k eigenvalues of S (k = 2 or 3 values per
// particle times the particles per cell), two are acoustic: the right- and left-going waves,
// e^{-/+ i omega_num dt}, the same phase by the layout's mirror symmetry. The others are the
// modes a grid does not see (FLIP's velocity differences within a cell, strain differences that
// exert no force: eigenvalue 1), PIC's and the series' damped ones and APIC's affine ones. The
// *physical branch* is the acoustic eigenvalue of positive phase, followed continuously in kh:
//  - at the smallest kh of the scan (kh = pi / kDispersionSamples), it is the eigenvalue nearest
//    e^{i C kh} among those whose eigenvector is acoustic: at least half of its norm in the part
//    where every particle of the cell has the same velocity and the same strain (the grid's
//    mode; the invisible modes have none of it);
//  - from one kh to the next it is the eigenvalue whose eigenvector overlaps most with the last
//    one (|<w_prev, w>|, both of norm 1), a step of pi / kDispersionSamples; its phase is
//    unwrapped along the way (arg(lambda / lambda_prev) added), so it may pass pi.
// Its phase speed is c_num / c = arg(lambda) / (C kh) and its damping |lambda| per step. Where the
// two acoustic eigenvalues (lambda and its mirror image conj(lambda)) meet on the real axis, at
// phase 0 (PIC and the series transfers at small C, FLIP near its limit: the wave is overdamped)
// or at phase pi, they turn real and the wave stops propagating: the branch ends there, and at
// that kh and every larger one `propagates` is false, with phase and phase speed 0.
#pragma once

#include <complex>
#include <optional>
#include <vector>

#include "base/params.hpp"

namespace mpmstab {

// The steps of the continuation from kh = 0 to kh = pi (and of the scan for the cells per
// wavelength): kh = pi j / kDispersionSamples.
inline constexpr int kDispersionSamples = 1024;
// The phase error the cells per wavelength are given for: |c_num / c - 1| <= 1%.
inline constexpr double kPhaseTolerance = 0.01;

// The physical branch at one wavenumber.
struct DispersionPoint {
  double kh = 0;                    // phase per cell (rad), in (0, pi]
  std::complex<double> lambda = 0;  // the eigenvalue of S(kh)
  double phase = 0;                 // arg(lambda), unwrapped along the branch (rad per step)
  double phase_speed = 0;           // c_num / c = phase / (C kh), dimensionless
  double damping = 0;               // |lambda|, per step
  bool propagates = true;           // false from where the branch turns real
};

// The parameters whose Bloch symbol gives p's dispersion: p's scheme (basis, transfer, update,
// particles per cell, shift) on the bar at rest (A = 0, Dirichlet, clip walls; the walls do not
// enter the interior's symbol). Throws std::invalid_argument where the symbol does not apply
// (jitter, or a symbol larger than kMaxBlochSymbol).
RunParams dispersion_scheme(const RunParams& p);

// The physical branch of p's scheme at the Courant number C = c dt / h, at every kh of `khs`
// (ascending, in (0, pi]); the continuation passes through every kh = pi j / kDispersionSamples
// below each. Throws std::invalid_argument for kh outside (0, pi] or unsorted.
std::vector<DispersionPoint> dispersion_branch(const RunParams& p, double courant,
                                               const std::vector<double>& khs);
// The branch at one kh.
DispersionPoint dispersion_at(const RunParams& p, double courant, double kh);

// The cells per wavelength 2 pi / kh_max that p's scheme needs at the Courant number C for a
// phase error |c_num / c - 1| <= tolerance: kh_max is the first kh, scanning up from
// kh = pi / kDispersionSamples in steps of that size and then bisecting to a relative 1e-6, at
// which the error exceeds the tolerance (every longer wave is then within it). 2 (kh = pi, the
// shortest wave of the grid) when the error stays within the tolerance up to pi; nullopt when it
// exceeds the tolerance already at the first kh of the scan.
std::optional<double> cells_per_wavelength(const RunParams& p, double courant,
                                           double tolerance = kPhaseTolerance);

// The complex amplitude error of a wave of the branch after `periods` of its exact periods at the
// Courant number C: |lambda^n - e^{i omega n dt}| with n = periods 2 pi / (C kh) steps (n need not
// be a whole number: lambda^n = |lambda|^n e^{i n phase}, the phase unwrapped), which is
// | |lambda|^n e^{i n (phase - C kh)} - 1 |: its damping and its phase error together, per unit
// amplitude (0 is exact, 1 a wave damped away, 2 one in antiphase). Infinite where the branch does
// not propagate (it has no phase to carry the wave). Throws std::invalid_argument for C or
// periods not positive.
double amplitude_error(const DispersionPoint& d, double courant, double periods);

// The longest wave the search of cells_per_wavelength_amplitude reaches, in cells per wavelength
// (kh = 2 pi / kMaxCellsPerWavelength = pi / kDispersionSamples / 32).
inline constexpr double kMaxCellsPerWavelength = 65536;

// The cells per wavelength 2 pi / kh_max that p's scheme needs at the Courant number C for an
// amplitude error (amplitude_error) of at most `tolerance` after `periods` periods. kh_max is the
// first kh at which the error exceeds the tolerance, scanning up the kh of cells_per_wavelength
// (pi j / kDispersionSamples, the branch followed) and bisecting to a relative 1e-6; where the
// error exceeds the tolerance at the first of them already, kh is halved below it, each kh
// identified anew by the branch's start rule, down to 2 pi / kMaxCellsPerWavelength, and the
// bisection runs between the last halving within the tolerance and the one before. 2 when the
// error stays within the tolerance up to kh = pi; nullopt when it exceeds it at every kh down to
// 2 pi / kMaxCellsPerWavelength.
std::optional<double> cells_per_wavelength_amplitude(const RunParams& p, double courant,
                                                     double periods, double tolerance);

// The period of the mode scene (scene = mode: wavelength 1 on p.cells cells, kh = 2 pi / cells)
// that the physical branch predicts at p's step: 2 pi dt / arg(lambda), in units of time (the
// exact period is 1 / c; infinite where the branch does not propagate). Requires a fixed step
// (the fixed or cfl policy).
double predicted_mode_period(const RunParams& p);

// The period of the mode scene measured by a run of p (scene mode, periodic, the fixed or cfl
// policy; any amplitude): the projection of the particle displacement on the mode,
//   a(t) = sum_p V_p^0 (x_p - X_p) sin(2 pi X_p) / sum_p V_p^0 sin^2(2 pi X_p),
// after every step to T; each extremum of a (a step whose value is a strict maximum or minimum
// of its neighbours') is located at the turning point of the quartic through the five values
// around it (the root of its derivative, by bisection); the period is twice the time from the
// first extremum to the last divided by the half periods between them. Extrema rather than zero
// crossings: the displacement is the sum of the grid velocities over the steps, so it carries a
// constant offset beside the oscillation (dt times the velocity mode's beta / (1 - lambda)); a
// scheme that damps (|lambda| < 1: FLIP, and more so PIC, on a coarse grid) shrinks the
// oscillation under the offset, which moves zero crossings later and later but leaves the
// turning points of c + r^n cos(n omega dt + phi) evenly spaced, half a period apart. Extrema
// after the oscillation has decayed below kModeNoiseFloor times |a(0)| are not counted.
inline constexpr double kModeNoiseFloor = 1e-6;
struct ModePeriod {
  double period = 0;   // in units of time (0 when fewer than two extrema were found)
  double periods = 0;  // the periods between the first and the last extremum (half-integer)
  int extrema = 0;     // extrema counted
  double first_extremum = 0, last_extremum = 0;
};
// Throws std::invalid_argument for a p that is not a valid fixed-step run of the mode scene.
ModePeriod measure_mode_period(const RunParams& p);

}  // namespace mpmstab
