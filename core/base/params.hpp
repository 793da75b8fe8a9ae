// Parameters of one run of the 1D bar: plain structs, validated in one place
// (scenes/validate.hpp: the checks need the scene each run poses).
//
// Every choice the paper's text leaves open is a named option here with the default documented
// in docs/theory.md ("Interpretation options and other choices").
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mpmstab {

// Shape functions (docs/theory.md, "The scheme"): linear hat ("mpm"), uGIMP with fixed half-width
// lp = h / (2 m) ("gimp"), or cpGIMP, whose half-width follows the deformation, lp = F_p h / (2 m)
// ("cpgimp"); a cpGIMP particle wider than two cells (lp > h) ends the run (support_too_wide);
// or the uniform quadratic or cubic B-spline ("bspline2", "bspline3"), whose node beyond a
// Dirichlet wall is eliminated by linear extrapolation (shape.hpp); or CPDI ("cpdi": the hat
// interpolated linearly between the two corners of cpGIMP's domain, which F_p carries). Eq. (108)
// is derived for the first three only: with the others the adaptive and min policies are refused
// and dt_stable is not measured.
enum class Method { mpm, gimp, cpgimp, bspline2, bspline3, cpdi };

// The basis is a B-spline (bspline2, bspline3): it eliminates its node beyond a Dirichlet wall.
constexpr bool is_bspline(Method m) {
  return m == Method::bspline2 || m == Method::bspline3;
}

// The particle's domain follows F_p (cpgimp, cpdi): wider than two cells it ends the run.
constexpr bool follows_F(Method m) {
  return m == Method::cpgimp || m == Method::cpdi;
}

// The paper's bound eq. (108) exists for this basis (mpm, gimp, cpgimp).
constexpr bool has_eq108(Method m) {
  return m == Method::mpm || m == Method::gimp || m == Method::cpgimp;
}

// The problem being solved (scene.hpp): the paper's bar ("bar", section 5.1: linear material,
// u = A sin(2 pi X) sin(c pi t)) or the manufactured solution of Steffen, Wallstedt, Guilkey,
// Kirby and Berzins (2008) ("steffen": neo-Hookean material, u = A sin(2 pi X) cos(c pi t)), or
// one free standing wave of the periodic linear bar ("mode": no body force,
// u = A sin(2 pi X) cos(2 pi c t), periodic boundaries only; the dispersion study's scene).
// Five scenes put a body inside a larger grid, with empty cells beside it (core/scenes/, one
// file each; docs/theory.md, "Scenes"): the axial vibration of a bar fixed at X = 0 and free at
// its other end ("vibration"), the same bar under a step force at its free end ("impulsive"),
// a column compacted by a ramped body force ("compaction"), a block in rigid translation
// ("block") and two bars meeting at speeds +v and -v ("impact"). In each, A is the scene's
// displacement scale (the tip amplitude, the largest tip or end displacement, the static
// compaction, the block's travel per time L / c with L = 1), so that A / h keeps its meaning.
enum class SceneKind { bar, steffen, mode, vibration, impulsive, compaction, block, impact };

// What a grid node with a sliver of mass does (docs/theory.md, "Small-mass nodes"). A node
// whose mass m_i is below small_mass_fraction * rho0 h (the mass of a node inside the body) is
// a small-mass node:
//  - none:     no treatment: a_i = f_i / m_i wherever m_i > 0;
//  - cutoff:   the node gets no acceleration, a_i = 0 and v_i = q_i / m_i (Uintah's
//              "minimum mass for acceleration");
//  - drop:     the node is dropped from the step: a_i = v_i = 0, as a node without mass;
//  - momentum: the node's new velocity is the mass-weighted mean of the particles' FLIP-updated
//              velocities, v_i = sum_p S_ip m_p v_p* / m_i, v_p* = v_p + dt sum_j S_jp a_j (the
//              velocity of the particles' momentum, as modified USL computes it for every node),
//              and its acceleration (v_i - q_i / m_i) / dt.
enum class SmallMass { none, cutoff, drop, momentum };

// Dirichlet: u = 0 at X = 0 and X = 1, a particle leaving [0, 1] ends the run as unstable.
// Periodic: node N is node 0; particles wrap around.
enum class Boundary { dirichlet, periodic };

// How g2p moves a particle: with the interpolated grid velocity v_i^{n+1} (default), or with the
// updated particle velocity v_p^{n+1} (the paper's eq. 10).
enum class PositionUpdate { grid, particle };

// Documented implementation choices of the MPM literature (docs/theory.md, "The scheme"). The first
// value of each is the default.
//  - walls (Dirichlet, GIMP supports): `clip` keeps nodes on [0, 1] only, so what a support
//    puts beyond a wall is dropped; `ghost` adds one free node beyond each wall (as codes that
//    extend the grid by one cell do), which takes part in every phase like an interior node; the
//    walls X = 0 and X = 1 stay fixed. For the B-splines: `clip` eliminates the node beyond each
//    wall by linear extrapolation, `modified` uses the boundary-modified splines of Steffen,
//    Kirby and Berzins (2008) (shape.hpp, SplineWalls); `ghost` is refused for them and
//    `modified` for every other basis.
//  - transfer (particle velocity in g2p): FLIP v_p += dt sum_i S_ip a_i; PIC v_p = sum_i S_ip v_i;
//    blend = flip_fraction * FLIP + (1 - flip_fraction) * PIC; APIC (Jiang et al. 2015): PIC's
//    velocity plus an affine velocity C_p per particle, C_p = sum_i G_ip v_i, which p2g carries
//    to the nodes as m_p (v_p + C_p (X_i - x_p)); XPIC(m) (Hammerquist and Nairn 2017) and FMPM(k)
//    (Nairn and Hammerquist 2021): PIC with the grid velocity corrected by m (or k) terms of the
//    series that approximates the full mass matrix (xpic.hpp), of order `xpic_order` or
//    `fmpm_order`; order 1 is PIC.
//  - update (when the stress is updated): USL after g2p with v_i^{n+1}; USF before the forces are
//    computed, with v_i^n = q_i / m_i (the paper's section 6); MUSL after g2p with the grid
//    velocity re-mapped from the updated particle velocities.
//  - body_force_time: b(X_p, t) at the start t^n of a step or at its end t^{n+1}.
enum class Walls { clip, ghost, modified };
enum class Transfer { flip, pic, blend, apic, xpic, fmpm };
enum class UpdateOrder { usl, usf, musl };
enum class BodyForceTime { start, end };
// How the particles' velocity starts (docs/theory.md, "The scheme"): `exact`, the exact v(X_p, 0);
// `half_step`, the exact v(X_p, -dt / 2). Symplectic Euler with USL is the leapfrog scheme with
// the velocity at half steps: the velocity the first position update uses is v^0 + dt a^0, which
// lies at t = dt / 2 only when v^0 lies at -dt / 2 (the staggered start of centred differences);
// starting from v(X_p, 0) leaves an O(dt) error where the acceleration at t = 0 is not zero. For
// the fixed and cfl policies (whose first dt is known) on the bar and the steffen scene.
enum class VelocityStart { exact, half_step };

// Eq. (108) leaves two points open; each is an option.
//  - sigma: section 4.6 rescales the stress as sigma / sqrt(E) (eq. 105) before stating eq. (108).
//    `scaled` uses sigma_max / sqrt(E) and (sigma F)_max / sqrt(E) in eq. (108) (default);
//    `raw` uses the unscaled stress as eq. (74) defines sigma_maxp.
//  - vnorm: ||v|| as the Euclidean norm of the nodal velocity vector (eq. 36, default) or its
//    maximum norm.
enum class StressScaling { scaled, raw };
enum class VelocityNorm { l2, max };

// How each step's dt is chosen (every policy lands exactly on T):
//  - fixed:    dt as given;
//  - cfl:      dt = C h / c, the speed-of-sound rule with Courant factor C (`cfl_factor`);
//  - adaptive: dt_n = s * eq. (108) bound of the current state (`safety` s);
//  - min:      dt_n = min(C h / c, s * eq. (108) bound);
//  - spectral: dt_n = s * the spectral limit (spectral.hpp) of the particles' layout when it was
//              last computed: at the start (the limit the record carries: Bloch for a uniform
//              layout, about 25 ms once per scheme in a process), and again, at the current
//              layout, by the dense map, each time the largest displacement any particle has
//              reached from its initial position grows by another h. A run computes it at most
//              max|u| / h + 1 times, each recomputation about 0.2-0.8 s of CPU at 100-200
//              particles; at most 600 particles.
// The bound of the current state is the one after the previous step; before the first step no
// grid velocity exists yet and the bound is taken with ||v|| = 0.
enum class TimeStepPolicy { fixed, cfl, adaptive, min, spectral };

// An adaptive or min run stops as unstable (dt_collapse) when the step its policy asks for falls
// below this fraction of the CFL step h / c: a run needing more than 1000 steps per cell
// crossing time of the wave is a policy that has failed, not a slow run (the bound collapses as
// the stress of a tangled state grows; GIMP at E = 1e8, A = 0.3 would otherwise take ~2e8 steps).
// The last step, shortened to land on T, is not checked.
inline constexpr double kDtCollapseFraction = 1e-3;

struct TimeStepping {
  TimeStepPolicy policy = TimeStepPolicy::fixed;
  double cfl_factor = 0.5;  // C
  double safety = 1.0;      // s
};

struct StableDtOptions {
  StressScaling sigma = StressScaling::scaled;
  VelocityNorm vnorm = VelocityNorm::l2;
};
// The four choices of StableDtOptions, numbered 0..3 (RunResult::dt_stable_min_of_option).
inline constexpr int kStableDtOptionCount = 4;
inline int option_index(const StableDtOptions& o) {
  return 2 * static_cast<int>(o.sigma) + static_cast<int>(o.vnorm);
}

// What a run measures beyond its verdict and final error. A run computes only what is asked:
// each flag switches a per-step observer on; all are cheap, histories are off by default.
struct Observe {
  bool error_over_time = true;  // max_error_over_time (and the "meaningless" flag)
  bool dt_stable = true;        // minimum of eq. (108) over the run
  bool crossings = true;        // cell-boundary crossings
  bool history = false;         // per-step rows (error, eq. 108, cumulative crossings)
  bool final_state = false;     // the particle state at the end, with the exact solution
  // The energies (energy.hpp): kinetic, strain, the body force's work and their balance at every
  // step, with the exact energies; off unless asked (a pass over the particles per step).
  bool energy = false;
  // The displacement error in L2 over the body and the run (error_l2.hpp); off unless asked.
  bool error_l2 = false;
  // The dense spectral limit of an initial layout that is not uniform (spectral.hpp; a uniform
  // layout's Bloch limit is on every record).
  bool spectral = false;
  // eq. (108) under every StableDtOptions, not only the run's own (RunResult::
  // dt_stable_min_of_option). Where the policy does not read eq. (108), the options change only
  // what is observed: one run then gives the records of cases that differ only in them.
  bool dt_stable_every_option = false;
  // In each history row, the displacement of the body's last particle (the largest X: the free
  // end of every scene that has one) beside the exact one there; off unless asked.
  bool tip = false;
  std::int64_t history_stride = 1;  // keep every k-th step in the history (and the last one)
};

// The largest order of XPIC(m) and FMPM(k): each order adds one pass from the grid to the
// particles and back per step.
inline constexpr int kMaxTransferOrder = 32;

// The initial particle layout, from the uniform one: particle k of cell i starts at
// X = (i + (k + 1/2 + shift + jitter u_ik) / ppc) h, with u_ik in [-1/2, 1/2) a fixed
// pseudo-random sequence of the particle's index (SplitMix64, the same on every platform).
// shift in (-1/2, 1/2) moves every particle by the same fraction of the spacing h / ppc (a
// uniform layout; near 1/2 every cell's last particle sits near a node); jitter in [0, 1) moves
// each by its own (particles keep their order and their cell).
struct Layout {
  double shift = 0;
  double jitter = 0;
};

struct RunParams {
  Method method = Method::gimp;
  double E = 4.0;    // Young's modulus
  double A = 0.015;  // amplitude of the manufactured solution
  double dt = 1e-3;  // time step
  double T = 1.0;    // final time
  int cells = 100;   // N, h = 1 / N
  int ppc = 2;       // particles per cell, m
  Boundary bc = Boundary::dirichlet;
  PositionUpdate position_update = PositionUpdate::grid;
  SceneKind scene = SceneKind::bar;
  Walls walls = Walls::clip;
  Transfer transfer = Transfer::flip;
  double flip_fraction = 0.95;  // FLIP share of a blend (transfer = blend only), in (0, 1)
  int xpic_order = 2;           // m of XPIC(m) (transfer = xpic only), 1..kMaxTransferOrder
  int fmpm_order = 2;           // k of FMPM(k) (transfer = fmpm only), 1..kMaxTransferOrder
  UpdateOrder update = UpdateOrder::usl;
  Layout layout;
  BodyForceTime body_force_time = BodyForceTime::start;
  VelocityStart start = VelocityStart::exact;
  // Where the body lies in the grid [0, 1], for the scenes whose body does not fill it
  // (SceneInfo in scene.hpp): its left end and its length. NaN: the scene's own (its
  // SceneInfo::body_start and body_length). Both must fall on cell boundaries.
  double body_start = std::numeric_limits<double>::quiet_NaN();
  double body_length = std::numeric_limits<double>::quiet_NaN();
  SmallMass small_mass = SmallMass::none;
  double small_mass_fraction = 1e-2;  // of rho0 h (small_mass other than none only)
  // A traction held on the free end of a bar fixed at X = 0 from t = 0 on, added to the
  // scene's own loads (the scenes whose SceneInfo::tip_load is set): tip_load * E A / (2 L),
  // the impulsive bar's traction, so that tip_load = 1 adds a largest tip displacement of A.
  // Its exact motion adds to the scene's (the law is linear; scenes/tip_load.hpp).
  double tip_load = 0;
  StableDtOptions stable;
  TimeStepping stepping;
  Observe observe;
  // Refuse, before running, a run that would need more steps than this (see README).
  std::int64_t max_steps = 200'000'000;
};

// A parameter that failed validation: `key` is the field name as it appears on the command line
// (without "--") and in JSON specs, so that callers can name the option or the key path.
struct ParamIssue {
  std::string key;
  std::string message;
};

// The parameters of a run that can change its result, by the names used as spec keys and CSV
// columns (the command line spells them with '-' for '_'). max_steps is a limit, not listed.
const std::vector<std::string>& parameter_names();

// Resource limits, so that no input can make a run allocate until the kernel kills it.
// Memory: the particle arrays (7 state arrays, the stencil's node index, weights and gradients
// for up to 4 nodes, the observers' per-particle values) take at most kBytesPerParticle per
// particle and the grid 40 bytes per node; a run may need at most kMaxRunBytes (2 GiB).
inline constexpr std::int64_t kBytesPerParticle = 160;
inline constexpr std::int64_t kMaxRunBytes = std::int64_t{2} << 30;
inline double run_bytes(const RunParams& p) {
  return double(p.cells) * p.ppc * kBytesPerParticle + (double(p.cells) + 1) * 40.0;
}
// The largest state the dense eigen-solver of the spectral limit is asked for (particles x
// values per particle; analysis/spectral.hpp): the spectral policy is refused above it.
inline constexpr std::int64_t kMaxSpectralState = 1200;
// History rows kept in memory (about 40 bytes each); a longer history is streamed instead.
inline constexpr std::int64_t kMaxHistoryRows = 10'000'000;

// Number of time steps the run takes: ceil(T / dt), the last one shortened to land on T.
// Returns nullopt when the count does not fit in 64 bits.
std::optional<std::int64_t> step_count(double T, double dt);

// The step of the fixed and cfl policies (dt, or C h / c); nullopt for the state-dependent ones.
std::optional<double> fixed_step(const RunParams& p);

// The dimensionless coordinates of a run (docs/theory.md, "Dimensionless coordinates"). With
// rho0 = 1 and c = sqrt(E), tau = c t removes E from both scenes: a run is fixed by the Courant
// number c dt / h, the amplitude in cells A / h, the wave passes c T / L (L = 1), the grid, the
// particles per cell and the method.
double wave_speed(const RunParams& p);          // c = sqrt(E / rho0)
double amplitude_per_cell(const RunParams& p);  // A / h = A N
double wave_passes(const RunParams& p);         // c T / L, L = 1 the grid's length
// c dt / h of the fixed and cfl policies; nullopt for the state-dependent ones.
std::optional<double> courant_number(const RunParams& p);

// Names used on the command line, in JSON and in reports.
std::string_view to_string(Method m);
std::string_view to_string(Boundary b);
std::string_view to_string(PositionUpdate u);
std::string_view to_string(StressScaling s);
std::string_view to_string(VelocityNorm n);
std::string_view to_string(TimeStepPolicy p);
std::string_view to_string(SceneKind s);
std::string_view to_string(Walls w);
std::string_view to_string(Transfer t);
std::string_view to_string(UpdateOrder u);
std::string_view to_string(BodyForceTime b);
std::string_view to_string(VelocityStart s);
std::string_view to_string(SmallMass s);

// Every name an enum's parse_* accepts, in the order of its table (messages list them).
// Defined for each enum of this header (explicit instantiations in params.cpp).
template <class Enum>
std::vector<std::string_view> names_of();
// "a, b or c": names as a message lists the accepted values.
std::string choices_text(const std::vector<std::string_view>& names);

std::optional<Method> parse_method(std::string_view s);
std::optional<Boundary> parse_boundary(std::string_view s);
std::optional<PositionUpdate> parse_position_update(std::string_view s);
std::optional<StressScaling> parse_stress_scaling(std::string_view s);
std::optional<VelocityNorm> parse_velocity_norm(std::string_view s);
std::optional<TimeStepPolicy> parse_time_step_policy(std::string_view s);
std::optional<SceneKind> parse_scene(std::string_view s);
std::optional<Walls> parse_walls(std::string_view s);
std::optional<Transfer> parse_transfer(std::string_view s);
std::optional<UpdateOrder> parse_update_order(std::string_view s);
std::optional<BodyForceTime> parse_body_force_time(std::string_view s);
std::optional<VelocityStart> parse_velocity_start(std::string_view s);
std::optional<SmallMass> parse_small_mass(std::string_view s);

// A number as text for messages: all 17 significant digits, or the shortest text that reads
// back as v.
std::string exact_text(double v);
std::string brief_text(double v);

// The implementation choices that differ from their defaults, for a one-line summary:
// ", walls modified, transfer xpic(3), update usf" (empty when all are at their defaults).
std::string nondefault_choices(const RunParams& p);

// True when every implementation choice above (scene, walls, transfer, update, body_force_time)
// is at its default: the runs of solver version 1, whose cache keys do not name these choices.
bool default_choices(const RunParams& p);

}  // namespace mpmstab
