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

namespace mpmstab {

namespace studies::dispersion {
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

// The amplitude a branch point keeps over one period: |lambda| to the power of the steps per
// period, a full turn of phase divided by the phase per step (0 where the phase does not turn).
double kept_per_period(const DispersionPoint& d) {
  return d.phase > 0 ? std::pow(d.damping, 2 * kPi / d.phase) : 0.0;
}

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
  for (const Transfer t : kTransfers) {
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
  }
  return out;
}

// One single-mode run: its prediction from the branch and its measured period.
struct ModeRun {
  const ojson* row = nullptr;
  std::string label;
  int cells = 0;
  double courant = 0, dt = 0, exact = 0;
  DispersionPoint predicted_point;
  double predicted = 0;  // 2 pi dt / arg(lambda)
  ModePeriod measured;
  bool measured_ok() const { return measured.periods > 0; }
  double relative() const { return measured.period / predicted - 1; }
  // |lambda| over one predicted period: the amplitude the branch keeps.
  double kept() const { return kept_per_period(predicted_point); }
};

std::vector<ModeRun> mode_runs(const ReportContext& c) {
  std::vector<ModeRun> out;
  for (std::size_t i = 0; i < c.rows.size() && i < c.spec.cases.size(); ++i) {
    const ojson& r = c.rows[i];
    const RunParams& p = c.spec.cases[i].params;
    ModeRun m;
    m.row = &r;
    m.label = method_label(r);
    m.cells = p.cells;
    m.courant = *courant_number(p);
    m.dt = *fixed_step(p);
    m.exact = 1 / wave_speed(p);
    m.predicted_point = dispersion_at(p, m.courant, 2 * kPi / p.cells);
    m.predicted = 2 * kPi * m.dt / m.predicted_point.phase;
    m.measured = measure_mode_period(p);
    out.push_back(m);
  }
  return out;
}

std::string cells_text(const AtCourant& a) {
  if (!a.below_limit) return "above the limit";
  return a.cells ? fixed(*a.cells, 1) : std::string("not reached");
}

std::string courant_header() {
  std::string s;
  for (const double C : kCourants)
    s += " C = " + shortest(C) + " |";
  return s;
}

// The schemes of a basis or of a transfer, in the table's order.
const Scheme* find_scheme(const std::vector<Scheme>& schemes, Method m, Transfer t) {
  for (const auto& s : schemes)
    if (s.params.method == m && s.params.transfer == t) return &s;
  return nullptr;
}

std::string cells_table(const std::vector<Scheme>& schemes) {
  std::ostringstream md;
  md << "| scheme | spectral limit (c dt / h) |" << courant_header() << "\n|---|---|";
  for (std::size_t k = 0; k < kCourants.size(); ++k)
    md << "---|";
  md << "\n";
  for (const auto& s : schemes) {
    md << "| " << s.label << " | " << (s.limit ? fixed(*s.limit, 4) : std::string("–")) << " |";
    for (const auto& a : s.at)
      md << " " << cells_text(a) << " |";
    md << "\n";
  }
  return md.str();
}

// The amplitude each scheme keeps over one period at the wavelength of the cells table.
std::string kept_table(const std::vector<Scheme>& schemes) {
  std::ostringstream md;
  md << "| scheme |" << courant_header() << "\n|---|";
  for (std::size_t k = 0; k < kCourants.size(); ++k)
    md << "---|";
  md << "\n";
  for (const auto& s : schemes) {
    md << "| " << s.label << " |";
    for (const auto& a : s.at)
      md << " " << (a.cells ? fixed(a.kept, 3) : std::string("–")) << " |";
    md << "\n";
  }
  return md.str();
}

// The reading of the tables: at each Courant number the scheme that needs the fewest cells per
// wavelength, with the amplitude it keeps, and the fewest among the schemes that keep at least
// kWellKept of it.
std::string reading(const std::vector<Scheme>& schemes) {
  // The schemes whose cells per wavelength equal s's at Courant number k (within kSameCells):
  // "mpm/apic, gimp/apic, cpgimp/apic and cpdi/apic".
  const auto tied = [&](const Scheme& s, std::size_t k, bool well_kept) {
    std::vector<std::string> names;
    for (const auto& o : schemes) {
      const AtCourant& a = o.at[k];
      if (a.cells && (!well_kept || a.kept >= kWellKept) &&
          std::abs(*a.cells - *s.at[k].cells) <= kSameCells * *s.at[k].cells)
        names.push_back(o.label);
    }
    return list_of(names);
  };
  std::ostringstream md;
  md << "**Reading** (computed from the table).";
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    const Scheme *best = nullptr, *kept = nullptr;
    for (const auto& s : schemes) {
      const AtCourant& a = s.at[k];
      if (!a.cells) continue;
      if (!best || *a.cells < *best->at[k].cells) best = &s;
      if (a.kept >= kWellKept && (!kept || *a.cells < *kept->at[k].cells)) kept = &s;
    }
    if (!best) continue;
    md << " At C = " << shortest(kCourants[k])
       << " the fewest cells per wavelength: " << tied(*best, k, false) << ", "
       << fixed(*best->at[k].cells, 1) << " (keeping " << fixed(best->at[k].kept, 3)
       << " of the amplitude per period there)";
    if (kept && kept != best) {
      md << "; of the schemes that keep at least " << shortest(kWellKept) << ", "
         << tied(*kept, k, true) << ", " << fixed(*kept->at[k].cells, 1) << " (keeping "
         << fixed(kept->at[k].kept, 3) << ")";
    }
    md << ".";
  }
  md << "\n\n";
  return md.str();
}

