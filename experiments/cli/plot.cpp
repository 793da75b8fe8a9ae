// `mpmstab plot`: a study's figure, drawn by gnuplot from its data.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "process.hpp"
#include "report.hpp"
#include "report_util.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kPlotHelp = R"(Usage: mpmstab plot <spec.json> [--out DIR]

Draws a figure experiment with gnuplot: runs experiments/<name>.gp (beside the spec) on
DIR/<name>_data.csv and writes DIR/<name>.png and DIR/<name>.svg atomically.
)";

// A gnuplot string literal holding `s` as data: single-quoted (inside which only a doubled quote
// is special), with every control character (a newline would end the statement) made a space.
std::string gnuplot_string(const std::string& s) {
  std::string q = "'";
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\'') {
      q += "''";
    } else if (c < 0x20 || c == 0x7f) {
      q += ' ';
    } else {
      q += ch;
    }
  }
  return q + "'";
}

// The script's variables, as gnuplot statements that only assign data.
std::string plot_variables(const std::filesystem::path& data, const std::filesystem::path& outbase,
                           const std::string& subtitle, const std::string& dt_text) {
  double dt = 0;
  try {
    dt = std::stod(dt_text);
  } catch (const std::exception&) {
    dt = 0;
  }
  return "datafile = " + gnuplot_string(data.string()) +
         "\noutbase = " + gnuplot_string(outbase.string()) +
         "\nsubtitle = " + gnuplot_string(subtitle) + "\ndt = " + shortest(dt) + "\n";
}

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
  // 1. Inputs: regular files of bounded size (gnuplot never opens a FIFO or a device through
  // us); targets: regular files or absent.
  for (const auto& f : {script, data, summary}) {
    if (!input_exists(f)) throw UsageError(f.string() + " does not exist");
  }
  for (const char* ext : {".png", ".svg"})
    require_regular_or_absent(out / (spec.name + ext));
  const auto doc = load_results(spec, out);
  const std::string subtitle = spec.study->figure_subtitle(spec, doc);
  const std::string dt = spec.study->figure_dt ? spec.study->figure_dt(doc) : "0";
  // 2. gnuplot, started without a shell, draws into a private staging folder (mode 0700, random
  // name): its variables come from a file of assignments (the values quoted as data), then the
  // script, both as arguments.
  const StagingFolder staging(out);
  const auto drawn = staging.path() / spec.name;
  const auto variables = staging.path() / "variables.gp";
  write_file_atomically(variables, plot_variables(data, drawn, subtitle, dt));
  const int status = run_program_visible({"gnuplot", variables.string(), script.string()});
  if (status != 0) {
    throw std::runtime_error("gnuplot failed (status " + std::to_string(status) + ") on " +
                             script.string());
  }
  // 3. Both figures are published together, each only if it changed.
  ReportBatch figures;
  for (const char* ext : {".png", ".svg"})
    write_if_changed(out / (spec.name + ext), read_input(drawn.string() + ext));
  figures.publish();
  return 0;
}

}  // namespace mpmstab::cli
