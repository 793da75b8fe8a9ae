// The dispersion study: how fast and how damped each scheme carries a wave
// (core/analysis/dispersion.hpp). From the Bloch symbol of the uniform layout: the phase speed
// c_num / c and the damping |lambda| of the physical branch against kh at a few Courant numbers,
// for every basis and transfer, and the cells per wavelength each needs for a phase error of at
// most kPhaseTolerance. Checked by its cases, single-mode runs of the mode scene (a free standing
// wave of the periodic bar whose wavelength is the bar's length): the period each run measures
// against the one the branch predicts at its kh and Courant number.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/bloch.hpp"
#include "analysis/dispersion.hpp"
#include "base/params.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "spec.hpp"
#include "study.hpp"

namespace mpmstab::studies::dispersion {
namespace {

using ojson = nlohmann::ordered_json;

constexpr double kPi = std::numbers::pi;

// The Courant numbers c dt / h of the Bloch curves and of the table of cells per wavelength.
const std::vector<double> kCourants = {0.1, 0.25, 0.5, 0.75};
// Every basis, each with every transfer (USL); XPIC and FMPM at order kSeriesOrder.
const std::vector<Method> kBases = {Method::mpm,  Method::gimp,     Method::cpgimp,
                                    Method::cpdi, Method::bspline2, Method::bspline3};
const std::vector<Transfer> kTransfers = {Transfer::flip, Transfer::pic, Transfer::apic,
                                          Transfer::xpic, Transfer::fmpm};
constexpr int kSeriesOrder = 2;
// The figure draws every basis with FLIP and this basis with every other transfer.
constexpr Method kTransferBasis = Method::gimp;
// The figure's curves: kh = pi j / kFigureSamples, j = 1 .. kFigureSamples.
constexpr int kFigureSamples = 96;
// A scheme is consistent when its phase speed at the smallest kh of the scan
// (pi / kDispersionSamples) lies within kConsistency of 1.
constexpr double kConsistency = 1e-4;
// The measured period of a single-mode run agrees with the predicted one within this fraction.
constexpr double kPeriodAgreement = 1e-4;
// The reading names the most accurate scheme among those that keep at least this fraction of
// the wave's amplitude over one period.
constexpr double kWellKept = 0.9;
// Two schemes need the same cells per wavelength when they agree within this fraction.
constexpr double kSameCells = 1e-6;
// The index's headline: the cells per wavelength of linear MPM and the cubic B-spline with FLIP
// and of the cubic B-spline with FMPM at the index's Courant number (one of kCourants).
constexpr std::size_t kIndexCourant = 1;
const std::vector<std::pair<Method, Transfer>> kHeadline = {{Method::mpm, Transfer::flip},
                                                            {Method::bspline3, Transfer::flip},
                                                            {Method::bspline3, Transfer::fmpm}};

// The amplitude a branch point keeps over one period: |lambda| to the power of the steps per
// period, a full turn of phase divided by the phase per step (0 where the phase does not turn).
double kept_per_period(const DispersionPoint& d) {
  return d.phase > 0 ? std::pow(d.damping, 2 * kPi / d.phase) : 0.0;
}

// One single-mode run: its prediction from the branch and its measured period.
struct ModeRun {
  const ojson* row = nullptr;
  std::string label;
  int cells = 0;
  double courant = 0, dt = 0, exact = 0;
  double predicted = 0;  // 2 pi dt / arg(lambda)
  double kept = 0;       // |lambda| over one predicted period: the amplitude the branch keeps
  ModePeriod measured;
  bool measured_ok() const { return measured.periods > 0; }
  double relative() const { return measured.period / predicted - 1; }
};

// The single-mode runs: the period each case measures (measure_mode_period, a run the report makes
// itself; the index and the subtitle do without) beside the one its branch predicts.
std::vector<ModeRun> mode_runs(const Spec& spec, const std::vector<ojson>& rows) {
  std::vector<ModeRun> out;
  for (std::size_t i = 0; i < rows.size() && i < spec.cases.size(); ++i) {
    const RunParams& p = spec.cases[i].params;
    ModeRun m;
    m.row = &rows[i];
    m.label = method_label(rows[i]);
    m.cells = p.cells;
    m.courant = *courant_number(p);
    m.dt = *fixed_step(p);
    m.exact = 1 / wave_speed(p);
    const DispersionPoint predicted = dispersion_at(p, m.courant, 2 * kPi / p.cells);
    m.predicted = 2 * kPi * m.dt / predicted.phase;
    m.kept = kept_per_period(predicted);
    m.measured = measure_mode_period(p);
    out.push_back(m);
  }
  return out;
}

// A scheme's flat description, as a row names it (method_label).
ojson scheme_row(const RunParams& p) {
  ojson r;
  r["method"] = std::string(to_string(p.method));
  r["transfer"] = std::string(to_string(p.transfer));
  r["xpic_order"] = p.transfer == Transfer::xpic ? ojson(p.xpic_order) : ojson(nullptr);
  r["fmpm_order"] = p.transfer == Transfer::fmpm ? ojson(p.fmpm_order) : ojson(nullptr);
  r["update"] = std::string(to_string(p.update));
  return r;
}

// One Courant number of one scheme: left out above the spectral limit; else the cells per
// wavelength for the tolerance and the phase speed at the first kh of the scan.
struct AtCourant {
  double courant = 0;
  bool below_limit = false;
  std::optional<double> cells;  // for |c_num / c - 1| <= kPhaseTolerance
  double kept = 0;              // the amplitude kept over one period at that wavelength
  double first_phase_speed = 0;
};

struct Scheme {
  RunParams params;
  std::string label;
  bool drawn = false;  // in the figure
  std::optional<double> limit;
  std::vector<AtCourant> at;                         // one per kCourants
  std::vector<std::vector<DispersionPoint>> curves;  // drawn schemes: one per kCourants (empty
                                                     // above the limit)
};

// Every scheme at the cases' particles per cell, with its Bloch limit, its cells per wavelength
// and, where drawn, its curves.
std::vector<Scheme> bloch_schemes(int ppc) {
  std::vector<double> figure_khs;
  for (int j = 1; j <= kFigureSamples; ++j)
    figure_khs.push_back(kPi * j / kFigureSamples);
  std::vector<Scheme> out;
  for (const Transfer t : kTransfers)
    for (const Method m : kBases) {
      Scheme s;
      s.params.method = m;
      s.params.transfer = t;
      s.params.xpic_order = kSeriesOrder;
      s.params.fmpm_order = kSeriesOrder;
      s.params.ppc = ppc;
      s.params = dispersion_scheme(s.params);
      s.label = method_label(scheme_row(s.params));
      s.drawn = t == Transfer::flip || m == kTransferBasis;
      s.limit = bloch_courant(s.params);
      for (const double C : kCourants) {
        AtCourant a;
        a.courant = C;
        a.below_limit = !s.limit || C < *s.limit;
        std::vector<DispersionPoint> curve;
        if (a.below_limit) {
          a.cells = cells_per_wavelength(s.params, C);
          // One branch: the first kh of the scan, the wavelength found and the figure's kh.
          const double first = kPi / kDispersionSamples;
          const double kh_cells = a.cells ? 2 * kPi / *a.cells : first;
          std::vector<double> khs = figure_khs;
          khs.push_back(first);
          khs.push_back(kh_cells);
          // Finite by construction, so < orders them: pi j / kFigureSamples, pi /
          // kDispersionSamples and 2 pi / cells, cells_per_wavelength being 2 pi over a kh in
          // (0, pi] (or 2).
          std::sort(khs.begin(), khs.end());
          for (const DispersionPoint& d : dispersion_branch(s.params, C, khs)) {
            if (d.kh == first) a.first_phase_speed = d.phase_speed;
            if (a.cells && d.kh == kh_cells) a.kept = kept_per_period(d);
            if (std::binary_search(figure_khs.begin(), figure_khs.end(), d.kh) &&
                (curve.empty() || curve.back().kh != d.kh))
              curve.push_back(d);
          }
        }
        s.at.push_back(a);
        if (s.drawn) s.curves.push_back(std::move(curve));
      }
      out.push_back(std::move(s));
    }
  return out;
}

// The schemes of a basis or of a transfer, in the table's order.
const Scheme* find_scheme(const std::vector<Scheme>& schemes, Method m, Transfer t) {
  for (const auto& s : schemes)
    if (s.params.method == m && s.params.transfer == t) return &s;
  return nullptr;
}

// The fewest cells per wavelength at one Courant number, and the schemes that need as many.
struct Fewest {
  std::vector<std::string> schemes;
  double cells = 0, kept = 0;
};
// One Courant number: the fewest cells per wavelength of every scheme and, where those do not
// keep kWellKept of the amplitude, of the schemes that do; the schemes above their spectral limit.
struct Reading {
  std::optional<Fewest> fewest, fewest_kept;
  std::vector<std::string> above_limit;
};

// The pairs of a B-spline and a Courant number compared (spline_pairs), those that hold, and the
// pairs themselves: "C = 0.1: mpm 23.0, bspline2 30.1; ...".
struct SplinePairs {
  int hits = 0, compared = 0;
  std::string pairs;
};

// What the study finds: every scheme's branch and cells per wavelength, the single-mode runs
// against their prediction, and what the claims, the text, the index and the subtitle count.
struct Findings {
  std::size_t cases = 0;
  int ppc = 0;        // the cases' particles per cell, every scheme's
  std::string bloch;  // what decides the claims no run decides: the Bloch symbol of that layout
  std::vector<Scheme> schemes;
  std::vector<Reading> readings;  // one per kCourants
  std::vector<std::string> drawn;
  int consistent = 0, branches = 0;  // branches whose phase speed at the first kh is within
  double worst_deviation = 0;        // kConsistency of one, and the largest deviation
  std::string worst_branch = "–";
  SplinePairs flip, full_mass;
  std::vector<ModeRun> runs;
  long meaningless = 0;                  // runs marked meaningless
  int agree = 0, measured = 0;           // runs whose measured period agrees with the prediction
  std::optional<std::size_t> worst_run;  // the largest relative difference
  int nearer = 0, compared = 0;          // runs nearer the prediction than the exact period
  Coverage measured_on, compared_on;     // the runs measured, and those compared
};

// The B-splines' cells per wavelength at each Courant number: with FLIP against linear MPM's
// (fmpm false: the pairs that need more), or with FMPM against their own with FLIP (fmpm true:
// the pairs that need fewer).
SplinePairs spline_pairs(const std::vector<Scheme>& schemes, bool fmpm) {
  SplinePairs p;
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    // Cells per wavelength of one basis with one transfer at Courant number k, if computed.
    const auto cells_of = [&](Method m, Transfer t) {
      const Scheme* s = find_scheme(schemes, m, t);
      return s ? s->at[k].cells : std::nullopt;
    };
    const auto linear = cells_of(Method::mpm, Transfer::flip);
    if (!fmpm && !linear) continue;
    std::string part = fmpm ? "" : "mpm " + fixed(*linear, 1);
    for (const Method m : {Method::bspline2, Method::bspline3}) {
      const auto flip = cells_of(m, Transfer::flip);
      const auto against = fmpm ? flip : linear;
      const auto cells = fmpm ? cells_of(m, Transfer::fmpm) : flip;
      if (!cells || !against) continue;
      ++p.compared;
      p.hits += fmpm ? *cells < *against : *cells > *against;
      part += std::string(part.empty() ? "" : ", ") + std::string(to_string(m)) + " " +
              fixed(*cells, 1) + (fmpm ? " against " + fixed(*against, 1) : "");
    }
    if (!part.empty())
      p.pairs += (p.pairs.empty() ? "" : "; ") + ("C = " + shortest(kCourants[k]) + ": " + part);
  }
  if (p.pairs.empty()) p.pairs = "–";
  return p;
}

// The findings from the rows and, in the report, the single-mode runs (mode_runs).
Findings find(const std::vector<ojson>& rows, std::vector<ModeRun> runs = {}) {
  Findings f;
  f.cases = rows.size();
  f.runs = std::move(runs);
  // The single-mode runs against their prediction.
  for (std::size_t i = 0; i < f.runs.size(); ++i) {
    const ModeRun& m = f.runs[i];
    f.meaningless += outcome(*m.row) == "meaningless";
    if (!m.measured_ok()) continue;
    ++f.measured;
    f.measured_on.add(*m.row);
    f.agree += std::abs(m.relative()) <= kPeriodAgreement;
    if (!f.worst_run || std::abs(m.relative()) > std::abs(f.runs[*f.worst_run].relative()))
      f.worst_run = i;
    if (std::abs(m.predicted / m.exact - 1) <= kPeriodAgreement) continue;
    ++f.compared;
    f.compared_on.add(*m.row);
    f.nearer += std::abs(m.measured.period - m.predicted) < std::abs(m.measured.period - m.exact);
  }
  if (rows.empty()) return f;
  f.ppc = rows.front()["ppc"].get<int>();
  f.bloch = "the Bloch symbol of the uniform layout, " + std::to_string(f.ppc) +
            " particles per cell, USL (no run)";
  f.schemes = bloch_schemes(f.ppc);
  // The reading of each Courant number, the schemes drawn, the consistency of every branch and
  // the B-splines' cells per wavelength.
  const auto fewest = [&](std::size_t k, bool well_kept) -> std::optional<Fewest> {
    // At Courant number k, of every scheme or of those that keep kWellKept, with every tie.
    const auto in = [&](const AtCourant& a) {
      return a.cells && (!well_kept || a.kept >= kWellKept);
    };
    const AtCourant* best = nullptr;
    for (const auto& s : f.schemes)
      if (in(s.at[k]) && (!best || *s.at[k].cells < *best->cells)) best = &s.at[k];
    if (!best) return std::nullopt;
    Fewest least{{}, *best->cells, best->kept};
    for (const auto& s : f.schemes)
      if (in(s.at[k]) && std::abs(*s.at[k].cells - least.cells) <= kSameCells * least.cells)
        least.schemes.push_back(s.label);
    return least;
  };
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    Reading r{fewest(k, false), fewest(k, true), {}};
    if (r.fewest && r.fewest->kept >= kWellKept) r.fewest_kept.reset();  // the same schemes
    for (const auto& s : f.schemes)
      if (!s.at[k].below_limit) r.above_limit.push_back(s.label);
    f.readings.push_back(r);
  }
  for (const auto& s : f.schemes) {
    if (s.drawn) f.drawn.push_back(s.label);
    for (const auto& a : s.at) {
      if (!a.below_limit) continue;
      ++f.branches;
      const double e = std::abs(a.first_phase_speed - 1);
      f.consistent += e <= kConsistency;
      if (e >= f.worst_deviation) {
        f.worst_deviation = e;
        f.worst_branch = s.label + " at C = " + shortest(a.courant);
      }
    }
  }
  f.flip = spline_pairs(f.schemes, false);
  f.full_mass = spline_pairs(f.schemes, true);
  return f;
}