// The Courant numbers left out of some scheme, with the schemes: "0.75 (bspline3, ...)".
std::string left_out_text(const std::vector<Scheme>& schemes) {
  std::vector<std::string> parts;
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    std::vector<std::string> names;
    for (const auto& s : schemes)
      if (!s.at[k].below_limit) names.push_back(s.label);
    if (!names.empty()) parts.push_back("C = " + shortest(kCourants[k]) + " for " + list_of(names));
  }
  return parts.empty() ? "none" : list_of(parts);
}

std::string runs_table(const std::vector<ModeRun>& runs) {
  std::ostringstream md;
  md << "| scheme | cells per wavelength | C | steps per exact period | exact period | predicted "
        "period "
        "| measured period | periods measured | relative difference, measured to predicted | "
        "amplitude kept per "
        "period (predicted) | run |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& m : runs) {
    md << "| " << m.label << " | " << m.cells << " | " << shortest(m.courant) << " | "
       << fixed(m.exact / m.dt, 1) << " | " << significant(m.exact, 6) << " | "
       << significant(m.predicted, 6) << " | "
       << (m.measured_ok() ? significant(m.measured.period, 6) : std::string("–")) << " | "
       << m.measured.periods << " | " << (m.measured_ok() ? sci(m.relative(), 2) : "–") << " | "
       << significant(m.kept(), 4) << " | " << verdict(*m.row) << " |\n";
  }
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Claims

Claim period_claim(const std::vector<ModeRun>& runs) {
  int agree = 0, measured = 0;
  const ModeRun* worst = nullptr;
  for (const auto& m : runs) {
    if (!m.measured_ok()) continue;
    ++measured;
    agree += std::abs(m.relative()) <= kPeriodAgreement;
    if (!worst || std::abs(m.relative()) > std::abs(worst->relative())) worst = &m;
  }
  Claim c = claim("period-agrees-with-bloch",
                  "The measured period of every single-mode run agrees with the Bloch "
                  "prediction within {tolerance}",
                  "{agree} of {runs} runs ({measured} with a measured period); the largest "
                  "relative difference is {worst}, {scheme} at {cells} cells per wavelength and "
                  "C = {C}");
  c.value("tolerance", percent(kPeriodAgreement))
      .every("agree", agree, "runs", static_cast<long long>(runs.size()))
      .count("measured", measured)
      .value("worst", worst ? sci(worst->relative(), 2) : "–")
      .value("scheme", worst ? worst->label : "–")
      .value("cells", worst ? std::to_string(worst->cells) : "–")
      .value("C", worst ? shortest(worst->courant) : "–");
  return c;
}

