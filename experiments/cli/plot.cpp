// `mpmstab plot`: a study's figure, drawn by gnuplot from its data.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "atomic_file.hpp"
#include "commands.hpp"
#include "csv.hpp"
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
  for (const auto& f : {script, data, summary}) {
    if (!std::filesystem::exists(f)) throw UsageError(f.string() + " does not exist");
  }
  const auto doc = load_results(spec, out);
  const std::string subtitle = spec.study->figure_subtitle(spec, doc);
  const std::string dt = spec.study->figure_dt ? spec.study->figure_dt(doc) : "0";
  // gnuplot is started without a shell: its variables come from a file of assignments (the
  // values quoted as data), then the script, both as arguments.
  const std::string stem = "." + spec.name + "." + std::to_string(::getpid());
  const auto tmp = out / (stem + ".tmp");
  const auto variables = out / (stem + ".vars.gp");
  write_file_atomically(variables, plot_variables(data, tmp, subtitle, dt));
  const int status = run_program_visible({"gnuplot", variables.string(), script.string()});
  std::filesystem::remove(variables);
  if (status != 0) {
    throw std::runtime_error("gnuplot failed (status " + std::to_string(status) + ") on " +
                             script.string());
  }
  for (const char* ext : {".png", ".svg"}) {
    std::filesystem::rename(tmp.string() + ext, out / (spec.name + ext));
  }
  return 0;
}

}  // namespace mpmstab::cli
