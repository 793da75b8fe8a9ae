// The spectral study: each scheme's spectral limit (core/spectral.hpp) beside two runs of the bar
// at a tiny amplitude under the spectral policy, at 0.95 and at 1.05 times the limit. The limit
// is confirmed when the first stays bounded and the second grows.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "claims.hpp"
#include "csv.hpp"
#include "paper_table1.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// A bounded run's error, its phase error included, is at most 2 A; a growing mode passes 3 A.
constexpr double kBound = 3.0;

// A run is bounded when it reached T and its error over time stayed within kBound A, as the
// spectral_edge search counts it; a bounded run may still be meaningless (error >= A), which
// its text says.
bool bounded(const ojson& r) {
  return survived(r) && has_number(r, "max_error_over_time") &&
         r["max_error_over_time"].get<double>() <= kBound * r["A"].get<double>();
}

// "bounded (error 0.41 A)", "bounded (error 1.2 A, meaningless)", "grew (error 2.3e+02 A)",
// "* nonpositive_F at step 96 (...)".
std::string run_text(const ojson& r) {
  if (outcome(r) == "unstable") return verdict(r);
  if (!has_number(r, "max_error_over_time")) return "–";
  const double ratio_to_A = r["max_error_over_time"].get<double>() / r["A"].get<double>();
  return std::string(bounded(r) ? "bounded" : "grew") + " (error " + sci(ratio_to_A) + " A" +
         (bounded(r) && outcome(r) == "meaningless" ? ", meaningless" : "") + ")";
}

// A row's layout parameter (0, the uniform layout, where the row has none).
double layout_of(const ojson& r, const char* key) {
  return has_number(r, key) ? r[key].get<double>() : 0.0;
}

// The scheme rows: those at the first row's E and grid (each scheme's pair of runs). The others
// measure eq. (108) against the limit at other E and particle counts (one run each, at 0.95
// times the limit).
bool scheme_row(const ojson& r, const ojson& first) {
  return r["E"] == first["E"] && r["cells"] == first["cells"];
}

std::vector<ojson> scheme_rows(const std::vector<ojson>& rows) {
  std::vector<ojson> out;
  for (const auto& r : rows)
    if (scheme_row(r, rows.front())) out.push_back(r);
  return out;
}

// One scheme: its two runs, by the policy's safety factor.
struct Scheme {
  std::string name;              // scheme_label
  const ojson* below = nullptr;  // s < 1
  const ojson* above = nullptr;  // s > 1
  const ojson& row() const { return below ? *below : *above; }
  std::optional<double> limit() const {
    return has_number(row(), "courant_spectral")
               ? std::optional(row()["courant_spectral"].get<double>())
               : std::nullopt;
  }
  int ppc() const { return row()["ppc"].get<int>(); }
  bool uniform_two() const {  // 2 particles per cell, uniform layout
    return ppc() == 2 && layout_of(row(), "shift") == 0 && layout_of(row(), "jitter") == 0;
  }
  bool confirmed() const { return below && above && bounded(*below) && !bounded(*above); }
  // The eq. (108) bound of the run below the limit (its minimum over the run), in c dt / h.
  std::optional<double> eq108() const {
    if (!below || !has_number(*below, "dt_stable_min")) return std::nullopt;
    return (*below)["dt_stable_min"].get<double>() / (*below)["dt_cfl"].get<double>();
  }
};

std::vector<Scheme> schemes_of(const std::vector<ojson>& rows) {
  std::vector<Scheme> out;
  for (const auto& r : rows) {
    const std::string name = scheme_label(r);
    auto it = std::find_if(out.begin(), out.end(), [&](const Scheme& s) { return s.name == name; });
    if (it == out.end()) it = out.insert(out.end(), Scheme{name});
    const double s = has_number(r, "safety") ? r["safety"].get<double>() : 1.0;
    (s < 1 ? it->below : it->above) = &r;
  }
  return out;
}

