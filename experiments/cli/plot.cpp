// `mpmstab plot`: a study's figure, drawn by gnuplot from its data.
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "csv.hpp"
#include "report_util.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kPlotHelp = R"(Usage: mpmstab plot <spec.json> [--out DIR]

Draws a figure experiment with gnuplot: runs experiments/<name>.gp (beside the spec) on
DIR/<name>_data.csv and writes DIR/<name>.png and DIR/<name>.svg atomically.
)";

}  // namespace

int cmd_plot(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kPlotHelp;
    return 0;
  }
  if (args.positional().size() != 1) throw UsageError("plot takes one spec");
  const Spec spec = load_specs(args.positional()).front();
  if (!spec.study->figure) {
    throw UsageError(spec.path.string() + ": a " + spec.study->name + " experiment has no figure");
  }
  const auto out = output_folder(args);
  const auto script = spec.path.parent_path() / (spec.name + ".gp");
  const auto data = out / (spec.name + "_data.csv");
  const auto summary = out / (spec.name + ".json");
  for (const auto& f : {script, data, summary}) {
    if (!std::filesystem::exists(f)) throw UsageError(f.string() + " does not exist");
  }
  const auto doc = nlohmann::ordered_json::parse(read_file(summary));
  const std::string subtitle = spec.study->figure_subtitle(spec, doc);
  const std::string dt = spec.study->figure_dt ? spec.study->figure_dt(doc) : "0";
  const auto tmp = out / ("." + spec.name + ".tmp");
  const std::string command = "gnuplot -e \"datafile='" + data.string() + "'; outbase='" +
                              tmp.string() + "'; subtitle='" + subtitle + "'; dt=" + dt + "\" '" +
                              script.string() + "'";
  if (std::system(command.c_str()) != 0) {
    throw std::runtime_error("gnuplot failed: " + command);
  }
  for (const char* ext : {".png", ".svg"}) {
    std::filesystem::rename(tmp.string() + ext, out / (spec.name + ext));
  }
  return 0;
}

}  // namespace mpmstab::cli
