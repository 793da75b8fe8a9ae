// The paper's Table 1 as transcribed (reference/paper/table1.csv): its cells, how a case finds
// the cell it is compared with, and the factor-3 rule every comparison with it uses. Shared by
// the studies that read Table 1 against ours (table1, variants, comparison).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "spec.hpp"

namespace mpmstab {

// A paper cell as transcribed: a number, "*" (unstable), or unreadable/missing text.
struct PaperValue {
  enum Kind { number, unstable, unreadable } kind = unreadable;
  double value = 0;
  std::string text;
};

PaperValue paper_value(const std::string& text);
std::string show(const PaperValue& p);

struct PaperCell {
  PaperValue dt_stable, max_error;
  std::string confidence, evidence;
  bool dt_printed = true;
};

using Table1Key = std::tuple<Key, Key, Key, std::string>;  // A, E, dt, method

// The paper cell a case is compared with: its A, E, dt and the method of the paper's column
// (CaseSpec::paper_method, the base case's method in a variants experiment).
Table1Key paper_key(const CaseSpec& c);

// Our value and the paper's agree when neither is more than this factor times the other: the
// comparator's rule |a - b| <= ((k - 1) / k) max(|a|, |b|) with k = kAgreementFactor
// (engine/compare.hpp). Every report that says "within a factor" prints this constant.
inline constexpr double kAgreementFactor = 3;
bool within_agreement_factor(double ours, double paper);
// kAgreementFactor as the reports print it: "3".
std::string agreement_factor();

// How a Table 1 cell of ours stands against the paper's stability verdict: the one rule of
// agreement, by which table1.md and comparison.md both count (over the same cells: every cell
// with a readable paper value). A cell is compared when the paper's value is readable (a max
// error, its run stable, or `*`, unstable); the verdicts agree when both are stable (ours stable
// over at least a wave pass, below A) or both unstable (ours failed before T). A meaningless run
// (it reached T with an error over time of at least A) and a run without a verdict (too few steps,
// or under a wave pass) agree with neither of the paper's verdicts.
enum class CellAgreement {
  unreadable,                  // the paper's value is missing or unreadable: not compared
  both_stable,                 // the paper gives a max error; ours is stable
  both_unstable,               // the paper marks `*`; ours failed before T
  paper_stable_ours_unstable,  // the paper gives a max error; ours failed before T
  paper_unstable_ours_stable,  // the paper marks `*`; ours is stable
  ours_meaningless,            // ours reached T with an error over time of at least A
  ours_too_short,              // ours has no verdict: too few steps, or under a wave pass
};
CellAgreement cell_agreement(const RunRow& row, const PaperCell* paper);
// The paper's verdict is readable (every CellAgreement but unreadable).
inline bool compared(CellAgreement a) {
  return a != CellAgreement::unreadable;
}
// The stability verdicts are the same: both stable or both unstable.
inline bool verdicts_agree(CellAgreement a) {
  return a == CellAgreement::both_stable || a == CellAgreement::both_unstable;
}
// The paper's run is stable (it gives a max error), of a compared cell.
bool paper_says_stable(const PaperCell& paper);

// A row of the transcribed Table 1 (reference/paper/table1.csv): A, E and the method in lower
// case, its dt where the paper prints one, and its cell.
struct PaperRow {
  double A = 0, E = 0;
  std::optional<double> dt;  // none where the paper prints no dt ("?")
  std::string method;
  PaperCell cell;
};

// Every row of the transcription in file order. Throws InputError naming the file, row and column
// where A, E or a printed dt is not a finite number.
std::vector<PaperRow> read_paper_rows(const std::filesystem::path& reference);

// The transcribed Table 1 of a spec that reads it (table1, eq108, variants), keyed by (A, E, dt,
// method). A row whose dt the paper does not print ("?") is keyed by the dt of the spec's cases
// at its A, E and method that no printed row has; those cases must be marked dt_inferred. A row
// that no case of the spec places is left out (the spec does not run that cell). Throws
// InputError naming the file and row for a number that is not finite, and naming the case for an
// unprinted dt the spec places without dt_inferred or at two dts.
std::map<Table1Key, PaperCell> read_paper_table1(const Spec& spec);

}  // namespace mpmstab