// The prediction explains the measured period: it lies nearer the prediction than the exact
// period, on every run whose predicted period differs from the exact one by more than the
// agreement.
Claim explains_claim(const std::vector<ModeRun>& runs) {
  int nearer = 0, compared = 0;
  for (const auto& m : runs) {
    if (!m.measured_ok() || std::abs(m.predicted / m.exact - 1) <= kPeriodAgreement) continue;
    ++compared;
    nearer += std::abs(m.measured.period - m.predicted) < std::abs(m.measured.period - m.exact);
  }
  Claim c = claim("dispersion-explains-period",
                  "Where the scheme's period differs from the exact one, the measured period "
                  "is the one the Bloch symbol predicts, not the exact one",
                  "{nearer} of {compared} runs whose predicted period differs from the exact "
                  "one by more than {tolerance} measure a period nearer the prediction");
  c.every("nearer", nearer, "compared", compared).value("tolerance", percent(kPeriodAgreement));
  return c;
}

Claim consistency_claim(const std::vector<Scheme>& schemes) {
  int consistent = 0, curves = 0;
  double worst = 0;
  std::string worst_label = "–";
  for (const auto& s : schemes) {
    for (const auto& a : s.at) {
      if (!a.below_limit) continue;
      ++curves;
      const double e = std::abs(a.first_phase_speed - 1);
      consistent += e <= kConsistency;
      if (e >= worst) {
        worst = e;
        worst_label = s.label + " at C = " + shortest(a.courant);
      }
    }
  }
  Claim c = claim("phase-speed-tends-to-one",
                  "Every scheme's phase speed tends to the wave speed as kh tends to zero",
                  "at kh = pi / {samples}: {consistent} of {curves} branches (scheme and "
                  "Courant number) within {tolerance} of c; the largest deviation is {worst}, "
                  "{scheme}");
  c.count("samples", kDispersionSamples)
      .every("consistent", consistent, "curves", curves)
      .value("tolerance", sci(kConsistency, 1))
      .value("worst", sci(worst, 2))
      .value("scheme", worst_label);
  return c;
}

// Cells per wavelength of one basis with one transfer at Courant number k, if computed.
std::optional<double> cells_of(const std::vector<Scheme>& schemes, Method m, Transfer t,
                               std::size_t k) {
  const Scheme* s = find_scheme(schemes, m, t);
  return s ? s->at[k].cells : std::nullopt;
}

const std::vector<Method> kSplines = {Method::bspline2, Method::bspline3};

// With FLIP, each B-spline needs more cells per wavelength than linear MPM: FLIP's transfer
// acts as the mass M_L M^-1 M_L (docs/theory.md, "Dispersion"), and a wider basis's consistent
// mass M differs more from its lumped one.
Claim flip_spline_claim(const std::vector<Scheme>& schemes) {
  int more = 0, compared = 0;
  std::string pairs;
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    const auto linear = cells_of(schemes, Method::mpm, Transfer::flip, k);
    if (!linear) continue;
    std::string part = "C = " + shortest(kCourants[k]) + ": mpm " + fixed(*linear, 1);
    for (const Method m : kSplines) {
      const auto spline = cells_of(schemes, m, Transfer::flip, k);
      if (!spline) continue;
      ++compared;
      more += *spline > *linear;
      part += ", " + std::string(to_string(m)) + " " + fixed(*spline, 1);
    }
    pairs += (pairs.empty() ? "" : "; ") + part;
  }
  Claim c = claim("flip-splines-need-more-cells",
                  "With FLIP, the quadratic and cubic B-splines need more cells per wavelength "
                  "than linear MPM for a phase error of {tolerance}, at every Courant number",
                  "{more} of {compared} pairs of a B-spline and a Courant number ({pairs})");
  c.value("tolerance", percent(kPhaseTolerance))
      .every("more", more, "compared", compared)
      .value("pairs", pairs.empty() ? "–" : pairs);
  return c;
}

