#include "performance.hpp"

#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "csv.hpp"
#include "report.hpp"
#include "report_util.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// Floating-point operations per particle-step of the step kernel, counted by hand from
// core/shape.hpp and core/phases.hpp (additions, multiplications and divisions; abs, negation,
// comparisons and conversions are not counted). The grid update is 5 flops per node (one a
// division), 99 nodes for 200 particles.
struct FlopCount {
  const char* method;
  double shape, p2g, grid, g2p, stress, body;
  double total() const { return shape + p2g + grid + g2p + stress + body; }
};
// uGIMP: shape functions 34 (14 multiplications, 20 additions), p2g contributions 19 and grid
// additions 9, g2p 16, stress update 11, body force 1.
const FlopCount kGimp{"gimp", 34, 28, 2.5, 16, 11, 1};
// Linear hat: shape functions 6, p2g contributions 14 and grid additions 6, g2p 12, stress 9.
const FlopCount kMpm{"mpm", 6, 20, 2.5, 12, 9, 1};

// Peak of one core in double precision: two FMA pipes; 256-bit ones give 16 flops per cycle,
// 512-bit ones 32. /proc/cpuinfo names the CPU only "AMD EPYC", so both are reported.
constexpr double kPeakNarrow = 16;
constexpr double kPeakWide = 32;

struct Figure {
  double median = 0, cv = 0;
};

}  // namespace