// The measured edges of the spectral_edge experiment at a tiny amplitude, by scheme label, in
// c dt / h (empty when it has not been run).
std::map<std::string, double> measured_edges(const StudyInputs& inputs) {
  std::map<std::string, double> out;
  const auto it = inputs.find("spectral_edge");
  if (it == inputs.end() || !it->second.present()) return out;
  for (const auto& r : it->second.doc.at("cases")) {
    if (r["A"].get<double>() >= 1e-5 || !has_number(r, "dt_edge")) continue;
    out[scheme_label(r)] = r["dt_edge"].get<double>() / r["dt_cfl"].get<double>();
  }
  return out;
}

// The update order of a scheme's name ("gimp/xpic(2)/usf" -> "usf"; no suffix: usl).
std::string update_of(const std::string& name) {
  for (const char* u : {"/usf", "/musl"}) {
    if (name.find(u) != std::string::npos) return u + 1;
  }
  return "usl";
}

std::string reading(const std::vector<Scheme>& schemes,
                    const std::map<std::string, double>& edges) {
  std::ostringstream md;
  int confirmed = 0;
  std::vector<std::string> not_confirmed;
  std::map<std::string, std::pair<double, double>> range;  // update order -> limits at ppc 2
  double eq_lo = 1e300, eq_hi = 0, edge_lo = 1e300, edge_hi = 0;
  for (const auto& s : schemes) {
    if (s.confirmed()) {
      ++confirmed;
    } else {
      not_confirmed.push_back(s.name);
    }
    const auto limit = s.limit();
    if (limit && s.uniform_two()) {
      auto [it, fresh] = range.emplace(update_of(s.name), std::pair{*limit, *limit});
      if (!fresh) {
        it->second.first = std::min(it->second.first, *limit);
        it->second.second = std::max(it->second.second, *limit);
      }
    }
    if (const auto e = s.eq108(); e && limit) {
      eq_lo = std::min(eq_lo, *e / *limit);
      eq_hi = std::max(eq_hi, *e / *limit);
    }
    if (const auto e = edges.find(s.name); e != edges.end() && limit) {
      edge_lo = std::min(edge_lo, e->second / *limit);
      edge_hi = std::max(edge_hi, e->second / *limit);
    }
  }
  md << "**Reading** (computed from the rows). The limit is confirmed (the run at 0.95 times it "
        "stays bounded, the run at 1.05 times it grows) for "
     << confirmed << " of " << schemes.size() << " schemes";
  if (not_confirmed.empty()) {
    md << ". ";
  } else {
    md << "; not for ";
    for (std::size_t i = 0; i < not_confirmed.size(); ++i)
      md << (i ? ", " : "") << "`" << not_confirmed[i] << "`";
    md << " (their rows show which run disagrees). ";
  }
  md << "Limits at 2 particles per cell and the uniform layout, in c dt / h, by update order:";
  std::string sep = " ";
  for (const char* u : {"usl", "usf", "musl"}) {
    const auto it = range.find(u);
    if (it == range.end()) continue;
    md << sep << u << " " << fixed(it->second.first, 3) << " to " << fixed(it->second.second, 3);
    sep = "; ";
  }
  md << " (the CFL number is 1).";
  if (edge_hi > 0) {
    md << " The measured edges lie at " << fixed(edge_lo, 4) << " to " << fixed(edge_hi, 4)
       << " times the limit.";
  }
  if (eq_hi > 0) {
    md << " Eq. (108) at the same state lies at " << fixed(eq_lo, 3) << " to " << fixed(eq_hi, 3)
       << " times the limit at this E and grid only: its ratio changes with E and with the "
          "particle count (the section on eq. (108) below).";
  }
  md << "\n\n";
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Eq. (108) against the limit, per E and per particle count

// One run at 0.95 times the limit of MPM or GIMP (USL, FLIP, uniform layout): eq. (108)'s
// minimum over it against the limit, both in c dt / h.
struct Eq108Point {
  std::string method;
  double E = 0;
  int cells = 0, ppc = 0, particles = 0;
  double limit = 0, eq108 = 0;
  double ratio() const { return eq108 / limit; }
};

std::vector<Eq108Point> eq108_points(const std::vector<ojson>& rows) {
  std::vector<Eq108Point> out;
  for (const auto& r : rows) {
    const std::string m = r["method"].get<std::string>();
    if ((m != "mpm" && m != "gimp") || method_label(r) != m || layout_of(r, "shift") != 0 ||
        layout_of(r, "jitter") != 0 || !has_number(r, "safety") || r["safety"].get<double>() >= 1 ||
        !has_number(r, "courant_spectral") || !has_number(r, "dt_stable_min"))
      continue;
    out.push_back({m, r["E"].get<double>(), r["cells"].get<int>(), r["ppc"].get<int>(),
                   r["particles"].get<int>(), r["courant_spectral"].get<double>(),
                   r["dt_stable_min"].get<double>() / r["dt_cfl"].get<double>()});
  }
  return out;
}

// Thresholds of the claims: a bound homogeneous in E would give the same ratio at every E of a
// run at the same c dt / h, A and c T (E alone rescales time); one whose l2 norm sums over the
// particles per cell falls as ppc^(-1/2) at a fixed grid.
constexpr double kHomogeneousSpread = 1.1;
constexpr double kSqrtSlope = -0.5, kSlopeTolerance = 0.1;
// (A homogeneous bound's ratio would not move with the grid at a fixed particles per cell.)

struct Eq108Findings {
  std::string markdown;
  std::vector<Claim> claims;
};

Eq108Findings eq108_findings(const std::vector<ojson>& rows) {
  const auto points = eq108_points(rows);
  const ojson& first = rows.front();
  const int cells0 = first["cells"].get<int>();
  Eq108Findings f;
  std::ostringstream md;
  md << "## Eq. (108) against the limit, per E and per particle count\n\nEq. (108) is not "
        "dimensionally homogeneous: it divides by the stress scaled by 1/sqrt(E) and by the l2 "
        "norm of the nodal velocities (a sum over nodes), so at the same c dt / h, A/h and c T "
        "its step in units of h/c changes with E, and with the particles per cell and the grid; "
        "the conclusions fit how. The first table gives its minimum over a run at 0.95 times the "
        "limit "
        "(c dt / h), per E at "
     << cells0 << " cells, T = " << shortest(first["T"].get<double>())
     << " / sqrt(E) (the same crossings of the bar), A = " << shortest(first["A"].get<double>())
     << ". Each cell is eq. (108) / the spectral limit (both in c dt / h); the first rows give "
        "the limit itself.\n\n";
  std::vector<int> ppcs;
  std::vector<double> Es;
  for (const auto& p : points) {
    if (p.cells != cells0) continue;
    if (std::find(ppcs.begin(), ppcs.end(), p.ppc) == ppcs.end()) ppcs.push_back(p.ppc);
    if (std::find(Es.begin(), Es.end(), p.E) == Es.end()) Es.push_back(p.E);
  }
  std::sort(ppcs.begin(), ppcs.end());
  std::sort(Es.begin(), Es.end());
  auto find = [&](const std::string& m, double E, int ppc) -> const Eq108Point* {
    for (const auto& p : points)
      if (p.method == m && p.E == E && p.ppc == ppc && p.cells == cells0) return &p;
    return nullptr;
  };
  md << "| method | E |";
  for (int ppc : ppcs)
    md << " ppc " << ppc << " |";
  md << "\n|---|---|";
  for (std::size_t k = 0; k < ppcs.size(); ++k)
    md << "---|";
  md << "\n";
  double worst = 0, worst_E = 0;
  int below = 0, n = 0;
  std::map<std::pair<std::string, int>, std::pair<double, double>> by_layout;  // ratio lo, hi
  for (const char* m : {"mpm", "gimp"}) {
    md << "| " << m << " | spectral limit |";
    for (int ppc : ppcs) {
      const Eq108Point* p = find(m, Es.empty() ? 0 : Es.front(), ppc);
      md << " " << (p ? fixed(p->limit, 3) : std::string("–")) << " |";
    }
    md << "\n";
    for (double E : Es) {
      md << "| " << m << " | " << shortest(E) << " |";
      for (int ppc : ppcs) {
        const Eq108Point* p = find(m, E, ppc);
        if (!p) {
          md << " – |";
          continue;
        }
        md << " " << sci(p->ratio(), 3) << " |";
        ++n;
        below += p->ratio() < 1;
        if (p->ratio() > worst) {
          worst = p->ratio();
          worst_E = p->E;
        }
        auto [it, fresh] =
            by_layout.emplace(std::pair{p->method, p->ppc}, std::pair{p->ratio(), p->ratio()});
        if (!fresh) {
          it->second.first = std::min(it->second.first, p->ratio());
          it->second.second = std::max(it->second.second, p->ratio());
        }
      }
      md << "\n";
    }
  }
  double spread = 1;
  for (const auto& [key, r] : by_layout)
    spread = std::max(spread, r.second / r.first);
  md << "\nThe ratio to the limit at one method and layout moves with E by up to a factor "
     << ratio(spread) << ".\n\n";

  // The particle count, at the first row's E and 2 particles per cell.
  std::vector<std::pair<double, double>> by_count;
  md << "| method | cells | particles | eq. (108) / limit | x sqrt(particles) "
        "|\n|---|---|---|---|---|\n";
  for (const char* m : {"mpm", "gimp"}) {
    std::vector<const Eq108Point*> mine;
    for (const auto& p : points)
      if (p.method == m && p.E == first["E"].get<double>() && p.ppc == 2) mine.push_back(&p);
    std::sort(mine.begin(), mine.end(),
              [](const Eq108Point* a, const Eq108Point* b) { return a->particles < b->particles; });
    for (const Eq108Point* p : mine) {
      md << "| " << p->method << " | " << p->cells << " | " << p->particles << " | "
         << sci(p->ratio(), 3) << " | " << fixed(p->ratio() * std::sqrt(double(p->particles)), 3)
         << " |\n";
      if (std::string(m) == "gimp") by_count.emplace_back(p->particles, p->ratio());
    }
  }
  md << "\n";
  const auto slope = loglog_slope(by_count);

  Claim a = claim("eq108-below-limit-every-E",
                  "Eq. (108) lies below the spectral limit at every E and particles per cell",
                  "{below} of {n} runs; the largest ratio is {worst}, at E = {E}");
  a.count("below", below)
      .count("n", n)
      .value("worst", n ? sci(worst, 3) : "–")
      .value("E", n ? shortest(worst_E) : "–");
  a.holds = n > 0 && below == n;
  f.claims.push_back(a);

  Claim b = claim("eq108-not-homogeneous",
                  "Eq. (108)'s ratio to the spectral limit changes with E at the same c dt/h, "
                  "A/h and c T: it is not dimensionally homogeneous",
                  "at one method and layout the ratio moves with E by up to a factor {spread} "
                  "(homogeneous: below {threshold})");
  b.value("spread", ratio(spread)).value("threshold", shortest(kHomogeneousSpread));
  b.holds = spread > kHomogeneousSpread;
  f.claims.push_back(b);

  // At the first E and grid: against the particles per cell (GIMP).
  std::vector<std::pair<double, double>> by_ppc;
  for (const auto& p : points)
    if (p.method == "gimp" && p.E == first["E"].get<double>() && p.cells == cells0)
      by_ppc.emplace_back(p.ppc, p.ratio());
  const auto ppc_slope = loglog_slope(by_ppc);
  Claim c = claim("eq108-falls-as-sqrt-ppc",
                  "At a fixed grid, eq. (108)'s ratio to the limit falls as the inverse square "
                  "root of the particles per cell",
                  "GIMP at E = {E}, {points} values of particles per cell: fitted exponent "
                  "{slope} (expected {expected} within {tolerance})");
  c.value("E", shortest(first["E"].get<double>()))
      .count("points", static_cast<long long>(by_ppc.size()))
      .value("slope", ppc_slope ? fixed(*ppc_slope, 3) : "–")
      .value("expected", shortest(kSqrtSlope))
      .value("tolerance", shortest(kSlopeTolerance));
  c.holds = ppc_slope && std::abs(*ppc_slope - kSqrtSlope) <= kSlopeTolerance;
  f.claims.push_back(c);

  Claim d = claim("eq108-independent-of-grid",
                  "At a fixed number of particles per cell, refining the grid leaves eq. (108)'s "
                  "ratio to the limit unchanged",
                  "GIMP at E = {E}, {points} grids: fitted exponent against the particle count "
                  "{slope} (unchanged: within {tolerance} of zero)");
  d.value("E", shortest(first["E"].get<double>()))
      .count("points", static_cast<long long>(by_count.size()))
      .value("slope", slope ? fixed(*slope, 3) : "–")
      .value("tolerance", shortest(kSlopeTolerance));
  d.holds = slope && std::abs(*slope) <= kSlopeTolerance;
  f.claims.push_back(d);
  f.markdown = md.str();
  return f;
}

// The paper's grid for Table 1 (experiments/table1.json): h = 1 / kPaperCells.
constexpr int kPaperCells = 100;

// The paper's dt stable column of Table 1 in c dt / h, per method, A and E: the median of its
// rows (each dt), with the count of rows read and of the rows whose value is unreadable.
std::string paper_table(const std::filesystem::path& reference,
                        const std::vector<Scheme>& schemes) {
  if (reference.empty() || !std::filesystem::exists(reference)) return "";
  const CsvTable t = read_csv(reference);
  std::map<std::tuple<std::string, double, double>, std::vector<double>> values;
  std::vector<double> Es;
  std::vector<std::pair<std::string, double>> keys;  // method, A, in order
  for (const auto& r : t.rows) {
    const double A = std::stod(r.at("A")), E = std::stod(r.at("E"));
    if (std::find(Es.begin(), Es.end(), E) == Es.end()) Es.push_back(E);
    std::string method = r.at("method");
    std::transform(method.begin(), method.end(), method.begin(),
                   [](unsigned char ch) { return char(std::tolower(ch)); });
    if (std::find(keys.begin(), keys.end(), std::pair{method, A}) == keys.end())
      keys.emplace_back(method, A);
    // Table 1's own reading of a cell: '*' and unreadable text ('4.?e-6') are no number.
    const PaperValue dt_stable = paper_value(r.at("dt_stable"));
    if (dt_stable.kind != PaperValue::number || !(dt_stable.value > 0)) continue;
    values[{method, A, E}].push_back(dt_stable.value * std::sqrt(E) * kPaperCells);
  }
  std::sort(Es.begin(), Es.end());
  auto limit_of = [&](const std::string& method) -> std::string {
    for (const auto& s : schemes)
      if (s.name == method && s.limit()) return fixed(*s.limit(), 3);
    return "–";
  };
  auto eq108_of = [&](const std::string& method) -> std::string {
    for (const auto& s : schemes)
      if (s.name == method && s.eq108()) return fixed(*s.eq108(), 3);
    return "–";
  };
  std::ostringstream md;
  md << "## The paper's dt stable column\n\nTable 1's \"dt stable\" (eq. (108) of the paper's "
        "runs, at its amplitudes and E, on "
     << kPaperCells
     << " cells), converted to c dt / h: the median over the dts of each cell's block. The "
        "paper's bound changes with the state (A and E); the spectral limit and our eq. (108) at "
        "the tiny amplitude do not.\n\n| method | A | ";
  for (double E : Es)
    md << "E = " << shortest(E) << " | ";
  md << "spectral limit | our eq. (108) at A = 1e-6 |\n|---|---|";
  for (std::size_t i = 0; i < Es.size() + 2; ++i)
    md << "---|";
  md << "\n";
  int above = 0, cells = 0;
  for (const auto& [method, A] : keys) {
    md << "| " << method << " | " << shortest(A) << " | ";
    for (double E : Es) {
      const auto it = values.find({method, A, E});
      if (it == values.end() || it->second.empty()) {
        md << "– | ";
        continue;
      }
      const double m = quantile(it->second, 0.5);
      md << fixed(m, 3) << " | ";
      for (const auto& s : schemes) {
        if (s.name != method || !s.limit()) continue;
        ++cells;
        above += m > *s.limit() ? 1 : 0;
      }
    }
    md << limit_of(method) << " | " << eq108_of(method) << " |\n";
  }
  md << "\n**Reading** (computed from the rows). " << above << " of " << cells
     << " of the paper's medians lie above the spectral limit of their method (a step the "
        "linearised scheme amplifies at a tiny amplitude).\n\n";
  return md.str();
}

std::string spectral_markdown(const ReportContext& c) {
  const std::vector<ojson> rows = scheme_rows(c.rows);
  const std::vector<Scheme> schemes = schemes_of(rows);
  const auto edges = measured_edges(c.inputs);
  const ojson& first = rows.front();
  std::ostringstream md;
  md << "![The spectral limit against the particles per cell](spectral.png)\n\n"
     << "Each scheme's spectral limit: the largest c dt / h at which its one-step map, "
        "linearised about rest with the particles frozen at the bar's initial layout, amplifies "
        "nothing (docs/design.md, \"The spectral limit\"): the Bloch limit of the interior for a "
        "uniform layout, the dense map of the whole bar for a jittered one. Beside it, two runs "
        "of the bar under the spectral policy at s = 0.95 and s = 1.05 times the limit, at A = "
     << shortest(first["A"].get<double>()) << ", E = " << shortest(first["E"].get<double>())
     << " and T = " << shortest(first["T"].get<double>())
     << " (c T / L = " << shortest(std::sqrt(first["E"].get<double>()) * first["T"].get<double>())
     << " crossings of the bar), " << first["cells"].get<int>()
     << " cells. A run is *bounded* when it reaches T with an error over time of at most 3 A "
        "(a bounded run's error, its phase error included, is at most 2 A; one that reaches A "
        "is also marked meaningless); a run that grows passes 3 A or fails. Eq. (108) is "
        "defined for MPM, GIMP and cpGIMP only (`–` for the other bases). The measured edge is the "
        "spectral_edge experiment's "
        "([spectral_edge.md](spectral_edge.md)): the largest fixed dt that stays bounded, found "
        "by bisection to 0.5% without reading the limit. Eq. (108) is the minimum of our bound "
        "over the run at 0.95 times the limit. The CFL number is 1 in these units.\n\n"
     << reading(schemes, edges)
     << "| scheme | spectral limit (c dt / h) | analysis | measured edge | eq. (108) at the same "
        "state | run at 0.95 x | run at 1.05 x | confirmed |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& s : schemes) {
    const auto limit = s.limit();
    const auto edge = edges.find(s.name);
    const auto eq = s.eq108();
    md << "| " << s.name << " | " << (limit ? fixed(*limit, 4) : std::string("none up to 8"))
       << " | "
       << (s.row()["spectral_analysis"].is_string()
               ? s.row()["spectral_analysis"].get<std::string>()
               : std::string("–"))
       << " | " << (edge != edges.end() ? fixed(edge->second, 4) : std::string("–")) << " | "
       << (eq ? fixed(*eq, 4) : std::string("–")) << " | " << (s.below ? run_text(*s.below) : "–")
       << " | " << (s.above ? run_text(*s.above) : "–") << " | "
       << (s.confirmed() ? "yes" : "**no**") << " |\n";
  }
  md << "\n" << eq108_findings(c.rows).markdown << paper_table(c.spec.reference, schemes);
  return md.str();
}

