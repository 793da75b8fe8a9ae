// The measured edges beside the spectral limit: for each case, the largest fixed dt with which the
// bar stays bounded to T (an edge search whose probes count as failing when their error over time
// passes 3 A, core/run/edge.hpp), against the spectral limit its record carries. At a tiny
// amplitude the two must agree (the agreement table, with its tolerance); at the paper's amplitudes
// the table shows where the nonlinear edge lies against the linear limit.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "shared/edge_length.hpp"
#include "study.hpp"

namespace mpmstab::studies::spectral_edge {
namespace {

using ojson = nlohmann::ordered_json;

// The amplitude below which a case measures the linear edge.
constexpr double kTinyA = 1e-5;
// The agreement asked of the measured tiny-amplitude edge and the spectral limit.
constexpr double kAgreement = 0.05;
// A probe is bounded when its error over time ends at most kProbeBound A.
constexpr double kProbeBound = 3.0;

// The search: the default scan, bisected to a finer tolerance, a probe surviving only bounded.
const EdgeOptions kSearch{.tolerance = 0.005, .bound = kProbeBound};

// The measured edge over the spectral limit; none without either.
std::optional<double> edge_ratio(const ojson& r) {
  if (!has_number(r, "dt_edge") || !has_number(r, "dt_spectral")) return std::nullopt;
  return r["dt_edge"].get<double>() / r["dt_spectral"].get<double>();
}

bool agrees(const ojson& r) {
  const auto q = edge_ratio(r);
  return q && std::abs(*q - 1) <= kAgreement;
}

// What the study finds, from its rows and the runs of each edge for length (none for the
// index, which prints no length finding). Its pointers are into the rows.
struct Findings {
  // The tiny-amplitude rows (the linear edge), how many agree with the limit and the range of
  // their edge over the limit (lo > hi: none measured).
  std::vector<const ojson*> linear;
  int agreeing = 0;
  double lo = 1e300, hi = -1e300;
  // The edges measured above the tiny amplitude, and those below the limit.
  int nonlinear = 0, below = 0;
  // The schemes measured at more than one amplitude (first seen first), those amplitudes in
  // increasing order, the row of each, and per scheme its lowest edge over the limit with its A
  // and the amplitudes at which the scan found no edge.
  std::vector<std::string> schemes;
  std::vector<double> amplitudes;
  std::map<std::pair<std::string, Key>, const ojson*> at;
  std::map<std::string, std::pair<double, double>> lowest;
  std::map<std::string, std::vector<double>> edgeless;
  // The rows with an edge (each rerun for length), and how long their edges hold.
  std::vector<const ojson*> with_edge;
  LengthTally lengths;
  // Where the runs lie (run_row.hpp) of the tiny amplitude, of the edges measured above it, of
  // the amplitude table and of the edges rerun for length.
  Coverage linear_at, nonlinear_at, amplitudes_at, lengths_at;
};

// The findings of the rows and their runs for length.
Findings find(const std::vector<ojson>& rows, const LengthRuns& lengths) {
  Findings f;
  std::map<std::string, int> runs;  // rows per scheme
  for (const auto& r : rows) {
    ++runs[scheme_label(r)];
    const Lasting lasts = lasting(lengths, r, "dt_edge", kProbeBound);
    f.lengths.add(lasts);
    if (lasts.tested) f.lengths_at.add(r);
    if (has_number(r, "dt_edge")) f.with_edge.push_back(&r);
    const auto q = edge_ratio(r);
    if (r["A"].get<double>() >= kTinyA) {
      f.nonlinear += q.has_value();
      f.below += q && *q < 1;
      if (q) f.nonlinear_at.add(r);
      continue;
    }
    f.linear.push_back(&r);
    f.linear_at.add(r);
    f.agreeing += agrees(r);
    if (q) {
      f.lo = std::min(f.lo, *q);
      f.hi = std::max(f.hi, *q);
    }
  }
  for (const auto& r : rows) {
    const double A = r["A"].get<double>();
    const std::string s = scheme_label(r);
    if (runs[s] < 2) continue;
    add_unique(f.amplitudes, A);
    add_unique(f.schemes, s);
    f.at[{s, Key(A, "A")}] = &r;
    f.amplitudes_at.add(r);
    if (!edge_ratio(r)) f.edgeless[s].push_back(A);
  }
  std::sort(f.amplitudes.begin(), f.amplitudes.end(), TotalLess());
  for (const auto& s : f.schemes) {
    for (double A : f.amplitudes) {
      const auto it = f.at.find({s, Key(A)});
      const auto q = it == f.at.end() ? std::nullopt : edge_ratio(*it->second);
      if (q && (!f.lowest.count(s) || *q < f.lowest[s].first)) f.lowest[s] = {*q, A};
    }
  }
  return f;
}

std::vector<Claim> spectral_edge_claims(const Findings& f) {
  Claim length = length_claim("edges-hold-for-length",
                              "Every measured edge stays bounded for {first}x and {second}x "
                              "its run length (at most {cap} wave passes)",
                              "{held} of {tested} do", f.lengths);
  Claim under = claim("nonlinear-edges-below-limit",
                      "Every edge measured above the tiny amplitude lies below the spectral limit",
                      "{below} of {n} do");
  under.every("below", f.below, "n", f.nonlinear).on(f.nonlinear_at);
  length.on(f.lengths_at);
  return {length, under};
}

std::string agreement_table(const Findings& f) {
  std::ostringstream md;
  md << "## The measured edge against the spectral limit (" << f.linear_at.text()
     << ")\n\n**Reading** (computed from the rows). " << f.agreeing << " of " << f.linear.size()
     << " measured edges lie within " << shortest(100 * kAgreement) << "% of the spectral limit";
  if (f.lo <= f.hi)
    md << " (edge / limit from " << fixed(f.lo, 4) << " to " << fixed(f.hi, 4) << ")";
  md << ".\n\n| scheme | measured edge (c dt / h) | first dt above it that grew | spectral limit "
        "(c dt / h) | analysis | edge / limit | within "
     << shortest(100 * kAgreement) << "% |\n|---|---|---|---|---|---|---|\n";
  for (const ojson* r : f.linear) {
    const double cfl = (*r)["dt_cfl"].get<double>();
    auto in_h = [&](const char* column) {
      return has_number(*r, column) ? fixed((*r)[column].get<double>() / cfl, 4) : std::string("–");
    };
    const auto q = edge_ratio(*r);
    md << "| " << scheme_label(*r) << " | " << in_h("dt_edge") << monotone_words(*r) << " | "
       << in_h("dt_fail") << " | " << in_h("dt_spectral") << " | " << text(*r, "spectral_analysis")
       << " | " << opt_fixed(q, 4) << " | " << (agrees(*r) ? "yes" : "**no**") << " |\n";
  }
  return md.str();
}

// Per scheme, the edge over the limit at each amplitude.
std::string amplitude_table(const Findings& f) {
  std::ostringstream md;
  md << "## The nonlinear edge as A grows (" << f.amplitudes_at.text()
     << ")\n\nEach cell: the measured edge over the spectral limit "
        "(the linear edge); `*` marks a case whose run at the edge is meaningless (its error "
        "reached A although it stayed below "
     << shortest(kProbeBound)
     << " A); `–` no edge in the scan.\n\n"
        "**Reading** (computed from the rows).";
  for (const auto& s : f.schemes) {
    const auto low = f.lowest.find(s);
    const auto none = f.edgeless.find(s);
    if (low == f.lowest.end() && none == f.edgeless.end()) continue;
    md << " " << s << ":";
    if (low != f.lowest.end())
      md << " lowest measured " << fixed(low->second.first, 3)
         << " of the limit, at A = " << shortest(low->second.second);
    if (none != f.edgeless.end())
      md << (low != f.lowest.end() ? ";" : "")
         << " no edge in the scan at A = " << listing(none->second);
    md << ".";
  }
  md << "\n\n| scheme |";
  for (double A : f.amplitudes)
    md << " A = " << shortest(A) << " |";
  md << "\n|---|" << rule_cells(f.amplitudes.size()) << "\n";
  for (const auto& s : f.schemes) {
    md << "| " << s << " |";
    for (double A : f.amplitudes) {
      const auto it = f.at.find({s, Key(A)});
      if (it == f.at.end()) {
        md << " |";
        continue;
      }
      const auto q = edge_ratio(*it->second);
      md << " " << opt_fixed(q) << (q && outcome(*it->second) == "meaningless" ? " *" : "") << " |";
    }
    md << "\n";
  }
  return md.str();
}

// Every edge rerun for length (edge_length.hpp): its run's error over time per A and the length
// to which it stays bounded.
std::string length_table(const Findings& f, const LengthRuns& lengths) {
  std::ostringstream md;
  md << "## Each edge for length\n\nEvery measured edge rerun at its dt for "
     << shortest(kLengthFactors[0]) << " and " << shortest(kLengthFactors[1])
     << " times its wave passes (at most " << shortest(kLongPasses)
     << "): it holds to a length where that run stays bounded (reaches it with an error over time "
        "at most "
     << shortest(kProbeBound)
     << " A), and is **transient** where it does not. The error over time at the edge is the "
        "search's own run.\n\n| scheme | A, c T | edge (c dt / h) | run at the edge | error over "
        "time / A there | length |\n|---|---|---|---|---|---|\n";
  for (const ojson* p : f.with_edge) {
    const ojson& r = *p;
    const RunRow rr(r);
    md << "| " << rr.scheme_label << " | " << shortest(*rr.A) << ", " << shortest(*rr.wave_passes)
       << " | " << fixed(r["dt_edge"].get<double>() / r["dt_cfl"].get<double>(), 4)
       << monotone_words(r) << " | " << edge_run_verdict(r) << " | "
       << (has_number(r, "error_at_edge_over_A")
               ? significant(r["error_at_edge_over_A"].get<double>(), 2)
               : std::string("–"))
       << " | " << lasting_text(lengths, r, "dt_edge", kProbeBound) << " |\n";
  }
  return md.str();
}

std::string spectral_edge_markdown(const std::vector<ojson>& rows, const Findings& f,
                                   const LengthRuns& lengths) {
  const ojson& first = rows.front();
  std::ostringstream md;
  md << "![The measured edge over the spectral limit against A](spectral_edge.png)\n\n"
     << "Each case's edge is the largest fixed dt with which the bar (E = "
     << shortest(first["E"].get<double>()) << ", " << first["cells"].get<int>()
     << " cells, T = " << shortest(first["T"].get<double>())
     << ": c T / L = " << shortest(std::sqrt(first["E"].get<double>()) * first["T"].get<double>())
     << " crossings) stays **bounded**: it reaches T without failing and its error over time "
        "stays at most "
     << shortest(kProbeBound)
     << " A. A growing mode at a tiny amplitude does not fail within T; this criterion sees it. "
        "The search: "
     << edge_search_text(kSearch)
     << "; `dt_fail` is the smallest dt above the edge that grew or failed. The spectral limit is "
        "the one each record carries: the Bloch limit of the interior for a uniform layout, the "
        "dense map of the whole bar for a jittered one (docs/theory.md, \"The spectral "
        "limit\").\n\n";
  if (!f.linear.empty()) md << agreement_table(f) << "\n";
  if (!f.schemes.empty()) md << amplitude_table(f) << "\n";
  md << length_table(f, lengths);
  return md.str();
}

// The figure's data, one row per amplitude and two columns per scheme (named in the header,
// which gnuplot takes for the legend): its edge over the limit, and the same where the run at
// the edge is meaningless. The first column holds the number of schemes.
std::string spectral_edge_data(const Findings& f, const std::string& header) {
  std::ostringstream csv;
  csv << header
      << "# one row per amplitude; per scheme (schemes of them): its measured edge over the "
         "spectral limit, and the same in the column '<scheme> meaningless' where the run at the "
         "edge is meaningless; empty: no edge in the scan\nschemes,A";
  for (const auto& s : f.schemes)
    csv << ',' << s;
  for (const auto& s : f.schemes)
    csv << ',' << s << " meaningless";
  csv << '\n';
  for (double A : f.amplitudes) {
    csv << f.schemes.size() << ',' << shortest(A);
    for (int meaningless = 0; meaningless < 2; ++meaningless) {
      for (const auto& s : f.schemes) {
        csv << ',';
        const auto it = f.at.find({s, Key(A)});
        if (it == f.at.end()) continue;
        const auto q = edge_ratio(*it->second);
        if (q && (!meaningless || outcome(*it->second) == "meaningless")) csv << shortest(*q);
      }
    }
    csv << '\n';
  }
  return csv.str();
}

std::string spectral_edge_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Findings f = find(rows, {});
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** " << f.agreeing
     << " of " << f.linear.size() << " measured edges lie within " << shortest(100 * kAgreement)
     << "% of the spectral limit (" << f.linear_at.text() << "); " << f.below << " of "
     << f.nonlinear << " edges measured at larger amplitudes lie below the limit ("
     << f.nonlinear_at.text() << "), and each edge is rerun for length: [" << spec.name << ".md]("
     << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kSpectralEdge{{
    .name = "spectral_edge",
    .summary = "per case, the largest fixed dt that stays bounded (error within " +
               shortest(kProbeBound) + " A), against the spectral limit (a search over dt)",
    .work = CaseWork::edge_search,
    .edge = kSearch,
    .records = {.error_over_time = true},
    .figure = true,
    .follow_up = [](const FollowUpContext& c) { return all_length_runs(c.rows, c.spec.cases); },
    .report =
        [](const ReportContext& c) {
          const LengthRuns lengths = read_length_runs(c.rows, c.follow_up);
          const Findings f = find(c.rows, lengths);
          return StudyReport{.markdown = spectral_edge_markdown(c.rows, f, lengths),
                             .data_csv = spectral_edge_data(f, c.csv_header),
                             .claims = spectral_edge_claims(f)};
        },
    .index = spectral_edge_index,
    .figure_subtitle =
        [](const Spec&, const ojson&) {
          return "edge: the largest fixed dt whose error over time stays within " +
                 shortest(kProbeBound) + " A to T; limit: the Bloch limit of the uniform layout";
        },
}};

}  // namespace
}  // namespace mpmstab::studies::spectral_edge
