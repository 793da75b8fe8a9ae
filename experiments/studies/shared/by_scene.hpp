// Scenes: studies that run more than one scene report each scene in its own section, the first
// scene of the spec (the paper's bar) first and in the figure.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "spec.hpp"
#include "study.hpp"

namespace mpmstab {

struct SceneRows {
  std::string scene;
  std::vector<nlohmann::ordered_json> rows;
};

// The rows grouped by their "scene" column, in the order the scenes first appear.
std::vector<SceneRows> by_scene(const std::vector<nlohmann::ordered_json>& rows);

// A section title for a scene: "The paper's bar", "Second scene: Steffen et al. (2008), ...".
std::string scene_title(const std::string& scene);

// The subtitle of a study's figure, which draws the first scene: how many cases it draws, and
// of how many when other scenes are only in the tables (a Study::figure_subtitle).
std::string first_scene_subtitle(const Spec& spec, const nlohmann::ordered_json& doc);

// A study's report with one section per scene, the first (the paper's bar) with the figure,
// and the figure's data from the first scene's rows.
using SceneSection = std::string (*)(const Spec& spec,
                                     const std::vector<nlohmann::ordered_json>& rows, bool first);
using SceneData = std::string (*)(const std::vector<nlohmann::ordered_json>& rows,
                                  const std::string& csv_header);
StudyReport report_by_scene(const ReportContext& c, SceneSection section, SceneData data);

// The rows of the scenes with free surfaces (the scene_edges and scenes studies).
// The row's small-mass treatment ("none" where the record has none).
std::string small_mass_of(const nlohmann::ordered_json& r);
// c dt / h of the dt in `column` of a row (its dt_cfl is h / c); none where either is null.
std::optional<double> courant_of(const nlohmann::ordered_json& r, const char* column);
// The survival edge of an edge-search row as a report prints it: its c dt/h, "every dt to T
// survives" where no dt of the scan failed, "0.812 (meaningless)" where the run at the edge is
// meaningless, "–" where it has none.
std::string edge_text(const nlohmann::ordered_json& r);

}  // namespace mpmstab