Claim period_claim(const Findings& f) {
  const ModeRun* worst = f.worst_run ? &f.runs[*f.worst_run] : nullptr;
  return claim("period-agrees-with-bloch",
               "The measured period of every single-mode run agrees with the Bloch "
               "prediction within {tolerance}",
               "{agree} of {runs} runs ({measured} with a measured period); the largest "
               "relative difference is {worst}, {scheme} at {cells} cells per wavelength and "
               "C = {C}")
      .value("tolerance", percent(kPeriodAgreement))
      .every("agree", f.agree, "runs", static_cast<long long>(f.runs.size()))
      .count("measured", f.measured)
      .value("worst", worst ? sci(worst->relative(), 2) : "–")
      .value("scheme", worst ? worst->label : "–")
      .value("cells", worst ? std::to_string(worst->cells) : "–")
      .value("C", worst ? shortest(worst->courant) : "–")
      .on(f.measured_on);
}

// The prediction explains the measured period: it lies nearer the prediction than the exact
// period, on every run whose predicted period differs from the exact one by more than the
// agreement.
Claim explains_claim(const Findings& f) {
  return claim("dispersion-explains-period",
               "Where the scheme's period differs from the exact one, the measured period "
               "is the one the Bloch symbol predicts, not the exact one",
               "{nearer} of {compared} runs whose predicted period differs from the exact "
               "one by more than {tolerance} measure a period nearer the prediction")
      .every("nearer", f.nearer, "compared", f.compared)
      .value("tolerance", percent(kPeriodAgreement))
      .on(f.compared_on);
}

