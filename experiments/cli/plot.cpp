// `mpmstab plot`: a study's figure, drawn by gnuplot from its data.
#include <unistd.h>

#include <cstdlib>

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
DIR/<name>_data.csv and writes DIR/<name>.png and DIR/<name>.svg atomically. The PNG's text is
drawn in DejaVu Sans (Debian's fonts-dejavu-core) whatever fonts and font settings the machine
has: gnuplot sees only that font, through a fontconfig configuration of its own.
)";

// The one font the PNG figures are drawn with (fonts-dejavu-core, in the Makefile's
// DEB_PACKAGES): the regular face every script names ("DejaVu Sans") and its bold face.
constexpr const char* kFontFolder = "/usr/share/fonts/truetype/dejavu";
constexpr const char* kFontFiles[] = {"DejaVuSans.ttf", "DejaVuSans-Bold.ttf"};

// gnuplot's pngcairo terminal lays out and draws text with pango, which asks fontconfig for a
// font by name ("DejaVu Sans", but also "sans", "Arial" or "") and for how to render it. With
// the machine's configuration (/etc/fonts, ~/.config/fontconfig, FONTCONFIG_FILE) the answer
// depends on the fonts installed (fonts-liberation makes "Arial" Liberation Sans; another
// package or a user's rule can make "sans" anything) and on its hinting, antialiasing and
// subpixel settings (dpkg-reconfigure fontconfig-config). This configuration replaces all of
// it: one font folder, of which only the pinned files are accepted (fonts-dejavu-extra installs
// more DejaVu Sans faces into the same folder), every family resolved to DejaVu Sans, and the
// rendering options fixed (Debian's defaults: slight hinting, greyscale antialiasing). No cache
// folder: the few files are scanned at each start, so no stale or foreign cache is read.
std::string font_configuration() {
  const std::string folder = kFontFolder;
  std::string accepted;
  for (const char* file : kFontFiles)
    accepted += "      <glob>" + folder + "/" + file + "</glob>\n";
  return "<?xml version=\"1.0\"?>\n"
         "<!DOCTYPE fontconfig SYSTEM \"urn:fontconfig:fonts.dtd\">\n"
         "<!-- Written by mpmstab plot for gnuplot: the only font its figures see, and how it is "
         "drawn. -->\n"
         "<fontconfig>\n"
         "  <dir>" +
         folder +
         "</dir>\n"
         "  <selectfont>\n"
         "    <acceptfont>\n" +
         accepted +
         "    </acceptfont>\n"
         "    <rejectfont>\n"
         "      <glob>*</glob>\n"
         "    </rejectfont>\n"
         "  </selectfont>\n"
         "  <match target=\"pattern\">\n"
         "    <edit name=\"family\" mode=\"assign\" binding=\"strong\">"
         "<string>DejaVu Sans</string></edit>\n"
         "  </match>\n"
         "  <match target=\"font\">\n"
         "    <edit name=\"antialias\" mode=\"assign\"><bool>true</bool></edit>\n"
         "    <edit name=\"hinting\" mode=\"assign\"><bool>true</bool></edit>\n"
         "    <edit name=\"hintstyle\" mode=\"assign\"><const>hintslight</const></edit>\n"
         "    <edit name=\"autohint\" mode=\"assign\"><bool>false</bool></edit>\n"
         "    <edit name=\"rgba\" mode=\"assign\"><const>none</const></edit>\n"
         "    <edit name=\"lcdfilter\" mode=\"assign\"><const>lcdnone</const></edit>\n"
         "    <edit name=\"embeddedbitmap\" mode=\"assign\"><bool>false</bool></edit>\n"
         "    <edit name=\"embolden\" mode=\"assign\"><bool>false</bool></edit>\n"
         "  </match>\n"
         "</fontconfig>\n";
}

// Runs gnuplot on `scripts` (no shell: an argument vector and an environment of our own), its
// output to our standard error; its exit status, or -1 when it did not start or exit normally.
// `-d` skips its start-up files (the system gnuplotrc and ~/.gnuplot, which may set colours or
// fonts); the environment holds only PATH (to find gnuplot's helpers, if any), HOME (the
// staging folder, so nothing of the user's is read), a fixed locale and FONTCONFIG_FILE (the
// configuration above): nothing else of the machine's environment reaches the drawing.
int run_gnuplot(const std::filesystem::path& staging, const std::vector<std::string>& scripts) {
  // Absolute: fontconfig reads a relative FONTCONFIG_FILE from its own folder, not from ours.
  const auto folder = std::filesystem::absolute(staging);
  const auto config = folder / "fonts.conf";
  write_file_atomically(config, font_configuration());
  std::vector<std::string> env = {"HOME=" + folder.string(), "LC_ALL=C.UTF-8",
                                  "FONTCONFIG_FILE=" + config.string()};
  if (const char* path = std::getenv("PATH")) env.push_back(std::string("PATH=") + path);
  std::vector<std::string> argv = {"gnuplot", "-d"};
  argv.insert(argv.end(), scripts.begin(), scripts.end());
  return run_program_visible(argv, env);
}

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
  for (const char* file : kFontFiles) {
    const std::filesystem::path font = std::filesystem::path(kFontFolder) / file;
    if (!std::filesystem::is_regular_file(font)) {
      throw std::runtime_error("the figures' font " + font.string() +
                               " is missing: install fonts-dejavu-core (make deps)");
    }
  }
  const auto doc = load_results(spec, out);
  const std::string subtitle = spec.study->figure_subtitle(spec, doc);
  const std::string dt = spec.study->figure_dt ? spec.study->figure_dt(doc) : "0";
  // 2. gnuplot, started without a shell, draws into a private staging folder (mode 0700, random
  // name): its variables come from a file of assignments (the values quoted as data), then the
  // script, both as arguments; it sees only the pinned font (run_gnuplot).
  const StagingFolder staging(out);
  const auto drawn = staging.path() / spec.name;
  const auto variables = staging.path() / "variables.gp";
  write_file_atomically(variables, plot_variables(data, drawn, subtitle, dt));
  const int status = run_gnuplot(staging.path(), {variables.string(), script.string()});
  if (status != 0) {
    throw std::runtime_error("gnuplot failed (status " + std::to_string(status) + ") on " +
                             script.string());
  }
  // 3. Both figures are published together, each only if it changed. One that did not change
  // is marked drawn (its time set to now, its bytes untouched), so that make's rule, which
  // compares times with its data and scripts, does not draw it again at every run.
  ReportBatch figures;
  for (const char* ext : {".png", ".svg"})
    write_if_changed(out / (spec.name + ext), read_input(drawn.string() + ext));
  figures.publish();
  for (const char* ext : {".png", ".svg"}) {
    std::error_code ec;
    std::filesystem::last_write_time(out / (spec.name + ext),
                                     std::filesystem::file_time_type::clock::now(), ec);
  }
  return 0;
}

}  // namespace mpmstab::cli
