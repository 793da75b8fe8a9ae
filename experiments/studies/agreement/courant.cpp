// The Courant scan: each E and A of Table 1 and both methods at Courant numbers c dt / h over a
// fixed list. Per case (method, A, E: A / h and c T fixed), where survival to T stops in C: the
// largest C such that the runs at it and at each smaller C of the scan reach T (its run's outcome,
// error over time per A and accuracy class, and how long it holds when rerun for length,
// edge_length.hpp), the same for runs that end stable, and the C at which survival comes back
// above a failure (not monotone).
#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "base/accuracy.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run/edge.hpp"
#include "shared/edge_length.hpp"
#include "study.hpp"

namespace mpmstab::studies::courant {
namespace {

using ojson = nlohmann::ordered_json;

// One case of the scan: its runs in increasing C, and where survival stops.
struct Scan {
  std::string method;
  double A = 0, E = 0;
  std::vector<std::size_t> runs;        // row indices, increasing C
  std::optional<std::size_t> survives;  // the run at the largest C up to which all survive
  bool edge = false;                    // a run above `survives` fails: a survival edge
  std::optional<std::size_t> stable;    // the run at the largest C up to which all are stable
  std::vector<double> comes_back;       // C that survive above a C that failed
  bool any_survives = false;            // some C of the scan reaches T
  // How long the survival edge lasts when rerun for length (lasting_text); "–" for no edge.
  std::string length = "–";
};

std::vector<Scan> scans(const std::vector<ojson>& rows) {
  const std::vector<RunRow> runs(rows.begin(), rows.end());
  std::map<std::tuple<std::string, Key, Key>, Scan> by;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const RunRow& r = runs[i];
    const double E = rows[i]["E"].get<double>();
    Scan& s = by[std::make_tuple(r.method, Key(*r.A, "A"), Key(E, "E"))];
    s.method = r.method;
    s.A = *r.A;
    s.E = E;
    s.runs.push_back(i);
  }
  std::vector<Scan> out;
  for (auto& [key, s] : by) {
    std::stable_sort(s.runs.begin(), s.runs.end(), [&](std::size_t a, std::size_t b) {
      return TotalLess()(*runs[a].courant, *runs[b].courant);
    });
    // The rule of every edge (core/run/edge.hpp, edge_line): the edge is the largest C up to
    // which every run with a verdict holds; a run too short for one neither holds nor fails.
    std::vector<std::pair<double, EdgeVerdict>> survival, stability;
    std::map<double, std::size_t> at;
    for (const std::size_t i : s.runs) {
      const RunRow& r = runs[i];
      const double C = *r.courant;
      at[C] = i;
      const bool judged = r.outcome != "too_short" && r.wave_passes.value_or(0) >= kMinWavePasses;
      auto verdict = [&](bool holds) {
        return !judged ? EdgeVerdict::none : holds ? EdgeVerdict::holds : EdgeVerdict::fails;
      };
      survival.emplace_back(C, verdict(r.survived()));
      stability.emplace_back(C, verdict(r.outcome == "stable"));
      s.any_survives = s.any_survives || survival.back().second == EdgeVerdict::holds;
    }
    const EdgeLine line = edge_line(survival), stable = edge_line(stability);
    if (line.edge) s.survives = at[*line.edge];
    s.edge = s.survives && *s.survives != s.runs.back();
    if (stable.edge) s.stable = at[*stable.edge];
    for (const auto& [C, v] : survival)
      if (line.fail && C > *line.fail && v == EdgeVerdict::holds) s.comes_back.push_back(C);
    out.push_back(std::move(s));
  }
  return out;
}

// The rows whose run is a survival edge of the scan, in row order: the runs rerun for length.
std::vector<std::size_t> edge_rows(const std::vector<Scan>& all) {
  std::vector<std::size_t> out;
  for (const Scan& s : all)
    if (s.edge) out.push_back(*s.survives);
  std::sort(out.begin(), out.end());
  return out;
}

// The edge rows `at` as edge_length reads them: each its own dt as dt_edge.
std::vector<ojson> as_edges(const std::vector<ojson>& rows, const std::vector<std::size_t>& at) {
  std::vector<ojson> edges;
  for (const std::size_t i : at) {
    ojson& e = edges.emplace_back(rows[i]);
    e["dt_edge"] = rows[i]["dt"];
    e["dt_accurate"] = nullptr;
  }
  return edges;
}

// The runs of every edge for length, each asked for the case whose run is the edge.
std::vector<FollowUp> courant_follow_up(const FollowUpContext& c) {
  std::vector<CaseSpec> cases;
  const std::vector<std::size_t> rows = edge_rows(scans(c.rows));
  for (const std::size_t i : rows)
    cases.push_back(c.spec.cases.at(i));
  return all_length_runs(as_edges(c.rows, rows), cases, rows);
}

// Every case of the scan, and what the text, the claims and the index count of them; the runs
// each claim reads: the scan's smallest C of each case, every run, the runs for length.
struct Findings {
  std::vector<Scan> scans;
  int cases = 0, no_survivor = 0, fail_everywhere = 0, not_monotone = 0, edges = 0,
      edges_meaningless = 0;
  LengthTally length_tally;
  Coverage smallest, all, lengths;
};

// The findings from the rows and the length runs of the survival edges (without them, each edge
// is not tested for length).
Findings find(const std::vector<ojson>& rows, const std::vector<ojson>& follow_up) {
  Findings f{.scans = scans(rows), .all = coverage_of(rows), .lengths = coverage_of(follow_up)};
  const std::vector<std::size_t> at = edge_rows(f.scans);
  const std::vector<ojson> edges = as_edges(rows, at);
  const LengthRuns lengths = read_length_runs(edges, follow_up, at);
  for (Scan& s : f.scans) {
    f.smallest.add(rows[s.runs.front()]);
    ++f.cases;
    f.no_survivor += !s.survives;
    f.fail_everywhere += !s.any_survives;
    f.not_monotone += !s.comes_back.empty();
    if (!s.edge) continue;
    const ojson& edge = edges[std::find(at.begin(), at.end(), *s.survives) - at.begin()];
    ++f.edges;
    f.edges_meaningless += outcome(rows[*s.survives]) == "meaningless";
    f.length_tally.add(lasting(lengths, edge, "dt_edge"));
    s.length = lasting_text(lengths, edge, "dt_edge");
  }
  return f;
}

std::vector<Claim> courant_claims(const Findings& f) {
  Claim some = claim("every-case-survives-somewhere",
                     "Every case survives to T at the smallest Courant number of the scan",
                     "{none} of {cases} cases fail at the smallest C of the scan");
  some.count("none", f.no_survivor).count("cases", f.cases).over(f.cases).on(f.smallest);
  some.holds = f.no_survivor == 0;
  Claim mono = claim("survival-monotone-in-courant",
                     "Survival to T is monotone in C in every case: no C survives above one "
                     "that failed",
                     "{not_monotone} of {cases} cases survive again above a failure");
  mono.count("not_monotone", f.not_monotone).count("cases", f.cases).over(f.cases).on(f.all);
  mono.holds = f.not_monotone == 0;
  Claim length = length_claim("courant-edges-hold-for-length",
                              "Every survival edge of the scan survives {first}x and "
                              "{second}x its run length (at most {cap} wave passes)",
                              "{held} of {tested} do", f.length_tally);
  return {some, mono, length.on(f.lengths)};
}

// A Courant number of the scan (dt = C h / c was rounded to 6 digits): "0.78", "0.0625".
std::string c_text(double C) {
  return significant(C, 3);
}

// A run's outcome with its error over time per A and, for a stable run, its accuracy class
// (core/base/accuracy.hpp): "stable (0.0043 A, accurate)", "**meaningless** (1.3 A)".
std::string run_text(const ojson& r) {
  const RunRow rr(r);
  std::string s = rr.outcome == "meaningless" ? "**meaningless**" : rr.outcome;
  if (const auto e = rr.error_over_A()) {
    s += " (" + significant(*e, 2) + " A";
    if (rr.outcome == "stable") s += ", " + std::string(to_string(*rr.accuracy()));
    s += ")";
  }
  return s;
}

StudyReport courant_report(const ReportContext& c) {
  const Findings f = find(c.rows, c.follow_up);
  std::ostringstream md;
  md << "## Results\n\n**Reading.** Per case (method, A and E: A / h and c T fixed): *survives "
        "to T up to C*, the largest Courant number C of the scan such that the runs at C and at "
        "each smaller C of the scan reach T; the run there (its outcome, its error over time per "
        "A and, for a stable run, its accuracy class: accurate below "
     << shortest(kAccurateFraction)
     << " A, inaccurate below A; a meaningless run reaches T with an error over time of at "
        "least A and answers nothing); how long that run lasts when rerun at "
     << shortest(kLengthFactors[0]) << " and " << shortest(kLengthFactors[1])
     << " times its wave passes (at most " << shortest(kLongPasses)
     << "); *stable up to C*, the same with runs that reach T with an error over time below A, "
        "and the run there; and the C that reach T above a C that failed. Of "
     << f.cases << " cases, " << f.no_survivor << " fail at the smallest C of the scan ("
     << f.fail_everywhere << " of them at each C of the scan) and " << f.not_monotone
     << " reach T again above a failure; of " << f.edges
     << " survival edges (a failure above them), " << f.edges_meaningless
     << " are meaningless runs and " << f.length_tally.held << " of " << f.length_tally.tested
     << " rerun for length survive each length they were rerun for.\n\n"
     << "| method | A | E | A/h | c T | survives to T up to C | run there | length | stable up "
        "to C | run there | survives again above a failure at C |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Scan& s : f.scans) {
    const ojson& first = c.rows[s.runs.front()];
    md << "| " << s.method << " | " << shortest(s.A) << " | " << shortest(s.E) << " | "
       << significant(first["A_over_h"].get<double>(), 3) << " | "
       << significant(*RunRow(first).wave_passes, 3) << " | ";
    if (!s.survives) {
      md << "below the scan: its smallest C, " << c_text(*RunRow(first).courant)
         << ", fails | – | – | ";
    } else {
      const ojson& at = c.rows[*s.survives];
      md << c_text(*RunRow(at).courant) << (s.edge ? "" : " (the largest C of the scan)") << " | "
         << run_text(at) << " | " << s.length << " | ";
    }
    if (s.stable) {
      md << c_text(*RunRow(c.rows[*s.stable]).courant) << " | " << run_text(c.rows[*s.stable])
         << " | ";
    } else {
      md << "below the scan: its smallest C is not stable | – | ";
    }
    std::vector<std::string> back;
    for (const double C : s.comes_back)
      back.push_back(c_text(C));
    md << (back.empty() ? std::string("–") : list_of(back)) << " |\n";
  }
  return StudyReport{.markdown = md.str(), .claims = courant_claims(f)};
}

std::string courant_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Findings f = find(rows, {});
  std::ostringstream md;
  md << "**What it shows.** Per case, the largest Courant number of the scan up to which its "
        "runs reach T ("
     << f.no_survivor << " of " << f.cases << " cases fail at the smallest C of the scan, "
     << f.fail_everywhere << " at each C of it), the run there and how long it lasts: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kCourant{{
    .name = "courant",
    .summary = "per case, the largest Courant number up to which the scan's runs reach T",
    .records = {.error_over_time = true},
    .follow_up = courant_follow_up,
    .report = courant_report,
    .index = courant_index,
}};

}  // namespace
}  // namespace mpmstab::studies::courant
