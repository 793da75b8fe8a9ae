#include "shared/by_scene.hpp"

#include "report_util.hpp"

#include <algorithm>

namespace mpmstab {

using ojson = nlohmann::ordered_json;

std::vector<SceneRows> by_scene(const std::vector<ojson>& rows) {
  std::vector<SceneRows> groups;
  for (const auto& r : rows) {
    const std::string scene = r["scene"].get<std::string>();
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const SceneRows& g) { return g.scene == scene; });
    if (it == groups.end()) it = groups.insert(groups.end(), SceneRows{scene, {}});
    it->rows.push_back(r);
  }
  return groups;
}

std::string scene_title(const std::string& scene) {
  if (scene == "steffen")
    return "Second scene: Steffen et al. (2008), neo-Hookean, u = A sin(2 pi X) cos(c pi t)";
  if (scene == "bar") return "The paper's bar";
  return "Scene " + scene;
}

std::string first_scene_subtitle(const Spec& spec, const ojson& doc) {
  const auto& c = doc["cases"][0];
  std::size_t drawn = 0;
  for (const auto& r : doc["cases"])
    drawn += r.value("scene", "") == c.value("scene", "");
  std::string subtitle = std::to_string(drawn) + " cases";
  if (drawn < doc["cases"].size()) {
    subtitle += " of the scene " + c.value("scene", std::string()) + " (of " +
                std::to_string(doc["cases"].size()) + "; every scene is in the tables)";
  }
  return subtitle + "; the parameters of each are in " + spec.name + ".md";
}

StudyReport report_by_scene(const ReportContext& c, SceneSection section, SceneData data) {
  StudyReport report;
  const auto scenes = by_scene(c.rows);
  for (std::size_t i = 0; i < scenes.size(); ++i)
    report.markdown += section(c.spec, scenes[i].rows, i == 0);
  report.data_csv = data(scenes.front().rows, c.csv_header);
  return report;
}

std::string small_mass_of(const ojson& r) {
  return r["small_mass"].is_string() ? r["small_mass"].get<std::string>() : "none";
}

std::optional<double> courant_of(const ojson& r, const char* column) {
  if (!has_number(r, column) || !has_number(r, "dt_cfl")) return std::nullopt;
  return r[column].get<double>() / r["dt_cfl"].get<double>();
}

std::string edge_text(const ojson& r) {
  const auto edge = courant_of(r, "dt_edge");
  // Where the run at the largest surviving dt has no verdict, the scan found no edge.
  if (edge && outcome(r) == "too_short")
    return "none: the run at " + opt_fixed(edge) + " is too short to judge";
  if (edge && !has_number(r, "dt_fail")) return "no dt probed up to a step of T fails";
  if (edge && outcome(r) == "meaningless") return opt_fixed(edge) + " (meaningless)";
  return opt_fixed(edge);
}

}  // namespace mpmstab