// With FMPM (the full mass matrix's series) each B-spline needs fewer cells per wavelength than
// with FLIP: the transfer, not the basis, sets the phase error.
Claim full_mass_claim(const std::vector<Scheme>& schemes) {
  int fewer = 0, compared = 0;
  std::string pairs;
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    std::string part;
    for (const Method m : kSplines) {
      const auto flip = cells_of(schemes, m, Transfer::flip, k);
      const auto full = cells_of(schemes, m, Transfer::fmpm, k);
      if (!flip || !full) continue;
      ++compared;
      fewer += *full < *flip;
      part += std::string(part.empty() ? "" : ", ") + std::string(to_string(m)) + " " +
              fixed(*full, 1) + " against " + fixed(*flip, 1);
    }
    if (!part.empty())
      pairs += (pairs.empty() ? "" : "; ") + ("C = " + shortest(kCourants[k]) + ": " + part);
  }
  Claim c = claim("full-mass-splines-need-fewer-cells",
                  "With FMPM({order}), the quadratic and cubic B-splines need fewer cells per "
                  "wavelength than with FLIP for a phase error of {tolerance}, at every Courant "
                  "number below the limit",
                  "{fewer} of {compared} pairs of a B-spline and a Courant number ({pairs})");
  c.count("order", kSeriesOrder)
      .value("tolerance", percent(kPhaseTolerance))
      .every("fewer", fewer, "compared", compared)
      .value("pairs", pairs.empty() ? "–" : pairs);
  return c;
}

// ---------------------------------------------------------------------------------------------
// Report