// The figure: MPM and GIMP (USL, FLIP, uniform layout) against the particles per cell: the
// limit and the measured edge (first E), eq. (108) at every E.
std::string spectral_data(const ReportContext& c) {
  const auto edges = measured_edges(c.inputs);
  const ojson& first = c.rows.front();
  std::ostringstream csv;
  csv << c.csv_header << "# method: 0 mpm, 1 gimp (USL, FLIP, uniform layout, "
      << first["cells"].get<int>()
      << " cells); in c dt / h: limit the spectral limit, edge the measured edge (empty: not "
         "measured), eq108 our eq. (108), the minimum over the run at 0.95 times the limit\n"
         "method,E,ppc,limit,edge,eq108\n";
  // Sorted by method, E and ppc: each curve one contiguous block.
  auto points = eq108_points(c.rows);
  std::stable_sort(points.begin(), points.end(), [](const Eq108Point& a, const Eq108Point& b) {
    return std::tuple(a.method != "mpm", a.E, a.ppc) < std::tuple(b.method != "mpm", b.E, b.ppc);
  });
  for (const auto& p : points) {
    if (p.cells != first["cells"].get<int>()) continue;
    std::string name = p.method;
    if (p.ppc != 2) name += " (ppc " + std::to_string(p.ppc) + ")";
    const auto edge = p.E == first["E"].get<double>() ? edges.find(name) : edges.end();
    csv << (p.method == "gimp" ? 1 : 0) << ',' << shortest(p.E) << ',' << p.ppc << ','
        << shortest(p.limit) << ',' << (edge != edges.end() ? shortest(edge->second) : "") << ','
        << shortest(p.eq108) << '\n';
  }
  return csv.str();
}