Claim consistency_claim(const Findings& f) {
  return claim("phase-speed-tends-to-one",
               "Every scheme's phase speed tends to the wave speed as kh tends to zero",
               "at kh = pi / {samples}: {consistent} of {curves} branches (scheme and Courant "
               "number) within {tolerance} of c; the largest deviation is {worst}, "
               "{scheme}")
      .count("samples", kDispersionSamples)
      .every("consistent", f.consistent, "curves", f.branches)
      .value("tolerance", sci(kConsistency, 1))
      .value("worst", sci(f.worst_deviation, 2))
      .value("scheme", f.worst_branch)
      .on(f.bloch);
}

// With FLIP, each B-spline needs more cells per wavelength than linear MPM: FLIP's transfer
// acts as the mass M_L M^-1 M_L (docs/theory.md, "Dispersion"), and a wider basis's consistent
// mass M differs more from its lumped one. With FMPM (the full mass matrix's series) each needs
// fewer than with FLIP: the transfer, not the basis, sets the phase error.
Claim spline_claim(const Findings& f, bool fmpm) {
  const SplinePairs& p = fmpm ? f.full_mass : f.flip;
  Claim c = fmpm ? claim("full-mass-splines-need-fewer-cells",
                         "With FMPM({order}), the quadratic and cubic B-splines need fewer cells "
                         "per wavelength than with FLIP for a phase error of {tolerance}, at every "
                         "Courant number below the limit",
                         "{hits} of {compared} pairs of a B-spline and a Courant number ({pairs})")
                 : claim("flip-splines-need-more-cells",
                         "With FLIP, the quadratic and cubic B-splines need more cells per "
                         "wavelength than linear MPM for a phase error of {tolerance}, at every "
                         "Courant number",
                         "{hits} of {compared} pairs of a B-spline and a Courant number ({pairs})");
  if (fmpm) c.count("order", kSeriesOrder);
  return c.value("tolerance", percent(kPhaseTolerance))
      .every("hits", p.hits, "compared", p.compared)
      .value("pairs", p.pairs)
      .on(f.bloch);
}

