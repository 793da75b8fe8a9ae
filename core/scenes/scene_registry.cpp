#include "scenes/scene_registry.hpp"

#include "scenes/bar.hpp"
#include "scenes/block.hpp"
#include "scenes/compaction.hpp"
#include "scenes/impact.hpp"
#include "scenes/impulsive.hpp"
#include "scenes/mode.hpp"
#include "scenes/steffen.hpp"
#include "scenes/tip_load.hpp"
#include "scenes/vibration.hpp"

namespace mpmstab {

const SceneInfo& scene_info(SceneKind kind) {
  switch (kind) {
    case SceneKind::bar:
      return BarScene::kInfo;
    case SceneKind::steffen:
      return SteffenScene::kInfo;
    case SceneKind::mode:
      return ModeScene::kInfo;
    case SceneKind::vibration:
      return VibrationScene::kInfo;
    case SceneKind::impulsive:
      return ImpulsiveScene::kInfo;
    case SceneKind::compaction:
      return CompactionScene::kInfo;
    case SceneKind::block:
      return BlockScene::kInfo;
    case SceneKind::impact:
      return ImpactScene::kInfo;
  }
  return BarScene::kInfo;
}

namespace {

// The scene p.scene declares, before any load p adds to it.
std::unique_ptr<Scene> make_declared_scene(const RunParams& p) {
  const double start = body_start(p), length = body_length(p);
  switch (p.scene) {
    case SceneKind::bar:
      return std::make_unique<BarScene>(p.E, p.A);
    case SceneKind::steffen:
      return std::make_unique<SteffenScene>(p.E, p.A);
    case SceneKind::mode:
      return std::make_unique<ModeScene>(p.E, p.A);
    case SceneKind::vibration:
      return std::make_unique<VibrationScene>(p.E, p.A, length);
    case SceneKind::impulsive:
      return std::make_unique<ImpulsiveScene>(p.E, p.A, length);
    case SceneKind::compaction:
      return std::make_unique<CompactionScene>(p.E, p.A, length);
    case SceneKind::block:
      return std::make_unique<BlockScene>(p.E, p.A, start, length);
    case SceneKind::impact:
      return std::make_unique<ImpactScene>(p.E, p.A, start, length);
  }
  return std::make_unique<BarScene>(p.E, p.A);
}

}  // namespace

std::unique_ptr<Scene> make_scene(const RunParams& p) {
  std::unique_ptr<Scene> scene = make_declared_scene(p);
  if (p.tip_load != 0) return std::make_unique<TipLoadedScene>(std::move(scene), p.tip_load);
  return scene;
}

double body_start(const RunParams& p) {
  return std::isnan(p.body_start) ? scene_info(p.scene).body_start : p.body_start;
}
double body_length(const RunParams& p) {
  return std::isnan(p.body_length) ? scene_info(p.scene).body_length : p.body_length;
}

std::int64_t spectral_state_size(const RunParams& p) {
  const auto [first, last] = body_cells(body_start(p), body_length(p), p.cells);
  const std::int64_t n = std::int64_t{last - first} * p.ppc;
  return (p.transfer == Transfer::apic ? 3 : 2) * n;
}

}  // namespace mpmstab
