#include "observers/energy.hpp"

#include <cmath>

namespace mpmstab {

namespace {

template <bool kWork>
EnergySums sums(const Particles& P, const MaterialLaw& law, const double* v_before, const double* b,
                double dt) {
  EnergySums s;
  for (Eigen::Index p = 0; p < P.size(); ++p) {
    s.kinetic += 0.5 * P.mass[p] * P.v[p] * P.v[p];
    s.strain += P.volume0[p] * law.energy(P.F[p]);
    if constexpr (kWork) s.work += P.mass[p] * b[p] * dt * 0.5 * (v_before[p] + P.v[p]);
  }
  return s;
}

}  // namespace

EnergySums energy_sums(const Particles& P, const MaterialLaw& law, const Eigen::ArrayXd& v_before,
                       const Eigen::ArrayXd& b, double dt) {
  if (b.size() == P.size() && v_before.size() == P.size()) {
    return sums<true>(P, law, v_before.data(), b.data(), dt);
  }
  return sums<false>(P, law, nullptr, nullptr, dt);
}

EnergyObserver::EnergyObserver(const Particles& P, const MaterialLaw& law, const Scene& scene)
    : law_(law), scene_(scene), initial_([&] {
        const EnergySums s = energy_sums(P, law, {}, {}, 0.0);
        return s.kinetic + s.strain;
      }()) {
  v_before_.resize(P.size());
}

void EnergyObserver::before_step(const Particles& P) {
  v_before_ = P.v;
}

EnergySample EnergyObserver::after_step(const Particles& P, const Eigen::ArrayXd& b, double t,
                                        std::int64_t step) {
  EnergySample s;
  const EnergySums sums = energy_sums(P, law_, v_before_, b, t - t_before_);
  s.kinetic = sums.kinetic;
  s.strain = sums.strain;
  work_ += sums.work;
  t_before_ = t;
  s.work = work_;
  s.exact = scene_.exact_energy(t);
  if (initial_ <= 0) return s;
  s.balance = (s.kinetic + s.strain - s.work - initial_) / initial_;
  const double vs_exact =
      std::abs(s.kinetic + s.strain - s.exact.kinetic - s.exact.strain) / initial_;
  const double e = std::abs(s.balance);
  if (!(e <= error_max_)) error_max_ = e;  // a NaN stays
  if (!(vs_exact <= exact_error_max_)) exact_error_max_ = vs_exact;
  if (!warning_step_ && !(e <= kEnergyWarning)) warning_step_ = step;
  n_ += 1;
  st_ += t;
  stt_ += t * t;
  se_ += s.balance;
  ste_ += t * s.balance;
  return s;
}

EnergySummary EnergyObserver::summary() const {
  EnergySummary s;
  if (initial_ <= 0) return s;
  s.error_max = error_max_;
  s.exact_error_max = exact_error_max_;
  s.warning_step = warning_step_;
  const double denominator = n_ * stt_ - st_ * st_;
  if (n_ > 2 && denominator > 0) s.drift = (n_ * ste_ - st_ * se_) / denominator * scene_.period();
  return s;
}

}  // namespace mpmstab