std::string cells_text(const AtCourant& a) {
  if (!a.below_limit) return "above the limit";
  return a.cells ? fixed(*a.cells, 1) : std::string("not reached");
}

// A table of every scheme, one column per Courant number: its cells per wavelength (after its
// spectral limit), or the amplitude it keeps over one period at that wavelength.
std::string scheme_table(const std::vector<Scheme>& schemes, bool cells) {
  std::ostringstream md;
  md << (cells ? "| scheme | spectral limit (c dt / h) |" : "| scheme |");
  for (const double C : kCourants)
    md << " C = " << shortest(C) << " |";
  md << (cells ? "\n|---|---|" : "\n|---|") << rule_cells(kCourants.size()) << "\n";
  for (const auto& s : schemes) {
    md << "| " << s.label << " |";
    if (cells) md << " " << opt_fixed(s.limit, 4) << " |";
    for (const auto& a : s.at)
      md << " " << (cells ? cells_text(a) : a.cells ? fixed(a.kept, 3) : std::string("–")) << " |";
    md << "\n";
  }
  return md.str();
}

// The reading of the tables: at each Courant number the schemes that need the fewest cells per
// wavelength, with the amplitude they keep, and the fewest among the schemes that keep at least
// kWellKept of it.
std::string reading(const Findings& f) {
  std::ostringstream md;
  md << "**Reading** (computed from the table).";
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    const Reading& r = f.readings[k];
    if (!r.fewest) continue;
    md << " At C = " << shortest(kCourants[k])
       << " the fewest cells per wavelength: " << list_of(r.fewest->schemes) << ", "
       << fixed(r.fewest->cells, 1) << " (keeping " << fixed(r.fewest->kept, 3)
       << " of the amplitude per period there)";
    if (r.fewest_kept) {
      md << "; of the schemes that keep at least " << shortest(kWellKept) << ", "
         << list_of(r.fewest_kept->schemes) << ", " << fixed(r.fewest_kept->cells, 1)
         << " (keeping " << fixed(r.fewest_kept->kept, 3) << ")";
    }
    md << ".";
  }
  md << "\n\n";
  return md.str();
}