void write_performance(const std::vector<Spec>& specs, const fs::path& bench, const fs::path& out) {
  std::ostringstream md;
  md << "# Performance\n\nWhat a result costs: the step kernel measured with Google Benchmark "
        "(`make bench`, `tests/bench_step.cpp`), what each measured quantity adds to it, and the "
        "wall time of every experiment of `make reproduce`.\n\n";

  const std::string text = read_file(bench);
  if (text.empty()) {
    md << "*No benchmark figures: " << bench.generic_string() << " is missing (run `make bench`)."
       << "*\n\n";
  } else {
    const ojson doc = ojson::parse(text);
    // name ("BM_Step") -> method -> median and coefficient of variation
    std::map<std::string, std::map<std::string, Figure>> fig;
    std::vector<std::string> order;
    for (const auto& b : doc["benchmarks"]) {
      const std::string run = b.value("run_name", b.value("name", ""));
      const std::string base = run.substr(0, run.find('/'));
      const std::string method = b.value("label", "");
      const std::string agg = b.value("aggregate_name", "");
      if (agg != "median" && agg != "cv") continue;
      if (!b.contains("ns_per_particle_step")) continue;
      if (std::find(order.begin(), order.end(), base) == order.end()) order.push_back(base);
      auto& f = fig[base][method];
      if (agg == "median") f.median = b["ns_per_particle_step"].get<double>();
      if (agg == "cv") f.cv = b["ns_per_particle_step"].get<double>();
    }
    const ojson& ctx = doc["context"];
    const double mhz = ctx.value("mhz_per_cpu", 0.0);
    md << "## The step kernel\n\nThe paper's bar, 100 cells x 2 particles = 200 particles, one "
          "core, median of "
       << (fig.count("BM_Step") ? "the repetitions" : "–")
       << " (coefficient of variation in "
          "brackets). Measured "
       << ctx.value("date", "") << " on " << ctx.value("host_name", "") << ", "
       << ctx.value("num_cpus", 0) << " CPUs at " << mhz
       << " MHz, the benchmark "
          "library's own build "
       << ctx.value("library_build_type", "")
       << " (Debian's package; the measured code is built -O3).\n\n"
       << "| benchmark | what it runs | GIMP ns / particle-step | MPM ns / particle-step |\n"
          "|---|---|---|---|\n";
    const std::map<std::string, std::string> what = {
        {"BM_StepBaseline", "a straightforward loop-per-particle step (the starting point)"},
        {"BM_Step", "the four phases: p2g, grid update, g2p, stress update"},
        {"BM_StepChecked", "+ the failure check every run makes after each step"},
        {"BM_StepInstrumented", "+ every observer: error over time, eq. (108), crossings"},
        {"BM_StepError", "+ the check and the error-over-time observer"},
        {"BM_StepStableDt", "+ the check and the eq. (108) observer"},
        {"BM_StepCrossings", "+ the check and the crossings observer"}};
    auto cell = [&](const std::string& base, const char* m) {
      if (!fig[base].count(m)) return std::string("–");
      const Figure& f = fig[base][m];
      return fixed(f.median, 2) + " (" + fixed(100 * f.cv, 1) + "%)";
    };
    for (const auto& base : order) {
      md << "| " << base << " | " << (what.count(base) ? what.at(base) : "") << " | "
         << cell(base, "gimp") << " | " << cell(base, "mpm") << " |\n";
    }
    auto median = [&](const std::string& base, const char* m) {
      return fig.count(base) && fig[base].count(m) ? fig[base][m].median : 0.0;
    };
    md << "\n";
    for (const char* m : {"gimp", "mpm"}) {
      const double step = median("BM_Step", m), base = median("BM_StepBaseline", m);
      const double target = std::string(m) == "gimp" ? 5.0 : 4.0;
      md << "- " << m << ": " << fixed(step, 2) << " ns per particle-step, target " << target
         << " ns: **" << (step > 0 && step <= target ? "met" : "not met") << "**";
      if (base > 0) md << "; " << fixed(base / step, 1) << " times faster than the baseline";
      const double checked = median("BM_StepChecked", m);
      const double instrumented = median("BM_StepInstrumented", m);
      if (checked > 0 && instrumented > 0) {
        md << "; the failure check adds " << fixed(checked - step, 2)
           << " ns, the observers another " << fixed(instrumented - checked, 2) << " ns";
      }
      for (const auto& [name, label] :
           {std::pair{"BM_StepError", "error over time"}, std::pair{"BM_StepStableDt", "eq. (108)"},
            std::pair{"BM_StepCrossings", "crossings"}}) {
        const double with = median(name, m);
        if (with > 0 && checked > 0)
          md << "; " << label << " alone " << fixed(with - checked, 2) << " ns";
      }
      md << ".\n";
    }
    md << "\nDifferences below the coefficient of variation are within the noise.\n"
          "\n### Floating-point work and the fraction of peak\n\nCounted by hand from "
          "`core/shape.hpp` and `core/phases.hpp` (additions, multiplications and divisions; "
          "the grid update is per node, counted per particle at 99 nodes for 200 particles):\n\n"
          "| method | shape functions | p2g | grid update | g2p | stress update | body force | "
          "total | measured GFLOP/s | of a 16 / 32 flop-per-cycle peak |\n"
          "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const FlopCount& f : {kGimp, kMpm}) {
      const double ns = median("BM_Step", f.method);
      const double gflops = ns > 0 ? f.total() / ns : 0;
      const double narrow = mhz * 1e-3 * kPeakNarrow, wide = mhz * 1e-3 * kPeakWide;  // GFLOP/s
      md << "| " << f.method << " | " << shortest(f.shape) << " | " << shortest(f.p2g) << " | "
         << shortest(f.grid) << " | " << shortest(f.g2p) << " | " << shortest(f.stress) << " | "
         << shortest(f.body) << " | " << shortest(f.total()) << " | " << fixed(gflops, 1) << " | "
         << (narrow > 0
                 ? fixed(100 * gflops / narrow, 0) + "% / " + fixed(100 * gflops / wide, 0) + "%"
                 : "–")
         << " |\n";
    }
    md << "\nPeak at the benchmark's reported clock of " << mhz
       << " MHz (the cores run faster under load, about 3.6 GHz by a dependent-multiply timing "
          "loop, which lowers these fractions by about a quarter). What limits the step is not "
          "arithmetic: the additions into the grid must stay in particle order to keep the "
          "results bit for bit, and a core retires about one store per cycle.\n\n";
  }

  // Experiments.
  md << "## Wall time of every experiment\n\nThe sweep wall time is that of the last sweep "
        "that computed a case (cached reruns take milliseconds); compute time is the sum of the "
        "cases' own run times.\n\n| experiment | cases | compute time | sweep wall time |\n"
        "|---|---|---|---|\n";
  double total_wall = 0, total_compute = 0;
  for (const auto& spec : specs) {
    if (!spec.study->has_cases) continue;  // computed from other experiments' results
    const std::string t = read_file(out / (spec.name + ".json"));
    if (t.empty()) {
      md << "| " << spec.name << " | not run | | |\n";
      continue;
    }
    const ojson doc = ojson::parse(t);
    const double wall = doc["sweep"]["wall_seconds"].get<double>();
    const double compute = doc["sweep"]["compute_seconds"].get<double>();
    total_wall += wall;
    total_compute += compute;
    md << "| [" << spec.name << "](" << spec.name << ".md) | " << doc["cases"].size() << " | "
       << seconds(compute) << " | " << seconds(wall) << " |\n";
  }
  md << "| all | | " << seconds(total_compute) << " | " << seconds(total_wall) << " |\n\n"
     << "`make reproduce` prints its own wall time when it ends; with every case cached it takes "
        "about a second.\n";
  write_if_changed(out / "performance.md", md.str());
}

}  // namespace mpmstab