std::string dispersion_markdown(const ReportContext& c, const std::vector<Scheme>& schemes,
                                const std::vector<ModeRun>& runs) {
  const ojson& first = c.rows.front();
  const auto meaningless = std::count_if(
      runs.begin(), runs.end(), [](const ModeRun& m) { return outcome(*m.row) == "meaningless"; });
  std::vector<std::string> drawn;
  for (const auto& s : schemes)
    if (s.drawn) drawn.push_back(s.label);
  std::ostringstream md;
  md << "![The phase speed of the physical branch against kh](" << c.spec.name << ".png)\n\n"
     << "A Fourier mode of the uniform layout with phase kh per cell (k the wavenumber, h the "
        "cell size: the wave spans a full turn of phase divided by kh cells) is multiplied each "
        "step by the eigenvalues of the Bloch symbol S(kh) (docs/theory.md, \"Dispersion\"). The "
        "*physical branch* is the acoustic eigenvalue lambda of positive phase, followed "
        "continuously from kh near zero; its phase speed is c_num / c = arg(lambda) / (C kh) "
        "and its damping |lambda| per step, at the Courant number C = c dt / h. Every scheme "
        "here is USL with "
     << first["ppc"].get<int>()
     << " particles per cell at the uniform layout; XPIC and FMPM at order " << kSeriesOrder
     << ". E only rescales time (docs/theory.md, \"Dimensionless coordinates\"): the phase "
        "speed, the damping per step and the period in units of 1/c depend on C, kh and the "
        "scheme alone, so the runs take E = "
     << shortest(first["E"].get<double>())
     << ". A Courant number at or above a scheme's spectral limit is left out for it (its "
        "branch amplifies some wave there): "
     << left_out_text(schemes) << ".\n\n";

  md << "## Cells per wavelength for a phase error of " << percent(kPhaseTolerance) << "\n\n"
     << "The smallest number of cells per wavelength above which the phase error |c_num - c| / c "
        "stays within "
     << percent(kPhaseTolerance)
     << " (the scan of kh from the longest waves up, then a bisection): on a coarser grid some "
        "wave the grid carries runs more than "
     << percent(kPhaseTolerance) << " too fast or too slow. Multiply by the particles per cell ("
     << first["ppc"].get<int>() << ") for particles per wavelength.\n\n"
     << cells_table(schemes) << "\n"
     << "**Amplitude kept per period** at the cells per wavelength of the table above: "
        "|lambda| to the power of the steps per period (a full turn of phase divided by "
        "arg(lambda)).\n\n"
     << kept_table(schemes) << "\n"
     << reading(schemes);

  md << "## Single-mode runs: the predicted and the measured period\n\n"
     << "Each case runs the mode scene: one free standing wave of the periodic bar whose "
        "wavelength is the bar's length, u = A sin(2 pi X) cos(omega t), no body force, exact "
        "period 1/c, at A = "
     << value_text(first["A"].get<double>())
     << " (linear) to T = " << shortest(first["T"].get<double>())
     << " on as many cells as the wave has cells per wavelength. The measured period is twice "
        "the mean spacing of the extrema (maxima and minima) of the mode's amplitude "
        "a(t) = sum_p V_p (x_p - X_p) s_p / sum_p V_p s_p s_p, V_p the reference volume and s_p "
        "the mode's shape sin(2 pi X) at X_p, each extremum the turning point of the quartic "
        "through the five values around "
        "it. Extrema, not zero crossings: the displacement sums the grid velocities over the "
        "steps, so it oscillates about a small constant offset, and where the scheme damps the "
        "oscillation shrinks under the offset and the zero crossings drift, while the turning "
        "points stay half a period apart. The predicted period is the branch's, a full turn of "
        "phase divided by arg(lambda) per step, at the run's kh and C; the amplitude kept per "
        "period is |lambda| to the power of the predicted steps per period. The run column is "
        "the harness's verdict against the exact wave: "
     << meaningless << " of " << runs.size()
     << " runs are marked meaningless because their error over time reached A (the scheme's "
        "wave drifts out of phase with the exact one, whose period differs from its own); their "
        "periods are measured all the same.\n\n"
     << runs_table(runs) << "\n"
     << "The figure draws " << list_of(drawn)
     << "; schemes whose curves coincide share one line, named by all of them. A curve ends "
        "where the branch's eigenvalue turns real (it meets its mirror image on the real axis) "
        "and the wave no longer propagates.\n\n";
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
  for (std::size_t k = 0; k < kCourants.size(); ++k) {
    for (std::size_t code = 0; code < series.size(); ++code) {
      for (const auto& d : series[code].scheme->curves[k]) {
        if (!d.propagates) continue;
        csv << k << ',' << shortest(kCourants[k]) << ',' << code << ',' << series[code].name << ','
            << shortest(d.kh) << ',' << shortest(d.phase_speed) << ',' << shortest(d.damping)
            << '\n';
      }
    }
  }
  return csv.str();
}