// The Courant numbers left out of some scheme, with the schemes: "0.75 (bspline3, ...)".
std::string left_out_text(const Findings& f) {
  std::vector<std::string> parts;
  for (std::size_t k = 0; k < kCourants.size(); ++k)
    if (!f.readings[k].above_limit.empty())
      parts.push_back("C = " + shortest(kCourants[k]) + " for " +
                      list_of(f.readings[k].above_limit));
  return parts.empty() ? "none" : list_of(parts);
}

std::string runs_table(const std::vector<ModeRun>& runs) {
  std::ostringstream md;
  md << "| scheme | cells per wavelength | C | steps per exact period | exact period | predicted "
        "period | measured period | periods measured | relative difference, measured to predicted "
        "| amplitude kept per period (predicted) | run "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& m : runs) {
    md << "| " << m.label << " | " << m.cells << " | " << shortest(m.courant) << " | "
       << fixed(m.exact / m.dt, 1) << " | " << significant(m.exact, 6) << " | "
       << significant(m.predicted, 6) << " | "
       << (m.measured_ok() ? significant(m.measured.period, 6) : std::string("–")) << " | "
       << m.measured.periods << " | " << (m.measured_ok() ? sci(m.relative(), 2) : "–") << " | "
       << significant(m.kept, 4) << " | " << verdict(*m.row) << " |\n";
  }
  return md.str();
}