std::string spectral_index(const Spec& spec, const std::vector<ojson>& all) {
  const std::vector<ojson> rows = scheme_rows(all);  // the schemes point into it
  const std::vector<Scheme> schemes = schemes_of(rows);
  const auto confirmed =
      std::count_if(schemes.begin(), schemes.end(), [](const Scheme& s) { return s.confirmed(); });
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name
     << ".png)\n\n**What it shows.** The spectral limit of " << schemes.size()
     << " schemes (basis x transfer x update order, particles per cell and layout), each checked "
        "by "
        "two runs at a tiny amplitude just below and just above it: confirmed for "
     << confirmed << " of " << schemes.size() << ": [" << spec.name << ".md](" << spec.name
     << ".md).\n\n";
  return md.str();
}

const StudyRegistration kSpectral{{
    .name = "spectral",
    .summary = "each scheme's spectral limit, checked by runs just below and above it, beside "
               "the measured edge, eq. (108) and the paper's dt stable",
    .records = {.error_over_time = true, .dt_stable = true},
    .inputs = {{.name = "spectral_edge"}},
    .figure = true,
    .report =
        [](const ReportContext& c) {
          return StudyReport{.markdown = spectral_markdown(c),
                             .data_csv = spectral_data(c),
                             .claims = eq108_findings(c.rows).claims};
        },
    .index = spectral_index,
    .figure_subtitle =
        [](const Spec&, const ojson&) {
          return std::string(
              "USL, FLIP, uniform layout, 50 cells; the CFL number is 1; eq. (108) "
              "at every E, the limit and the edge at E = 1");
        },
}};

}  // namespace

}  // namespace mpmstab
