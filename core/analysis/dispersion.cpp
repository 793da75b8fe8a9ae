#include "analysis/dispersion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "analysis/bloch.hpp"
#include "analysis/eigen_solve.hpp"
#include "scenes/validate.hpp"
#include "step/simulation.hpp"

namespace mpmstab {

namespace {

constexpr double kPi = std::numbers::pi;
// The symbol is recovered from this many samples on the circle (its blocks reach at most half as
// many cells), doubled up to kMaxSymbolSamples until it matches a direct sample.
constexpr int kSymbolSamples = 32;
constexpr int kMaxSymbolSamples = 256;
// A wavenumber off every sampling grid, and the agreement asked there (relative to the size of
// the symbol; its entries are central differences of the step, exact to about 1e-10).
constexpr double kCheckTheta = 0.7371;
constexpr double kSymbolAgreement = 1e-9;
// The share of an eigenvector's norm in the grid's mode that makes it acoustic.
constexpr double kAcousticShare = 0.5;
// An eigenvalue with |Im lambda| at most this fraction of |lambda| is real (the symbol's entries
// are exact to about 1e-10; past a meeting on the real axis Im lambda is exactly 0).
constexpr double kRealEigenvalue = 1e-9;
// The bisection for the cells per wavelength stops at this relative width in kh.
constexpr double kBisectionTolerance = 1e-6;

// S(theta) = sum_d B_d e^{-i d theta} from its samples at theta_m = 2 pi m / N: the blocks are
// B_d = (1/N) sum_m S(theta_m) e^{i d theta_m}, d = -N/2 .. N/2 - 1 (exact while the map reaches
// fewer than N/2 cells). One symbol is then a sum of a few real blocks per wavenumber, where
// bloch_symbol builds the program's map anew at every call.
class SymbolSeries {
 public:
  SymbolSeries(const RunParams& q, double courant) {
    for (int n = kSymbolSamples; n <= kMaxSymbolSamples; n *= 2) {
      build(q, courant, n);
      const Eigen::MatrixXcd direct = bloch_symbol(q, courant, kCheckTheta);
      const double size = 1 + direct.cwiseAbs().maxCoeff();
      if ((at(kCheckTheta) - direct).cwiseAbs().maxCoeff() <= kSymbolAgreement * size) return;
    }
    throw std::invalid_argument("dispersion: the Bloch symbol reaches beyond " +
                                std::to_string(kMaxSymbolSamples / 2) + " cells");
  }

  Eigen::MatrixXcd at(double theta) const {
    Eigen::MatrixXcd S = Eigen::MatrixXcd::Zero(size_, size_);
    for (std::size_t k = 0; k < blocks_.size(); ++k)
      S += blocks_[k].cast<std::complex<double>>() *
           std::polar(1.0, -double(min_d_ + int(k)) * theta);
    return S;
  }

 private:
  void build(const RunParams& q, double courant, int n) {
    std::vector<Eigen::MatrixXcd> samples;
    for (int m = 0; m < n; ++m)
      samples.push_back(bloch_symbol(q, courant, 2 * kPi * m / n));
    size_ = samples.front().rows();
    min_d_ = -n / 2;
    blocks_.clear();
    for (int d = min_d_; d < n / 2; ++d) {
      Eigen::MatrixXcd B = Eigen::MatrixXcd::Zero(size_, size_);
      for (int m = 0; m < n; ++m)
        B += samples[std::size_t(m)] * std::polar(1.0, d * 2 * kPi * m / n);
      blocks_.push_back((B / double(n)).real());
    }
  }