std::string dispersion_markdown(const ReportContext& c, const Findings& f) {
  const ojson& first = c.rows.front();
  std::ostringstream md;
  md << "![The phase speed of the physical branch against kh](" << c.spec.name << ".png)\n\n"
     << "A Fourier mode of the uniform layout with phase kh per cell (k the wavenumber, h the "
        "cell size: the wave spans a full turn of phase divided by kh cells) is multiplied each "
        "step by the eigenvalues of the Bloch symbol S(kh) (docs/theory.md, \"Dispersion\"). The "
        "*physical branch* is the acoustic eigenvalue lambda of positive phase, followed "
        "continuously from kh near zero; its phase speed is c_num / c = arg(lambda) / (C kh) and "
        "its damping |lambda| per step, at the Courant number C = c dt / h. Every scheme here is "
        "USL with "
     << f.ppc << " particles per cell at the uniform layout; XPIC and FMPM at order "
     << kSeriesOrder
     << ". E only rescales time (docs/theory.md, \"Dimensionless coordinates\"): the phase "
        "speed, the damping per step and the period in units of 1/c depend on C, kh and the scheme "
        "alone, so the runs take E = "
     << shortest(first["E"].get<double>())
     << ". A Courant number at or above a scheme's spectral limit is left out for it (its "
        "branch amplifies some wave there): "
     << left_out_text(f) << ".\n\n";

  md << "## Cells per wavelength for a phase error of " << percent(kPhaseTolerance) << "\n\n"
     << "The smallest number of cells per wavelength above which the phase error |c_num - c| / c "
        "stays within "
     << percent(kPhaseTolerance)
     << " (the scan of kh from the longest waves up, then a bisection): on a coarser grid some "
        "wave the grid carries runs more than "
     << percent(kPhaseTolerance) << " too fast or too slow. Multiply by the particles per cell ("
     << f.ppc << ") for particles per wavelength.\n\n"
     << scheme_table(f.schemes, true) << "\n"
     << "**Amplitude kept per period** at the cells per wavelength of the table above: "
        "|lambda| to the power of the steps per period (a full turn of phase divided by "
        "arg(lambda)).\n\n"
     << scheme_table(f.schemes, false) << "\n"
     << reading(f);

  md << "## Single-mode runs: the predicted and the measured period\n\n"
     << "Each case runs the mode scene: one free standing wave of the periodic bar whose "
        "wavelength is the bar's length, u = A sin(2 pi X) cos(omega t), no body force, exact "
        "period 1/c, at A = "
     << value_text(first["A"].get<double>())
     << " (linear) to T = " << shortest(first["T"].get<double>())
     << " on as many cells as the wave has cells per wavelength. The measured period is twice "
        "the mean spacing of the extrema (maxima and minima) of the mode's amplitude a(t) = sum_p "
        "V_p (x_p - X_p) s_p / sum_p V_p s_p s_p, V_p the reference volume and s_p the mode's "
        "shape sin(2 pi X) at X_p, each extremum the turning point of the quartic through the five "
        "values around it. Extrema, not zero crossings: the displacement sums the grid velocities "
        "over the steps, so it oscillates about a small constant offset, and where the scheme "
        "damps the oscillation shrinks under the offset and the zero crossings drift, while the "
        "turning points stay half a period apart. The predicted period is the branch's, a full "
        "turn of phase divided by arg(lambda) per step, at the run's kh and C; the amplitude kept "
        "per period is |lambda| to the power of the predicted steps per period. The run column is "
        "the harness's verdict against the exact wave: "
     << f.meaningless << " of " << f.runs.size()
     << " runs are marked meaningless because their error over time reached A (the scheme's "
        "wave drifts out of phase with the exact one, whose period differs from its own); their "
        "periods are measured all the same.\n\n"
     << runs_table(f.runs) << "\n"
     << "The figure draws " << list_of(f.drawn)
     << "; schemes whose curves coincide share one line, named by all of them. A curve ends "
        "where the branch's eigenvalue turns real (it meets its mirror image on the real axis) and "
        "the wave no longer propagates.\n\n";
  return md.str();
}

