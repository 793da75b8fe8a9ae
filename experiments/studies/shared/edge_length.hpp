// Edges tested for length (docs/studies.md, "The stability edges"). An edge in dt is found for
// the run length searched. Every edge a report prints (below the spectral limit too: a mode that
// does not grow in the linearised step can grow through the nonlinear terms) is rerun at its dt
// for kLengthFactors times its wave passes c T, at most kLongPasses, and printed as holding to
// the longest length it passed or as transient, with the length at which it failed. A survival
// edge passes a length when its run survives it; an accuracy edge when its run ends stable and
// accurate (docs/studies.md, "Accuracy classes").
#pragma once

#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/params.hpp"
#include "claims.hpp"
#include "spec.hpp"

namespace mpmstab {

inline constexpr double kLongPasses = 1000;
inline constexpr std::array<double, 2> kLengthFactors = {10, 100};

// The row's search found survival monotone in dt (column monotone; a row without one: no search).
bool survival_monotone(const nlohmann::ordered_json& row);
// ", **not monotone**: survives again at up to c dt/h = 0.237" where the row's search found a dt
// above its lowest failure that survives (the edge stays below that failure); "" where survival
// is monotone (core/run/edge.hpp, edge_line).
std::string monotone_words(const nlohmann::ordered_json& row);

// The edges of a row (dt_edge, then dt_accurate where it differs).
std::vector<double> edges_of(const nlohmann::ordered_json& row);

// The wave passes an edge of a case run to c T is rerun for, ascending: kLengthFactors x c T, at
// most kLongPasses, each longer than c T.
std::vector<double> test_lengths(double cT);

// The runs at the fixed step dt for each test length of `base`.
std::vector<RunParams> length_runs(const RunParams& base, double dt);

// What one run at an edge's dt for a test length found: the length asked, the wave passes it
// reached (the length when it survived), its outcome and its error over time per A.
struct LongRun {
  double dt = 0;
  double length = 0;
  double passes = 0;
  bool survived = false;
  std::string outcome;
  std::optional<double> error_over_A;
  bool accurate() const;  // stable with an error over time below kAccurateFraction A
};

// The runs of every edge of every row, each found by what it was asked for (its case, its edge's
// dt and its length: length_role), by row address; rows whose runs are missing get none.
// `case_of[i]` is the case rows[i] stands for (default: the i-th).
using LengthRuns = std::map<const nlohmann::ordered_json*, std::vector<LongRun>>;
LengthRuns read_length_runs(const std::vector<nlohmann::ordered_json>& rows,
                            const std::vector<nlohmann::ordered_json>& follow_up,
                            const std::vector<std::size_t>& case_of = {});
// The follow-up runs read_length_runs reads, for rows[i] and its case `cases[i]`, each asked for
// case case_of[i] (default: i).
std::vector<FollowUp> all_length_runs(const std::vector<nlohmann::ordered_json>& rows,
                                      const std::vector<CaseSpec>& cases,
                                      const std::vector<std::size_t>& case_of = {});
// What a length rerun is for: "length rerun 2 of dt 1.2e-3", the second of test_lengths().
std::string length_role(double dt, std::size_t k);

// How far an edge (dt_col: "dt_edge" or "dt_accurate") holds: the first test length it does not
// pass, or the longest it passed. With `bound`, a survival edge passes a length only where its
// run also keeps its error over time at most bound A (the bounded edge of spectral_edge).
struct Lasting {
  bool tested = false, holds = false;
  double length = 0;  // the longest passed (holds), or where the failing run failed
  const LongRun* failing = nullptr;
  const LongRun* longest = nullptr;  // the longest run (holds)
};
Lasting lasting(const LengthRuns& runs, const nlohmann::ordered_json& row, const char* dt_col,
                std::optional<double> bound = std::nullopt);

// "holds to c T = 1000", "holds to c T = 200 (meaningless there)", "**transient**: fails at
// c T = 530", "**transient**: not accurate at c T = 80 (0.31 A)", "not tested for length".
std::string lasting_text(const LengthRuns& runs, const nlohmann::ordered_json& row,
                         const char* dt_col, std::optional<double> bound = std::nullopt);

// How many edges were rerun for length, how many held, and where the others failed.
struct LengthTally {
  int tested = 0, held = 0;
  std::vector<double> failed_at;
  void add(const Lasting& l);
};

// The claim that every edge of `t` holds for length: `statement` may name {first}, {second}
// (kLengthFactors) and {cap} (kLongPasses), `evidence` {held} and {tested}; it is over the
// edges tested.
Claim length_claim(std::string id, std::string statement, std::string evidence,
                   const LengthTally& t);

}  // namespace mpmstab
