// The one list of the scenes (params.hpp, SceneKind): what each declares and how a run makes
// it. Adding a scene: docs/architecture.md, "How to add a scene".
#pragma once

#include <cstdint>
#include <memory>

#include "base/params.hpp"
#include "scenes/scene.hpp"

namespace mpmstab {

// The declaration of scene `kind` (its class's kInfo).
const SceneInfo& scene_info(SceneKind kind);

// The body's extent in the grid: p.body_start and p.body_length, or the scene's own.
double body_start(const RunParams& p);
double body_length(const RunParams& p);

// The state size of p's linearised one-step map (analysis/spectral.hpp): per particle of the
// body (its cells times ppc), the velocity and the strain, and APIC's affine term.
std::int64_t spectral_state_size(const RunParams& p);

// The scene of a run: p.scene with p.E, p.A and the body's extent body_start(p), body_length(p),
// with the traction p.tip_load on its free end when it is not 0 (scenes/tip_load.hpp).
std::unique_ptr<Scene> make_scene(const RunParams& p);

// Whether scene `kind` is posed with boundaries `bc`, without making the scene (validate()).
inline bool scene_supports(SceneKind kind, Boundary bc) {
  return scene_info(kind).supports(bc);
}

}  // namespace mpmstab
