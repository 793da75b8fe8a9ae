// The spectral limit of the interior of a uniform layout, by Bloch (Fourier) analysis
// (docs/theory.md, "The spectral limit", "Bloch analysis").
//
// At a uniform layout (every cell holds its particles at the same offsets) the linearised
// one-step map is the same from every cell to its neighbours, away from the walls: the state of
// cell j + d responds to that of cell j through a block B_d (k x k, k = values per particle x
// particles per cell) that does not depend on j. A Fourier mode s_j = s e^{i j theta} is then
// mapped to S(theta) s e^{i j theta} with the symbol S(theta) = sum_d B_d e^{i d theta}, and the
// interior amplifies nothing while every S(theta) has spectral radius at most 1. The blocks
// come from the program's own step (linear_step_columns) on a bar long enough that the response
// to one cell vanishes four cells short of either wall. The limit holds for the interior of
// a long bar at any grid size; the walls' own modes are not in it (a bar's dense limit can
// differ where a wall mode limits: the spectral study shows both).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "analysis/spectral.hpp"
#include "base/params.hpp"

namespace mpmstab {

// The number of wavenumbers theta = pi j / kBlochSamples (j = 0..kBlochSamples) at which the
// symbol's radius is taken.
inline constexpr int kBlochSamples = 256;

// Whether p's scene starts from a uniform layout (the bar at every A; the steffen and mode
// scenes at A = 0).
bool uniform_layout(const RunParams& p);
// The largest symbol the Bloch limit is computed for (values per particle x particles per cell:
// 12 particles per cell, 8 with APIC); its cost grows with the cube.
inline constexpr int kMaxBlochSymbol = 24;
// Whether bloch_limit(p) is computed: a uniform layout and a symbol of at most kMaxBlochSymbol.
bool bloch_applies(const RunParams& p);

// The symbol S(theta) at the Courant number `courant`: k x k, k = values x particles per cell,
// ordered as the state (the velocities v / c of the cell's particles, then their strains, then
// APIC's C h / c), for the mode s_j = s e^{i j theta} of cell j.
Eigen::MatrixXcd bloch_symbol(const RunParams& p, double courant, double theta);

// The Bloch limit of p's scheme (p's cells do not enter): the first Courant number, searched as
// spectral_limit does, at which some S(theta) has spectral radius above 1 + kSpectralTolerance.
// Requires bloch_applies(p). The mode is that of the largest eigenvalue just above the limit:
// its wavenumber and its |velocity| and |strain| per particle of a cell.
SpectralLimit bloch_limit(const RunParams& p);
// bloch_limit(p).courant without the mode (the sweep over every wavenumber just above the limit
// and an eigenvector solve): what each run's record carries.
std::optional<double> bloch_courant(const RunParams& p);

}  // namespace mpmstab