// The study's JSON: the cells per wavelength, for the other studies to read.
ojson dispersion_json(const std::vector<Scheme>& schemes, const std::vector<ModeRun>& runs) {
  ojson j;
  j["phase_tolerance"] = kPhaseTolerance;
  j["courants"] = kCourants;
  ojson cells = ojson::array();
  for (const auto& s : schemes) {
    for (const auto& a : s.at) {
      ojson e;
      e["method"] = s.label;
      e["basis"] = std::string(to_string(s.params.method));
      e["transfer"] = std::string(to_string(s.params.transfer));
      e["update"] = std::string(to_string(s.params.update));
      e["ppc"] = s.params.ppc;
      e["courant"] = a.courant;
      e["spectral_limit"] = s.limit ? ojson(*s.limit) : ojson(nullptr);
      e["below_limit"] = a.below_limit;
      e["cells_per_wavelength_1pct"] = a.cells ? ojson(*a.cells) : ojson(nullptr);
      cells.push_back(e);
    }
  }
  j["cells_per_wavelength"] = cells;
  ojson periods = ojson::array();
  for (const auto& m : runs) {
    ojson e;
    e["method"] = m.label;
    e["cells"] = m.cells;
    e["courant"] = m.courant;
    e["exact_period"] = m.exact;
    e["predicted_period"] = m.predicted;
    e["measured_period"] = m.measured_ok() ? ojson(m.measured.period) : ojson(nullptr);
    e["periods_measured"] = m.measured.periods;
    e["relative_difference"] = m.measured_ok() ? ojson(m.relative()) : ojson(nullptr);
    periods.push_back(e);
  }
  j["periods"] = periods;
  return j;
}

std::string dispersion_subtitle(const Spec&, const ojson& doc) {
  const auto& rows = doc["cases"];
  if (rows.empty()) return "";
  return "USL, " + std::to_string(rows.front()["ppc"].get<int>()) +
         " particles per cell, uniform layout (the Bloch symbol of the interior); every basis "
         "with FLIP, and " +
         std::string(to_string(kTransferBasis)) + " with every other transfer";
}

// The index's headline: the cells per wavelength of linear MPM and the cubic B-spline with FLIP
// and of the cubic B-spline with FMPM at the index's Courant number.
constexpr double kIndexCourant = 0.25;

std::string dispersion_index(const Spec& spec, const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name
     << ".png)\n\n**What it shows.** The phase speed and damping of every basis and transfer "
        "against the wavenumber, from the Bloch symbol, at C = "
     << listing(std::vector<double>(kCourants)) << "; the cells per wavelength each needs for "
     << "a phase error of " << percent(kPhaseTolerance);
  if (!rows.empty()) {
    std::vector<std::string> parts;
    for (const auto& [m, t] :
         {std::pair{Method::mpm, Transfer::flip}, std::pair{Method::bspline3, Transfer::flip},
          std::pair{Method::bspline3, Transfer::fmpm}}) {
      RunParams p;
      p.method = m;
      p.transfer = t;
      p.fmpm_order = kSeriesOrder;
      p.ppc = rows.front()["ppc"].get<int>();
      const auto cells = cells_per_wavelength(p, kIndexCourant);
      parts.push_back(method_label(scheme_row(p)) + " " +
                      (cells ? fixed(*cells, 1) : std::string("–")));
    }
    md << " (at C = " << shortest(kIndexCourant) << ": " << list_of(parts) << ")";
  }
  md << "; and " << rows.size()
     << " single-mode runs whose measured period is set against the predicted one: [" << spec.name
     << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kDispersion{{
    .name = "dispersion",
    .summary = "phase speed and damping of every scheme from the Bloch symbol, the cells per "
               "wavelength for a small phase error, and single-mode runs that measure the period",
    .figure = true,
    .report =
        [](const ReportContext& c) {
          const std::vector<Scheme> schemes = bloch_schemes(c.rows.front()["ppc"].get<int>());
          const std::vector<ModeRun> runs = mode_runs(c);
          std::vector<Claim> claims = {period_claim(runs), explains_claim(runs),
                                       consistency_claim(schemes), flip_spline_claim(schemes),
                                       full_mass_claim(schemes)};
          return StudyReport{.markdown = dispersion_markdown(c, schemes, runs),
                             .data_csv = dispersion_data(schemes, c.csv_header),
                             .json = dispersion_json(schemes, runs),
                             .claims = std::move(claims)};
        },
    .index = dispersion_index,
    .figure_subtitle = dispersion_subtitle,
}};

}  // namespace
}  // namespace studies::dispersion

}  // namespace mpmstab
