// The walls study: each cell run with Dirichlet walls and with periodic boundaries, side by side.
// The manufactured solution is periodic, so the periodic twin has no wall at all: the difference
// between the two runs of a cell is what the walls' treatment does to the verdict and the error.
#include <cmath>
#include <map>
#include <sstream>

#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab::studies::walls {
namespace {

using ojson = nlohmann::ordered_json;

// The two runs of one cell.
struct Twin {
  const ojson* dirichlet = nullptr;
  const ojson* periodic = nullptr;
  // Periodic / Dirichlet error over time, where both runs end stable over a wave pass.
  std::optional<double> ratio;
};

// Two rows are the same cell when every parameter but the boundary kind agrees.
bool same_but_bc(const ojson& a, const ojson& b) {
  for (const auto& name : parameter_names()) {
    if (name == "bc") continue;
    const bool in_a = a.contains(name), in_b = b.contains(name);
    if (in_a != in_b || (in_a && a[name] != b[name])) return false;
  }
  return true;
}

// The cells in the order of their periodic runs; a periodic run without a Dirichlet twin (or the
// reverse) is paired with nothing.
std::vector<Twin> twins(const std::vector<ojson>& rows) {
  std::vector<Twin> out;
  for (const auto& r : rows) {
    if (text(r, "bc") != "periodic") continue;
    Twin t{.periodic = &r};
    for (const auto& d : rows)
      if (text(d, "bc") == "dirichlet" && same_but_bc(d, r)) t.dirichlet = &d;
    // The errors over time of runs that ended stable over at least a wave pass.
    const auto ed = t.dirichlet ? RunRow(*t.dirichlet).stable_error_over_time() : std::nullopt;
    if (const auto ep = RunRow(r).stable_error_over_time(); ed && ep) t.ratio = *ep / *ed;
    out.push_back(t);
  }
  return out;
}

// What the walls do, per method: the cells, how many change verdict, and over the cells where
// both runs end stable, periodic / Dirichlet error over time.
// Two errors within this relative difference are the same: the walls leave the error alone.
constexpr double kSameError = 0.01;

struct MethodWalls {
  int cells = 0, both_stable = 0;
  int both_accurate = 0;  // of both_stable: both runs accurate (core/base/accuracy.hpp)
  int walls_raise = 0, walls_lower = 0, same = 0;  // the Dirichlet error against the periodic one
  int only_periodic_survives = 0, only_dirichlet_survives = 0, same_verdict = 0;
  // Of those, the runs that survive only one way and are meaningless there (they survive and
  // answer nothing); and the cells stable (meaningful) only one way.
  int only_periodic_meaningless = 0, only_dirichlet_meaningless = 0;
  int only_periodic_stable = 0, only_dirichlet_stable = 0;
  std::vector<double> ratios;            // periodic / Dirichlet
  std::optional<double> lo, median, hi;  // of the ratios
  Coverage both_stable_runs;             // both runs of the cells where both end stable
};

// Every cell, and per method what the walls do.
struct Findings {
  std::vector<Twin> cells;
  std::map<std::string, MethodWalls> methods;
};

// The findings from the rows: the cells paired, then tallied per method.
Findings find(const std::vector<ojson>& rows) {
  Findings f{.cells = twins(rows)};
  for (const auto& t : f.cells) {
    if (!t.dirichlet) continue;
    MethodWalls& m = f.methods[RunRow(*t.periodic).method];
    ++m.cells;
    const bool d = survived(*t.dirichlet), p = survived(*t.periodic);
    m.same_verdict += outcome(*t.dirichlet) == outcome(*t.periodic);
    m.only_periodic_survives += p && !d;
    m.only_dirichlet_survives += d && !p;
    m.only_periodic_meaningless += p && !d && outcome(*t.periodic) == "meaningless";
    m.only_dirichlet_meaningless += d && !p && outcome(*t.dirichlet) == "meaningless";
    const bool ds = outcome(*t.dirichlet) == "stable", ps = outcome(*t.periodic) == "stable";
    m.only_periodic_stable += ps && !ds;
    m.only_dirichlet_stable += ds && !ps;
    if (!t.ratio) continue;
    ++m.both_stable;
    m.both_stable_runs.add(*t.dirichlet);
    m.both_stable_runs.add(*t.periodic);
    m.both_accurate += accurate_run(*t.dirichlet) && accurate_run(*t.periodic);
    m.ratios.push_back(*t.ratio);
    if (std::abs(*t.ratio - 1) <= kSameError) {
      ++m.same;
    } else {
      ++(*t.ratio < 1 ? m.walls_raise : m.walls_lower);
    }
  }
  for (auto& [name, m] : f.methods) {
    if (m.ratios.empty()) continue;
    m.lo = quantile(m.ratios, 0);
    m.median = quantile(m.ratios, 0.5);
    m.hi = quantile(m.ratios, 1);
  }
  return f;
}

std::vector<Claim> walls_claims(const Findings& f) {
  std::vector<Claim> claims;
  for (const auto& [name, m] : f.methods) {
    Claim c = claim("walls-leave-error-" + name,
                    "For {method}, Dirichlet walls leave the error over time within {tol} of the "
                    "periodic run's in every cell where both runs end stable",
                    "{same} of {n} within; periodic / Dirichlet {lo} to {hi}");
    c.value("method", name)
        .value("tol", percent(kSameError))
        .every("same", m.same, "n", m.both_stable)
        .value("lo", m.lo ? significant(*m.lo, 3) : "–")
        .value("hi", m.hi ? significant(*m.hi, 3) : "–");
    claims.push_back(c.on(m.both_stable_runs));
  }
  return claims;
}

std::string reading(const Findings& f) {
  std::ostringstream md;
  md << "**Reading.** ";
  for (const auto& [name, m] : f.methods) {
    md << name << ": of " << m.cells << " cells, " << m.same_verdict
       << " end with the same outcome under both boundaries; " << m.only_periodic_survives
       << " survive only without walls (" << m.only_periodic_meaningless
       << " of them meaningless there) and " << m.only_dirichlet_survives << " only with them ("
       << m.only_dirichlet_meaningless << " meaningless); " << m.only_periodic_stable
       << " are stable only without walls and " << m.only_dirichlet_stable
       << " only with them. Where both runs end stable (" << m.both_stable << " cells: both "
       << "accurate in " << m.both_accurate << ", at least one inaccurate in "
       << m.both_stable - m.both_accurate << ")";
    if (!m.lo) {
      md << ", nothing to compare. ";
      continue;
    }
    md << ", the periodic error over time is " << ratio(*m.lo) << " to " << ratio(*m.hi)
       << " times the Dirichlet one (median " << ratio(*m.median)
       << "): the walls raise the error by more than " << percent(kSameError) << " in "
       << m.walls_raise << " cells, lower it in " << m.walls_lower << " and leave it within "
       << percent(kSameError) << " in " << m.same << ". ";
    if (m.walls_raise > 0)
      md << "Where they raise it, the interior's own error is the periodic column. ";
  }
  return md.str();
}

std::string walls_table(const Findings& f) {
  std::ostringstream md;
  md << "| method | E | A | dt | c dt/h | A/h | c T | Dirichlet: verdict | error over time | "
        "periodic: verdict | error over time | periodic / Dirichlet |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& t : f.cells) {
    const ojson& p = *t.periodic;
    md << "| " << RunRow(p).method << " | " << shortest(p["E"].get<double>()) << " | "
       << shortest(p["A"].get<double>()) << " | " << param(p["dt"].get<double>()) << " | "
       << sci(RunRow(p).courant.value()) << " | " << significant(p["A_over_h"].get<double>(), 3)
       << " | " << significant(*RunRow(p).wave_passes, 3) << " | "
       << (t.dirichlet ? verdict(*t.dirichlet) : "not run") << " | "
       << (t.dirichlet ? opt_sci(RunRow(*t.dirichlet).error_over_time) : "–") << " | " << verdict(p)
       << " | " << opt_sci(RunRow(p).error_over_time) << " | "
       << (t.ratio ? ratio(*t.ratio) : std::string("–")) << " |\n";
  }
  return md.str();
}

StudyReport walls_report(const ReportContext& c) {
  const Findings f = find(c.rows);
  std::ostringstream md;
  md << "## Results\n\nEach cell run twice: with Dirichlet walls (the paper's bar, our default "
        "treatment of the nodes beyond a wall) and with periodic boundaries, which the periodic "
        "manufactured solution allows and which have no wall at all. The columns compare the "
        "error over time (the largest error after any step) of runs that ended stable; a "
        "meaningless or unstable run shows its verdict.\n\n"
     << reading(f) << "\n\n"
     << walls_table(f) << "\n";
  return StudyReport{.markdown = md.str(), .claims = walls_claims(f)};
}

std::string walls_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  std::ostringstream md;
  md << "**What it shows.** " << reading(find(rows)) << "Details: [" << spec.name << ".md]("
     << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kWalls{{
    .name = "walls",
    .summary = "each cell with Dirichlet walls and with periodic boundaries, side by side",
    .records = {.error_over_time = true, .crossings = true},
    .report = walls_report,
    .index = walls_index,
}};

}  // namespace
}  // namespace mpmstab::studies::walls
