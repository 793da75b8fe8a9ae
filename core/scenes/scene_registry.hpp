// The one list of the scenes (params.hpp, SceneKind): what each declares and how a run makes
// it. Adding a scene: docs/architecture.md, "How to add a scene".
#pragma once

#include <memory>

#include "params.hpp"
#include "scene.hpp"

namespace mpmstab {

// The declaration of scene `kind` (its class's kInfo).
const SceneInfo& scene_info(SceneKind kind);

// The scene of a run: p.scene with p.E, p.A and the body's extent body_start(p), body_length(p).
std::unique_ptr<Scene> make_scene(const RunParams& p);

// Whether scene `kind` is posed with boundaries `bc`, without making the scene (validate()).
inline bool scene_supports(SceneKind kind, Boundary bc) {
  return scene_info(kind).supports(bc);
}

}  // namespace mpmstab
