// The spectral limit of a scheme: the largest time step at which its one-step map, linearised
// about rest with the particles frozen where they are, does not amplify any state
// (docs/theory.md, "The spectral limit").
//
// The state of the map is, per particle, the velocity and the strain, and APIC's affine
// velocity: s = (v_p / c, F_p - 1, C_p h / c). Linearised about rest (v_p = 0, F_p = 1,
// sigma_p = 0, C_p = 0) with the positions x_p frozen, one step of every scheme of this program
// is linear in s, and in these units it depends on dt only through the Courant number
// c dt / h: the limit is a Courant number, the same for every E. The map is taken from the
// program's own step (Simulation::advance_to) by central differences, column by column, so it
// is the map of exactly the code that runs; a quadratic term of the step (sigma_p F_p V_p^0,
// F_p (1 + dt L_p)) cancels exactly in a central difference.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "base/params.hpp"
#include "base/result.hpp"

namespace mpmstab {

// The largest Courant number searched, and the round-off tolerance on the spectral radius: a
// map is taken as not amplifying when its spectral radius is at most 1 + kSpectralTolerance.
inline constexpr double kMaxSpectralCourant = 8.0;
inline constexpr double kSpectralTolerance = 1e-8;

struct SpectralLimit {
  SpectralAnalysis analysis = SpectralAnalysis::dense;
  // c dt / h at the limit; none when the map does not amplify up to kMaxSpectralCourant.
  std::optional<double> courant;
  double radius_above = 0;  // the spectral radius just above the limit (growth per step)
  // The eigenvector of the largest eigenvalue just above the limit, as |component| per
  // particle, normalised to a largest value of 1: its velocity part and its strain part (dense:
  // every particle; Bloch: the particles of one cell).
  Eigen::ArrayXd mode_v, mode_strain;
  // Bloch: the limiting mode's wavenumber theta / pi, 1 for a mode alternating from cell to cell.
  std::optional<double> wavenumber;
  int evaluations = 0;  // maps built from the step
  int solves = 0;       // eigenvalue problems solved
};

// Sets out's limiting mode from the moduli of an eigenvector ordered as the state (velocities
// of `particles` particles, then their strains, then any APIC terms), normalised to a largest
// component of 1.
void set_limiting_mode(SpectralLimit& out, Eigen::ArrayXd moduli, Eigen::Index particles);

// The linearised one-step map at the Courant number `courant`, about rest with the particles at
// `x` (their count and order those of p's scene). `p` must be valid.
Eigen::MatrixXd linear_step_map(const RunParams& p, const Eigen::ArrayXd& x, double courant);
// The columns `columns` of that map (state index: velocity of particle k at k, its strain at
// n + k, its APIC affine term at 2 n + k, for n particles).
Eigen::MatrixXd linear_step_columns(const RunParams& p, const Eigen::ArrayXd& x, double courant,
                                    const std::vector<Eigen::Index>& columns);

// A map that is a polynomial of degree two in the Courant number, M(C) = M0 + C M1 + C^2 M2,
// from `build` at C = 0, 1 and 2, checked against build(1/2); where the check fails, every C
// is built. `builds` counts the calls of `build`.
std::function<Eigen::MatrixXd(double)> quadratic_in_courant(
    const std::function<Eigen::MatrixXd(double)>& build, int& builds);

// The search for the first amplifying Courant number: up from 1/4 by factors of 1.4 (to
// kMaxSpectralCourant), then bisection to a relative 1e-4; `near`, a limit expected close by,
// starts the bracket at 0.9 and 1.1 times it. Returns (largest not amplifying, smallest
// amplifying), none when nothing amplifies; `calls` counts the calls of `amplifies`.
std::optional<std::pair<double, double>> first_amplifying_courant(
    const std::function<bool(double)>& amplifies, std::optional<double> near, int& calls);

// The largest modulus of the eigenvalues of a square matrix.
double spectral_radius(const Eigen::MatrixXd& M);

// The spectral limit of p's scheme at the initial particle layout of its scene: the first
// Courant number, searched upwards from 1/4 by factors of 1.4 and then by bisection to a
// relative 1e-4, at which the spectral radius exceeds 1 + kSpectralTolerance. Requires a state
// of at most kMaxSpectralState values. E, A (but for the layout), dt, T and the policy do not
// enter.
SpectralLimit spectral_limit(const RunParams& p);
// The same with the particles frozen at `x` (their count and order those of p's scene); `near`,
// a limit expected close by (another layout's), starts the search at 0.9 and 1.1 times it: a
// window of amplification that opened and closed again below 0.9 times it would be missed.
SpectralLimit spectral_limit(const RunParams& p, const Eigen::ArrayXd& x,
                             std::optional<double> near = std::nullopt);

// spectral_limit(p, x, near).courant, without the limiting mode and its eigenvector solve: what
// the spectral policy needs at each new layout.
std::optional<double> spectral_courant_at(const RunParams& p, const Eigen::ArrayXd& x,
                                          std::optional<double> near = std::nullopt);

// What the limit of p's initial layout by `analysis` depends on (the scheme, the grid for
// dense, the layout): spectral_courant computes it once per key in a process.
std::string spectral_analysis_key(const RunParams& p, SpectralAnalysis analysis);

// The dense analyses of its initial layout a run of p asks for, for scheduling: the key of
// the one its record takes (a layout that is not uniform, recorded with `spectral`) or its
// spectral policy starts from, if any, and how many more the spectral policy may take as the
// layout moves (at most max|u| / h + 1, params.hpp; A / h + 1 here).
struct DenseAnalyses {
  std::optional<std::string> initial_key;
  double later = 0;
};
DenseAnalyses dense_analyses(const RunParams& p);

// The limit of p's initial layout by `analysis`, computed once per scheme, grid (dense only)
// and layout in a process, shared by threads. None when the analysis does not apply (dense:
// a state above kMaxSpectralState; Bloch: bloch_applies(p) false) or nothing amplifies.
std::optional<double> spectral_courant(const RunParams& p, SpectralAnalysis analysis);

}  // namespace mpmstab
