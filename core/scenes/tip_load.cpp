#include "scenes/tip_load.hpp"

#include <utility>

namespace mpmstab {

namespace {

// The sum of two loads at the particles.
class SumOfLoads final : public BodyForceAtParticles {
 public:
  SumOfLoads(std::unique_ptr<BodyForceAtParticles> first,
             std::unique_ptr<BodyForceAtParticles> second)
      : first_(std::move(first)), second_(std::move(second)) {}
  void evaluate(double t, Eigen::ArrayXd& b) const override {
    first_->evaluate(t, b);
    second_->evaluate(t, other_);
    b += other_;
  }

 private:
  std::unique_ptr<BodyForceAtParticles> first_, second_;
  mutable Eigen::ArrayXd other_;
};

}  // namespace

TipLoadedScene::TipLoadedScene(std::unique_ptr<Scene> scene, double tip_load)
    : Scene(scene->E, scene->A, scene->x0, scene->L),
      scene_(std::move(scene)),
      tip_(scene_->E, tip_load * scene_->A, scene_->L) {}

double TipLoadedScene::displacement(double X, double t) const {
  return scene_->displacement(X, t) + tip_.displacement(X, t);
}
double TipLoadedScene::velocity(double X, double t) const {
  return scene_->velocity(X, t) + tip_.velocity(X, t);
}
double TipLoadedScene::stress(double X, double t) const {
  return scene_->stress(X, t) + tip_.stress(X, t);
}

void TipLoadedScene::displacements(const Eigen::ArrayXd& X, double t, Eigen::ArrayXd& u) const {
  scene_->displacements(X, t, u);
  for (Eigen::Index p = 0; p < X.size(); ++p)
    u[p] += tip_.displacement(X[p], t);
}

std::unique_ptr<BodyForceAtParticles> TipLoadedScene::body_force_at(const Eigen::ArrayXd& X) const {
  if (!scene_->has_body_force()) return tip_.body_force_at(X);
  return std::make_unique<SumOfLoads>(scene_->body_force_at(X), tip_.body_force_at(X));
}

}  // namespace mpmstab