  Eigen::Index size_ = 0;
  int min_d_ = 0;
  std::vector<Eigen::MatrixXd> blocks_;  // B_{min_d_ + k}
};

// The share of w's norm in the grid's mode: every particle of the cell with the same velocity
// and the same strain (values 0 and 1 of the state; APIC's affine velocities are not in it).
double acoustic_share(const Eigen::VectorXcd& w, int ppc) {
  double inside = 0;
  for (int v = 0; v < 2; ++v)
    inside += std::norm(w.segment(Eigen::Index(v) * ppc, ppc).sum()) / ppc;
  return inside / w.squaredNorm();
}

// The physical branch followed along increasing kh.
class Branch {
 public:
  Branch(const RunParams& p, double courant)
      : symbol_(dispersion_scheme(p), courant), courant_(courant), ppc_(p.ppc) {
    if (!(courant > 0) || !std::isfinite(courant))
      throw std::invalid_argument("dispersion: the Courant number must be > 0");
  }

  // The branch at kh from the last point committed (or the start rule at the first, and with
  // `anew` at any kh, ignoring the points committed); with `commit`, it becomes the last point.
  DispersionPoint at(double kh, bool commit, bool anew = false) {
    const bool start = !started_ || anew;
    const EigenPairs es = eigen_pairs(symbol_.at(kh), true);
    const auto& values = es.values;
    const Eigen::Index n = values.size();
    Eigen::Index pick = -1;
    double best = 0;
    for (Eigen::Index j = 0; j < n; ++j) {
      const Eigen::VectorXcd w = es.vectors.col(j).normalized();
      double score;
      if (start) {
        // Nearest e^{i C kh} among the acoustic eigenvectors of positive phase.
        if (std::arg(values[j]) <= 0 || acoustic_share(w, ppc_) < kAcousticShare) continue;
        score = -std::abs(values[j] - std::polar(1.0, courant_ * kh));
      } else {
        score = std::abs(w_.dot(w));  // |<w_prev, w>|
      }
      if (pick < 0 || score > best) {
        pick = j;
        best = score;
      }
    }
    if (pick < 0) throw std::runtime_error("dispersion: no acoustic eigenvalue at the first kh");
    DispersionPoint point;
    point.kh = kh;
    point.lambda = values[pick];
    point.phase =
        start ? std::arg(point.lambda) : last_.phase + std::arg(point.lambda / last_.lambda);
    point.phase_speed = point.phase / (courant_ * kh);
    point.damping = std::abs(point.lambda);
    if ((ended_ && !start) || std::abs(point.lambda.imag()) <= kRealEigenvalue * point.damping) {
      point.propagates = false;
      point.phase = point.phase_speed = 0;
    }
    if (commit) {
      ended_ = !point.propagates;
      w_ = es.vectors.col(pick).normalized();
      last_ = point;
      started_ = true;
    }
    return point;
  }

  const DispersionPoint& last() const { return last_; }