// The study's JSON: the cells per wavelength, for the other studies to read.
ojson dispersion_json(const std::vector<Scheme>& schemes, const std::vector<ModeRun>& runs) {
  ojson j = {{"phase_tolerance", kPhaseTolerance},
             {"courants", kCourants},
             {"cells_per_wavelength", ojson::array()},
             {"periods", ojson::array()}};
  for (const auto& s : schemes)
    for (const auto& a : s.at)
      j["cells_per_wavelength"].push_back(
          {{"method", s.label},
           {"basis", std::string(to_string(s.params.method))},
           {"transfer", std::string(to_string(s.params.transfer))},
           {"update", std::string(to_string(s.params.update))},
           {"ppc", s.params.ppc},
           {"courant", a.courant},
           {"spectral_limit", s.limit ? ojson(*s.limit) : ojson(nullptr)},
           {"below_limit", a.below_limit},
           {"cells_per_wavelength_1pct", a.cells ? ojson(*a.cells) : ojson(nullptr)}});
  for (const auto& m : runs)
    j["periods"].push_back(
        {{"method", m.label},
         {"cells", m.cells},
         {"courant", m.courant},
         {"exact_period", m.exact},
         {"predicted_period", m.predicted},
         {"measured_period", m.measured_ok() ? ojson(m.measured.period) : ojson(nullptr)},
         {"periods_measured", m.measured.periods},
         {"relative_difference", m.measured_ok() ? ojson(m.relative()) : ojson(nullptr)}});
  return j;
}

std::string dispersion_index(const Spec& spec, const std::vector<ojson>& rows,
                             const ojson& published) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name
     << ".png)\n\n**What it shows.** The phase speed and damping of every basis and transfer "
        "against the wavenumber, from the Bloch symbol, at C = "
     << listing(std::vector<double>(kCourants)) << "; the cells per wavelength each needs for "
     << "a phase error of " << percent(kPhaseTolerance);
  if (published.contains("cells_per_wavelength")) {  // as the report published them
    std::vector<std::string> parts;
    for (const auto& [m, t] : kHeadline)
      for (const auto& c : published["cells_per_wavelength"])
        if (c["basis"] == to_string(m) && c["transfer"] == to_string(t) &&
            c["courant"] == kCourants[kIndexCourant]) {
          const ojson& cells = c["cells_per_wavelength_1pct"];
          parts.push_back(
              c["method"].get<std::string>() + " " +
              opt_fixed(cells.is_null() ? std::nullopt : std::optional(cells.get<double>()), 1));
        }
    md << " (at C = " << shortest(kCourants[kIndexCourant]) << ": " << list_of(parts) << ")";
  }
  md << "; and " << rows.size()
     << " single-mode runs whose measured period is set against the predicted one: [" << spec.name
     << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

