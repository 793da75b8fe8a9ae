// The advice study's settings and the runs each is checked by, as results/advice.json stores them:
// what `mpmstab advise` predicts from before it verifies (advice_verify.hpp).
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/params.hpp"

namespace mpmstab {

// ---------------------------------------------------------------------------------------------
// Regions (docs/studies.md, "Advice: verified on the problem"). A setting is a method, a grid of
// `cells` cells with 2 particles each and a Courant number C = c dt / h; its base run solves the
// bar with walls at the middle amplitude to the shorter length. E only rescales time, so a region
// is stated in A / L, c T / L, scene, boundary, layout and cells, and checked at its corners:
//   - on the bar with walls, at the smallest, middle and largest amplitude, to each length;
//   - at the largest amplitude, to each length: periodic, on the neo-Hookean scene (Steffen et
//     al. 2008) and on layouts jittered by each of `jitters` of the particle spacing, across the
//     jitter `mpmstab advise` answers;
//   - on `refine` times the cells at the same C, at the middle amplitude, to the shorter length.
// A corner passes when its run ends stable and accurate (below kAccurateFraction A). A failing
// corner is excluded, and the region says so: the amplitudes stop below it; periodic, the other
// scene are in only where their corner and the largest amplitude pass, the jittered layouts up
// to the largest jitter below which every jittered corner passes;
// finer grids only where the refined corner passes. A region exists to a length only where the
// base run to it passes and C is within the spectral limit / limit_margin. It describes where
// the runs passed; no answer is given from it (the error between its runs is not measured).
// The paper's largest amplitude, A / L (reference/paper/table1.csv; a test checks it there): the
// largest corner's, and where tradeoff verifies each cheapest setting it names.
inline constexpr double kPaperLargestA = 5e-2;
struct RegionRule {
  std::array<double, 3> amplitudes{1e-3, 1.5e-2,
                                   kPaperLargestA};  // A / L: smallest, middle, largest
  std::array<double, 2> lengths{10, 100};            // c T / L: the base's, the longest
  int refine = 8;                                    // the finest grid: cells x refine
  // The jittered corners: particles moved up to jitter / 2 of their spacing, for each.
  std::array<double, 3> jitters{0.05, 0.2, 0.5};
  double limit_margin = 1.25;  // C at most the spectral limit / limit_margin
};
inline constexpr RegionRule kRegionRule{};
// Every run of the advice study is at this E: c = 1, so that T is c T (E only rescales time).
inline constexpr double kAdviceE = 1;

enum class CornerKind { base, smallest_A, largest_A, periodic, other_scene, jittered, finer };
std::string_view to_string(CornerKind k);  // its name in results/advice.json
// A kind in a report's words: "base", "periodic", "neo-Hookean", "jittered" (else empty).
std::string_view corner_words(CornerKind k);

struct Corner {
  CornerKind kind = CornerKind::base;
  double length = 0;  // c T / L
  double jitter = 0;  // the layout's (the jittered corners')
  RunParams params;
};

// The corner runs of a setting whose base run is `base` (the bar with walls, A = the middle
// amplitude, T = the shorter length / c), in a fixed order: per length, the base (the longer
// length only: the base run is the case itself), the smallest and largest amplitude, periodic,
// the other scene and the jittered layouts, by jitter; then the finer grid.
std::vector<Corner> region_corners(const RunParams& base, const RegionRule& rule = kRegionRule);
inline constexpr std::size_t kRegionCorners = 16;

// One corner run as a setting's region reads it.
struct CornerRun {
  CornerKind kind = CornerKind::base;
  double length = 0, A = 0;
  double jitter = 0;  // the layout's jitter (of the particle spacing; 0: uniform)
  int cells = 0;
  std::string outcome;                 // unstable, meaningless, stable, too_short
  std::optional<double> error_over_A;  // error over time / A, where measured
  bool passes() const;                 // stable and accurate
};

// A setting's region to one length.
struct Region {
  double length = 0;            // checked to c T / L = length
  double A_min = 0, A_max = 0;  // A / L
  bool periodic = false, other_scene = false, finer = false;
  double jitter = 0;                // jittered layouts up to this jitter (0: uniform only)
  int cells_max = 0;                // the setting's cells, or cells x refine
  double error_over_A = 0;          // the largest error over time / A of its corners
  std::vector<CornerRun> excluded;  // the corners that failed, and what they excluded
};

// A setting with its corners and regions: what advice.json stores and `mpmstab advise` reads.
struct CheckedSetting {
  std::string method, transfer, update;  // "gimp", "flip", "usl"; transfer with its order
  int cells = 0, ppc = 2;
  double courant = 0;
  std::optional<double> courant_spectral;  // the spectral limit of its uniform layout
  std::vector<CornerRun> corners;          // the base run first, then region_corners() order
  std::vector<Region> regions;             // per length at which a region exists, ascending
  // The corner run of a kind to a length (nullptr where it was not run); a jittered one at a
  // jitter.
  const CornerRun* corner(CornerKind kind, double length, double jitter = 0) const;
  // "gimp/apic/usl": basis, transfer and update order.
  std::string method_text() const { return method + "/" + transfer + "/" + update; }
};

// The regions of a setting from its corner runs (the base run first).
std::vector<Region> regions_of(const CheckedSetting& s, const RegionRule& rule = kRegionRule);

// A problem in the dimensionless form of `mpmstab advise`.
struct Problem {
  double A = 0;       // A / L
  double cT = 0;      // c T / L
  double target = 0;  // error over time / A
  std::string scene = "bar";
  std::string bc = "dirichlet";
  std::vector<std::string> methods;  // empty: every method
};

// A method filter's entry names a basis ("gimp"), a method ("gimp/apic", "gimp/musl") or a
// method with every part ("gimp/flip/usl"); an empty filter selects every setting.
bool advice_selected(const CheckedSetting& s, const std::vector<std::string>& methods);
// The options of `mpmstab run` that give a setting's transfer ("fmpm(2)": --fmpm-order 2).
std::string transfer_options(const std::string& transfer);

// The setting's name: "gimp/apic usl, 50 cells, C = 0.25".
std::string setting_name(const CheckedSetting& s);
// Where a setting's runs passed, in words: "A/L 1e-3 to 0.05, c T/L to 100; walls and periodic;
// the bar and the neo-Hookean scene; uniform and jittered (0.05); and one run on 400 cells (A/L
// 0.015, walls, the bar, uniform, to c T/L 10)".
std::string region_text(const Region& r, const RegionRule& rule = kRegionRule);

nlohmann::ordered_json to_json(const CheckedSetting& s);
// Throws InputError naming the key for a malformed setting (results/advice.json is an input).
// A transfer as a setting names it, with its parameter where it has one ("fmpm(2)",
// "blend(0.99)"): the name before the parenthesis, or "" when the parenthesis is not closed at
// the end.
std::string transfer_name(const std::string& transfer);
// Refuses (InputError) a method, transfer or update the solver does not know.
CheckedSetting checked_setting_from_json(const nlohmann::ordered_json& j);
// Every setting of an advice results document; throws InputError naming a malformed one's key.
std::vector<CheckedSetting> checked_settings_of(const nlohmann::ordered_json& doc);

}  // namespace mpmstab