 private:
  SymbolSeries symbol_;
  double courant_;
  int ppc_;
  bool started_ = false;
  bool ended_ = false;  // the branch has turned real
  DispersionPoint last_;
  Eigen::VectorXcd w_;
};

double grid_kh(int j) {
  return kPi * j / kDispersionSamples;
}

}  // namespace

RunParams dispersion_scheme(const RunParams& p) {
  RunParams q = p;
  q.scene = SceneKind::bar;
  q.bc = Boundary::dirichlet;
  q.walls = Walls::clip;
  q.A = 0;
  if (!bloch_applies(q)) {
    throw std::invalid_argument(
        "dispersion: the Bloch symbol needs a uniform layout (no jitter) and at most " +
        std::to_string(kMaxBlochSymbol) + " values per cell");
  }
  return q;
}

std::vector<DispersionPoint> dispersion_branch(const RunParams& p, double courant,
                                               const std::vector<double>& khs) {
  for (std::size_t i = 0; i < khs.size(); ++i) {
    if (!(khs[i] > 0) || !(khs[i] <= kPi) || (i > 0 && khs[i] < khs[i - 1]))
      throw std::invalid_argument("dispersion: kh must be ascending in (0, pi]");
  }
  Branch branch(p, courant);
  std::vector<DispersionPoint> out;
  int j = 1;
  for (const double kh : khs) {
    for (; j <= kDispersionSamples && grid_kh(j) < kh; ++j)
      branch.at(grid_kh(j), true);
    out.push_back(branch.at(kh, true));
  }
  return out;
}

DispersionPoint dispersion_at(const RunParams& p, double courant, double kh) {
  return dispersion_branch(p, courant, {kh}).front();
}

std::optional<double> cells_per_wavelength(const RunParams& p, double courant, double tolerance) {
  Branch branch(p, courant);
  const auto error = [](const DispersionPoint& d) { return std::abs(d.phase_speed - 1); };
  for (int j = 1; j <= kDispersionSamples; ++j) {
    const DispersionPoint& lo = branch.last();
    const DispersionPoint hi = branch.at(grid_kh(j), false);
    if (error(hi) > tolerance) {
      if (j == 1) return std::nullopt;
      // Bisection between the last kh within the tolerance and the first beyond it, each
      // midpoint followed from the last one within.
      double a = lo.kh, b = hi.kh;
      while (b - a > kBisectionTolerance * a) {
        const double mid = 0.5 * (a + b);
        (error(branch.at(mid, false)) > tolerance ? b : a) = mid;
      }
      return 2 * kPi / b;
    }
    branch.at(grid_kh(j), true);
  }
  return 2.0;  // within the tolerance up to kh = pi
}

double amplitude_error(const DispersionPoint& d, double courant, double periods) {
  if (!(courant > 0) || !(periods > 0))
    throw std::invalid_argument("amplitude_error: the Courant number and periods must be > 0");
  if (!d.propagates) return std::numeric_limits<double>::infinity();
  const double steps = periods * 2 * kPi / (courant * d.kh);
  const std::complex<double> ratio =
      std::polar(std::pow(d.damping, steps), steps * (d.phase - courant * d.kh));
  return std::abs(ratio - 1.0);
}

std::optional<double> cells_per_wavelength_amplitude(const RunParams& p, double courant,
                                                     double periods, double tolerance) {
  Branch branch(p, courant);
  const auto error = [&](const DispersionPoint& d) { return amplitude_error(d, courant, periods); };
  // Bisection between a kh within the tolerance and one beyond it; `at` gives the branch there.
  const auto bisect = [&](double a, double b, const auto& at) {
    while (b - a > kBisectionTolerance * a) {
      const double mid = 0.5 * (a + b);
      (error(at(mid)) > tolerance ? b : a) = mid;
    }
    return 2 * kPi / b;
  };
  for (int j = 1; j <= kDispersionSamples; ++j) {
    const DispersionPoint& lo = branch.last();
    const DispersionPoint hi = branch.at(grid_kh(j), false);
    if (error(hi) > tolerance) {
      if (j > 1) return bisect(lo.kh, hi.kh, [&](double kh) { return branch.at(kh, false); });
      // Below the scan: each kh identified anew by the start rule.
      const auto fresh = [&](double kh) { return branch.at(kh, false, true); };
      const double longest = 2 * kPi / kMaxCellsPerWavelength;
      for (double b = hi.kh; b / 2 >= longest * (1 - kBisectionTolerance); b /= 2) {
        if (error(fresh(b / 2)) <= tolerance) return bisect(b / 2, b, fresh);
      }
      return std::nullopt;
    }
    branch.at(grid_kh(j), true);
  }
  return 2.0;  // within the tolerance up to kh = pi
}

double predicted_mode_period(const RunParams& p) {
  const auto C = courant_number(p);
  const auto dt = fixed_step(p);
  if (!C || !dt || p.cells < 2)
    throw std::invalid_argument("predicted_mode_period: needs a fixed step and at least 2 cells");
  const DispersionPoint d = dispersion_at(p, *C, 2 * kPi / p.cells);
  return d.propagates ? 2 * kPi * *dt / d.phase : std::numeric_limits<double>::infinity();
}

namespace {

// The value at t of the polynomial through the points (ts[i], as[i]) (Lagrange's form).
double interpolate(const std::vector<double>& ts, const std::vector<double>& as, double t) {
  double sum = 0;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    double term = as[i];
    for (std::size_t k = 0; k < ts.size(); ++k)
      if (k != i) term *= (t - ts[k]) / (ts[i] - ts[k]);
    sum += term;
  }
  return sum;
}

// The turning point near sample n (a strict extremum of its neighbours): the root between
// t[n - 1] and t[n + 1] of the derivative of the polynomial through samples n - 2 .. n + 2
// (fewer at either end of the run), by bisection; t[n] if that derivative does not change sign.
double extremum_time(const std::vector<double>& t, const std::vector<double>& a, std::size_t n) {
  const std::size_t first = n >= 2 ? n - 2 : n - 1;
  const std::size_t last = std::min(n + 2, t.size() - 1);
  const std::vector<double> ts(t.begin() + long(first), t.begin() + long(last) + 1);
  const std::vector<double> as(a.begin() + long(first), a.begin() + long(last) + 1);
  const double delta = 1e-6 * (t[n + 1] - t[n - 1]);
  const auto slope = [&](double s) {
    return interpolate(ts, as, s + delta) - interpolate(ts, as, s - delta);
  };
  double lo = t[n - 1], hi = t[n + 1];
  const bool rising = slope(lo) > 0;
  if (rising == (slope(hi) > 0)) return t[n];
  for (int it = 0; it < 100 && hi - lo > 1e-13 * std::abs(hi); ++it) {
    const double mid = 0.5 * (lo + hi);
    ((slope(mid) > 0) == rising ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

ModePeriod measure_mode_period(const RunParams& p) {
  const auto dt = fixed_step(p);
  if (p.scene != SceneKind::mode || !dt || !validate(p).empty())
    throw std::invalid_argument("measure_mode_period: needs a valid fixed-step run of scene mode");
  Simulation sim(p);
  const Particles& P = sim.particles();
  const Eigen::ArrayXd weight = P.volume0 * (2 * kPi * P.X).sin();
  const double norm = (weight * (2 * kPi * P.X).sin()).sum();
  const auto amplitude = [&] { return (weight * (P.x - P.X)).sum() / norm; };

  // The steps of a run (run.cpp): t^n = n dt, the last one landing on T.
  const std::int64_t steps = *step_count(p.T, std::min(*dt, p.T));
  std::vector<double> t = {0.0}, a = {amplitude()};
  t.reserve(std::size_t(steps) + 1);
  a.reserve(std::size_t(steps) + 1);
  for (std::int64_t n = 1; n <= steps; ++n) {
    sim.advance_to(n == steps ? p.T : double(n) * *dt);
    const double value = amplitude();
    if (!std::isfinite(value)) break;
    t.push_back(sim.time());
    a.push_back(value);
  }

  ModePeriod out;
  const double floor = kModeNoiseFloor * std::abs(a.front());
  for (std::size_t n = 1; n + 1 < a.size(); ++n) {
    const bool maximum = a[n] > a[n - 1] && a[n] > a[n + 1];
    const bool minimum = a[n] < a[n - 1] && a[n] < a[n + 1];
    // The swing from the neighbouring samples: the oscillation, not the offset.
    if (!(maximum || minimum) || std::abs(a[n] - a[n - 1]) + std::abs(a[n] - a[n + 1]) <= floor)
      continue;
    const double te = extremum_time(t, a, n);
    if (out.extrema == 0) out.first_extremum = te;
    out.last_extremum = te;
    ++out.extrema;
  }
  if (out.extrema >= 2) {
    out.periods = 0.5 * (out.extrema - 1);
    out.period = (out.last_extremum - out.first_extremum) / out.periods;
  }
  return out;
}

}  // namespace mpmstab