// Two schemes whose phase speeds agree at every Courant number and kh within kSameCurve (a
// branch that stops propagating counts as phase speed 0) are drawn as one series named by both
// ("mpm = gimp": at the uniform layout with two particles per cell the weights of GIMP, cpGIMP
// and CPDI at rest are the hat's at the particle).
constexpr double kSameCurve = 1e-5;

bool same_curves(const Scheme& a, const Scheme& b) {
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    if (a.curves[k].size() != b.curves[k].size()) return false;
    for (std::size_t i = 0; i < a.curves[k].size(); ++i) {
      const DispersionPoint &p = a.curves[k][i], &q = b.curves[k][i];
      if (std::abs(p.phase_speed - q.phase_speed) > kSameCurve) return false;
    }
  }
  return true;
}

// The figure's series: each drawn scheme, those with the same curves merged.
struct Series {
  std::string name;
  const Scheme* scheme = nullptr;
};

std::vector<Series> figure_series(const std::vector<Scheme>& schemes) {
  std::vector<Series> out;
  for (const auto& s : schemes) {
    if (!s.drawn) continue;
    auto same = std::find_if(out.begin(), out.end(),
                             [&](const Series& e) { return same_curves(*e.scheme, s); });
    if (same != out.end()) {
      same->name += " = " + s.label;
    } else {
      out.push_back({s.label, &s});
    }
  }
  return out;
}

// The figure's data: the drawn schemes' curves where they propagate, one panel per Courant
// number.
std::string dispersion_data(const std::vector<Scheme>& schemes, const std::string& header) {
  std::vector<std::string> panels, names;
  for (const double C : kCourants)
    panels.push_back("C = " + shortest(C));
  const std::vector<Series> series = figure_series(schemes);
  for (const auto& e : series)
    names.push_back(e.name);
  std::ostringstream csv;
  csv << header << "# panel: " << codes(panels) << "; series: " << codes(names)
      << "; kh in radians per cell; phase_speed c_num / c; damping |lambda| per step; a series "
         "has no rows at a Courant number at or above its spectral limit, nor where its branch "
         "does not propagate\n"
      << "panel,courant,series,scheme,kh,phase_speed,damping\n";
  for (std::size_t k = 0; k < kCourants.size(); ++k)
    for (std::size_t code = 0; code < series.size(); ++code)
      for (const auto& d : series[code].scheme->curves[k]) {
        if (!d.propagates) continue;
        csv << k << ',' << shortest(kCourants[k]) << ',' << code << ',' << series[code].name << ','
            << shortest(d.kh) << ',' << shortest(d.phase_speed) << ',' << shortest(d.damping)
            << '\n';
      }
  return csv.str();
}

std::string dispersion_subtitle(const Spec&, const ojson& doc) {
  const ojson& rows = doc["cases"];
  if (rows.empty()) return "";
  return "USL, " + std::to_string(rows.front()["ppc"].get<int>()) +
         " particles per cell, uniform layout (the Bloch symbol of the interior); every basis "
         "with FLIP, and " +
         std::string(to_string(kTransferBasis)) + " with every other transfer";
}

// The report: the findings once (with the single-mode runs), and from them the claims, the text,
// the figure's data and the study's JSON.
StudyReport dispersion_report(const ReportContext& c) {
  const Findings f = find(c.rows, mode_runs(c.spec, c.rows));
  return StudyReport{.markdown = dispersion_markdown(c, f),
                     .data_csv = dispersion_data(f.schemes, c.csv_header),
                     .json = dispersion_json(f.schemes, f.runs),
                     .claims = {period_claim(f), explains_claim(f), consistency_claim(f),
                                spline_claim(f, false), spline_claim(f, true)}};
}

const StudyRegistration kDispersion{{
    .name = "dispersion",
    .summary = "phase speed and damping of every scheme from the Bloch symbol, the cells per "
               "wavelength for a small phase error, and single-mode runs that measure the period",
    .figure = true,
    .report = dispersion_report,
    .index = dispersion_index,
    .figure_subtitle = dispersion_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::dispersion
