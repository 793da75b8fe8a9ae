#include "performance.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <sstream>

#include "cache.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "strict_json.hpp"
#include "sweep.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// Floating-point operations per particle-step of the step kernel, counted by hand from
// core/step/shape.hpp and core/step/phases.hpp (additions, multiplications and divisions; abs,
// negation, comparisons and conversions are not counted). The grid update is 5 flops per node (one
// a division), 99 nodes for 200 particles.
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
// The other bases' target: a step within this factor of GIMP's.
constexpr double kOtherBasisTarget = 1.6;

struct Figure {
  double median = 0, cv = 0;
};

// The benchmark's figures: name ("BM_Step") -> method -> median and coefficient of variation,
// with the names in the order the benchmark ran them.
struct BenchFigures {
  std::map<std::string, std::map<std::string, Figure>> fig;
  std::vector<std::string> order;
  std::string machine;  // machine_of its context: the CPU and the kernels' version

  const Figure* find(const std::string& base, const std::string& method) const {
    const auto b = fig.find(base);
    if (b == fig.end()) return nullptr;
    const auto m = b->second.find(method);
    return m == b->second.end() ? nullptr : &m->second;
  }
  // 0 when the benchmark did not run.
  double median(const std::string& base, const std::string& method) const {
    const Figure* f = find(base, method);
    return f ? f->median : 0.0;
  }
};

BenchFigures read_figures(const ojson& doc) {
  BenchFigures b;
  if (doc.contains("context")) b.machine = machine_of(doc["context"]);
  for (const auto& entry : doc["benchmarks"]) {
    const std::string run = entry.value("run_name", entry.value("name", ""));
    const std::string base = run.substr(0, run.find('/'));
    const std::string method = entry.value("label", "");
    const std::string agg = entry.value("aggregate_name", "");
    if (agg != "median" && agg != "cv") continue;
    if (!entry.contains("ns_per_particle_step")) continue;
    if (std::find(b.order.begin(), b.order.end(), base) == b.order.end()) b.order.push_back(base);
    auto& f = b.fig[base][method];
    if (agg == "median") f.median = entry["ns_per_particle_step"].get<double>();
    if (agg == "cv") f.cv = entry["ns_per_particle_step"].get<double>();
  }
  return b;
}

// When, on what and of which code a benchmark file was measured, from its context: "<date> on
// <CPU>, <version> kernels (<host>, <n> CPUs at <f> MHz), commit <c>". Files written before the
// benchmark recorded its CPU, kernels and commit (tests/bench_step.cpp) say so.
std::string bench_machine(const ojson& ctx) {
  const std::string commit = text(ctx, "commit");
  std::ostringstream s;
  s << ctx.value("date", "") << " on " << machine_of(ctx) << " (" << ctx.value("host_name", "")
    << ", " << ctx.value("num_cpus", 0) << " CPUs at " << ctx.value("mhz_per_cpu", 0.0)
    << " MHz), commit " << (commit.empty() ? std::string("not recorded") : commit.substr(0, 7));
  if (text(ctx, "dirty") == "true") s << " with uncommitted changes";
  return s.str();
}

// The table of every benchmark, with the machine it ran on.
void write_kernel_table(std::ostream& md, const BenchFigures& b, const ojson& ctx) {
  const RunParams bar;  // the benchmark's bar: the default parameters (tests/bench_step.cpp)
  md << "## The step kernel\n\nThe paper's bar, " << bar.cells << " cells x " << bar.ppc
     << " particles = " << bar.cells * bar.ppc
     << " particles, one "
        "core, median of "
     << (b.fig.count("BM_Step") ? "the repetitions" : "–")
     << " (coefficient of variation in "
        "brackets). Measured "
     << bench_machine(ctx)
     << ", the benchmark "
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
    const Figure* f = b.find(base, m);
    if (!f) return std::string("–");
    return fixed(f->median, 2) + " (" + fixed(100 * f->cv, 1) + "%)";
  };
  for (const auto& base : b.order) {
    if (!b.find(base, "gimp") && !b.find(base, "mpm")) continue;
    md << "| " << base << " | " << (what.count(base) ? what.at(base) : "") << " | "
       << cell(base, "gimp") << " | " << cell(base, "mpm") << " |\n";
  }
  // The other bases (BM_StepNewBases: the four phases as BM_Step), against GIMP's BM_Step.
  std::ostringstream others;
  const double gimp = b.median("BM_Step", "gimp");
  if (b.fig.count("BM_StepNewBases")) {
    for (const auto& [method, f] : b.fig.at("BM_StepNewBases")) {
      others << "| " << method << " | BM_StepNewBases | " << fixed(f.median, 2) << " ("
             << fixed(100 * f.cv, 1) << "%) | "
             << (gimp > 0 ? fixed(f.median / gimp, 2) + "x (target " + shortest(kOtherBasisTarget) +
                                "x: " +
                                (f.median <= kOtherBasisTarget * gimp ? "met" : "**not met**") + ")"
                          : std::string("–"))
             << " |\n";
    }
  }
  if (!others.str().empty()) {
    md << "\nThe other bases, the same four phases:\n\n"
          "| basis | benchmark | ns / particle-step | against GIMP's BM_Step |\n|---|---|---|---|\n"
       << others.str();
  }
  // A whole run with its observers (BM_RunObservers: run(), GIMP, 1000 steps), by observers.
  if (b.fig.count("BM_RunObservers")) {
    md << "\nA whole run of the bar (`run()`, GIMP, as BM_RunObservers runs it) with the "
          "observers it is asked for:\n\n"
          "| observers | ns / particle-step | against GIMP's BM_StepInstrumented "
          "|\n|---|---|---|\n";
    const double instrumented = b.median("BM_StepInstrumented", "gimp");
    for (const auto& [observers, f] : b.fig.at("BM_RunObservers")) {
      md << "| " << observers << " | " << fixed(f.median, 2) << " (" << fixed(100 * f.cv, 1)
         << "%) | "
         << (instrumented > 0 ? fixed(f.median / instrumented, 2) + "x" : std::string("–"))
         << " |\n";
    }
  }
  // GIMP under the other update orders and transfers (BM_StepScheme: the whole step of each),
  // by name.
  if (b.fig.count("BM_StepScheme")) {
    md << "\nGIMP under the other update orders and transfers (update / transfer; USL with FLIP is "
          "BM_Step's gimp):\n\n| update / transfer | ns / particle-step | against GIMP's BM_Step "
          "|\n|---|---|---|\n";
    for (const auto& [scheme, f] : b.fig.at("BM_StepScheme")) {
      md << "| " << scheme << " | " << fixed(f.median, 2) << " (" << fixed(100 * f.cv, 1) << "%) | "
         << (gimp > 0 ? fixed(f.median / gimp, 2) + "x" : std::string("–")) << " |\n";
    }
  }
}

// Per method: the step against its target and the baseline, and what the check and each
// observer add to it.
void write_kernel_summary(std::ostream& md, const BenchFigures& b) {
  md << "\n";
  for (const char* m : {"gimp", "mpm"}) {
    const double step = b.median("BM_Step", m), base = b.median("BM_StepBaseline", m);
    const double checked = b.median("BM_StepChecked", m);
    const double instrumented = b.median("BM_StepInstrumented", m);
    // The targets: bare step and step with every observer (GIMP 2.5 / 3.0 ns, MPM 2.0 / 2.5).
    const bool gimp = std::string(m) == "gimp";
    const double bare_target = gimp ? 2.5 : 2.0, observed_target = gimp ? 3.0 : 2.5;
    auto verdict = [](double v, double target) {
      return std::string(v > 0 && v <= target ? "met" : "not met");
    };
    md << "- " << m << ": " << fixed(step, 2) << " ns per particle-step bare (target "
       << fixed(bare_target, 1) << " ns: **" << verdict(step, bare_target) << "**), "
       << fixed(instrumented, 2) << " ns with every observer (target " << fixed(observed_target, 1)
       << " ns: **" << verdict(instrumented, observed_target) << "**)";
    if (base > 0) md << "; " << fixed(base / step, 1) << " times faster than the baseline";
    // A difference of two medians that comes out negative is no speed-up (the benchmark with
    // the check does more work): no cost can be read from it, and it is printed as such.
    auto cost = [](double d) {
      return d > 0 ? fixed(d, 2) + " ns"
                   : "no cost that can be read (" + fixed(d, 2) +
                         " ns: the benchmark doing more "
                         "work ran faster)";
    };
    if (checked > 0 && instrumented > 0) {
      md << "; the failure check adds " << cost(checked - step) << ", the observers together "
         << cost(instrumented - checked);
    }
    for (const auto& [name, label] :
         {std::pair{"BM_StepError", "error over time"}, std::pair{"BM_StepStableDt", "eq. (108)"},
          std::pair{"BM_StepCrossings", "crossings"}}) {
      const double with = b.median(name, m);
      if (with > 0 && checked > 0) md << "; " << label << " alone " << cost(with - checked);
    }
    md << ".\n";
  }
  md << "\nEach cost is a difference of two medians, each observer's measured in a benchmark "
        "of its own: they need not add up to the cost of all together. Differences below the "
        "coefficient of variation are within the noise; a negative one shows two benchmarks "
        "whose medians drift apart by more than their repetitions vary, so that the other "
        "differences of the same list are uncertain by as much.\n";
}

// The hand-counted flops per particle-step and the fraction of the core's peak they reach.
void write_flops(std::ostream& md, const BenchFigures& b, double mhz) {
  const RunParams bar;
  md << "\n### Floating-point work and the fraction of peak\n\nCounted by hand from "
        "`core/step/shape.hpp` and `core/step/phases.hpp` (additions, multiplications and "
        "divisions; "
        "the grid update is per node, counted per particle at "
     << bar.cells - 1 << " interior nodes for " << bar.cells * bar.ppc
     << " particles):\n\n"
        "| method | shape functions | p2g | grid update | g2p | stress update | body force | "
        "total | measured GFLOP/s | of a "
     << shortest(kPeakNarrow) << " / " << shortest(kPeakWide)
     << " flop-per-cycle peak |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const FlopCount& f : {kGimp, kMpm}) {
    const double ns = b.median("BM_Step", f.method);
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
     << " MHz (a core that runs faster under load than this reported clock reaches a smaller "
        "fraction of its peak than these). What limits the step is not "
        "arithmetic: the additions into the grid must stay in particle order to keep the "
        "results bit for bit, and a core retires about one store per cycle.\n\n";
}

// The benchmark's sections, or a note that its output is missing.
// The benchmark's figures, none when the file is missing.
BenchFigures bench_figures(const fs::path& bench) {
  const std::string text = read_if_present(bench).value_or("");
  if (text.empty()) return {};
  return read_figures(parse_json_strict<ojson>(text, bench));
}

void write_benchmark(std::ostream& md, const fs::path& bench) {
  const std::string text = read_if_present(bench).value_or("");
  if (text.empty()) {
    md << "*No benchmark figures: " << bench.generic_string() << " is missing (run `make bench`)."
       << "*\n\n";
    return;
  }
  const ojson doc = parse_json_strict<ojson>(text, bench);
  const BenchFigures figures = read_figures(doc);
  const ojson& ctx = doc["context"];
  write_kernel_table(md, figures, ctx);
  write_kernel_summary(md, figures);
  write_flops(md, figures, ctx.value("mhz_per_cpu", 0.0));
}

// The work, CPU time and wall time of every experiment that runs cases, and of the whole
// reproduction, from <out>/timings.json, against what the kernel's speed allows.
// results/timings.json as an object (an empty object when it is absent or unreadable).
ojson read_timings(const fs::path& out) {
  ojson timings = ojson::object();
  if (const auto t = read_if_present(out / "timings.json"); t && !t->empty()) {
    try {
      timings = parse_json_strict<ojson>(*t, out / "timings.json");
    } catch (const InputError&) {
    }
    if (!timings.is_object()) timings = ojson::object();
  }
  return timings;
}

// The follow-up runs of every experiment with cases, by name.
using FollowUps = std::map<std::string, FollowUpWork>;

// The follow-up runs column: how many, and how many of them the cache lacks.
std::string follow_up_cell(const FollowUpWork& f) {
  if (f.runs == 0) return "–";
  std::string s = std::to_string(f.runs);
  if (f.cached < f.runs) s += " (" + std::to_string(f.runs - f.cached) + " not in the cache)";
  return s;
}

// FollowUpWork as timings.json records it beside an experiment's cases, and back (all zero
// where the entry has none: measured before follow-up runs were recorded, or none asked for).
ojson to_json(const FollowUpWork& f) {
  return {{"runs", f.runs},
          {"in_cache", f.cached},
          {"particle_steps", f.particle_steps},
          {"cpu_seconds", f.seconds},
          {"ns_per_particle_step", f.ns_per_particle_step}};
}

FollowUpWork follow_up_of(const ojson& entry) {
  FollowUpWork f;
  if (!entry.contains("follow_up") || !entry["follow_up"].is_object()) return f;
  const ojson& j = entry["follow_up"];
  const auto count = [&](const char* key) {
    return static_cast<std::size_t>(std::llround(number_or_zero(j, key)));
  };
  f.runs = count("runs");
  f.cached = count("in_cache");
  f.particle_steps = number_or_zero(j, "particle_steps");
  f.seconds = number_or_zero(j, "cpu_seconds");
  if (j.contains("ns_per_particle_step") && j["ns_per_particle_step"].is_array())
    for (const auto& ns : j["ns_per_particle_step"])
      if (ns.is_number()) f.ns_per_particle_step.push_back(ns.get<double>());
  return f;
}

// One row per experiment with cases: its work and CPU time with its follow-up runs', its wall
// time and median ns per particle-step; then the total.
void experiment_rows(std::ostream& md, const std::vector<Spec>& specs, const ojson& timings,
                     const FollowUps& follow) {
  double total_compute = 0, total_work = 0;
  for (const auto& spec : specs) {
    if (!spec.study->has_cases) continue;  // computed from other experiments' results
    if (!timings.contains(spec.name)) {
      md << "| " << spec.name << " | not run | | | | | |\n";
      continue;
    }
    const ojson& e = timings[spec.name];
    const FollowUpWork& f = follow.at(spec.name);
    const ReportRuns own = report_runs_of(e);
    const double wall = e["sweep_wall_seconds"].get<double>();
    const double compute = e["compute_seconds"].get<double>() + f.seconds + own.seconds;
    const double work = (e.contains("particle_steps") ? e["particle_steps"].get<double>() : 0.0) +
                        f.particle_steps + own.particle_steps;
    std::vector<double> ns = f.ns_per_particle_step;
    for (const auto& c : e["per_case"]) {
      if (c["ns_per_particle_step"].is_number()) ns.push_back(c["ns_per_particle_step"]);
    }
    total_compute += compute;
    total_work += work;
    md << "| [" << spec.name << "](" << spec.name << ".md) | " << e["cases"].dump() << " | "
       << follow_up_cell(f) << " | " << (own.runs ? std::to_string(own.runs) : std::string("–"))
       << " | " << sci(work) << " | " << seconds(compute) << " | " << seconds(wall) << " | "
       << (ns.empty() ? std::string("-") : fixed(quantile(ns, 0.5), 1)) << " |\n";
  }
  md << "| all | | | | " << sci(total_work) << " | " << seconds(total_compute) << " | | "
     << (total_work > 0 ? fixed(1e9 * total_compute / total_work, 1) : std::string("-"))
     << " (mean) |\n\n";
}

// The groups of cases of one experiment and one time step with the most CPU time: where the
// time goes, finer than by experiment. A case's CPU time is its run's, or its share of a run it
// shares; an experiment's follow-up runs found in the cache are a group of their own. An
// experiment whose timings do not match its spec case for case (the spec changed since they were
// measured) is left out, and said so.
void costliest_groups(std::ostream& md, const std::vector<Spec>& specs, const ojson& timings,
                      const FollowUps& follow) {
  struct Group {
    std::string experiment, step;
    std::size_t cases = 0;
    double seconds = 0;
  };
  static const std::string kFollowUpGroup = "follow-up runs";
  static const std::string kReportGroup = "runs of its report";
  std::vector<Group> groups;
  std::vector<std::string> stale;
  double total = 0;
  for (const auto& spec : specs) {
    if (!spec.study->has_cases || !timings.contains(spec.name)) continue;
    const ojson& per_case = timings[spec.name]["per_case"];
    bool matches = per_case.is_array() && per_case.size() == spec.cases.size();
    std::map<std::string, Group> by_step;
    for (std::size_t i = 0; matches && i < spec.cases.size(); ++i) {
      const RunParams& p = spec.cases[i].params;
      const ojson& c = per_case[i];
      matches = c.is_object() && c.contains("key") && c["key"] == case_key(p) &&
                c.contains("wall_seconds") && c["wall_seconds"].is_number();
      if (!matches) break;
      const std::string step = spec.study->work == CaseWork::edge_search ? "edge searches"
                               : p.stepping.policy == TimeStepPolicy::fixed
                                   ? "dt = " + param(p.dt)
                                   : std::string(to_string(p.stepping.policy)) + " steps";
      Group& g = by_step[step];
      g.experiment = spec.name;
      g.step = step;
      ++g.cases;
      g.seconds += c["wall_seconds"].get<double>();
    }
    if (!matches) {
      stale.push_back(spec.name);
      continue;
    }
    if (const FollowUpWork& f = follow.at(spec.name); f.cached > 0) {
      by_step[kFollowUpGroup] = Group{spec.name, kFollowUpGroup, f.cached, f.seconds};
    }
    if (const ReportRuns own = report_runs_of(timings[spec.name]); own.runs > 0) {
      by_step[kReportGroup] = Group{spec.name, kReportGroup, own.runs, own.seconds};
    }
    for (auto& [step, g] : by_step) {
      total += g.seconds;
      groups.push_back(std::move(g));
    }
  }
  if (groups.empty() || total <= 0) return;
  std::stable_sort(groups.begin(), groups.end(),
                   [](const Group& a, const Group& b) { return a.seconds > b.seconds; });
  constexpr std::size_t kShown = 8;
  groups.resize(std::min(groups.size(), kShown));
  md << "Where the CPU time goes, by experiment and time step: the " << groups.size()
     << " groups of cases with the most (of " << seconds(total) << " in all";
  if (!stale.empty()) {
    md << "; left out, their timings measured on other cases than their spec's:";
    for (const auto& name : stale)
      md << " " << name;
  }
  md << ").\n\n| experiment | time step | cases | CPU time | of all |\n|---|---|---|---|---|\n";
  double shown = 0;
  for (const auto& g : groups) {
    shown += g.seconds;
    md << "| " << g.experiment << " | " << g.step << " | " << g.cases << " | " << seconds(g.seconds)
       << " | " << fixed(100 * g.seconds / total, 0) << "% |\n";
  }
  md << "| these " << groups.size() << " | | | " << seconds(shown) << " | "
     << fixed(100 * shown / total, 0) << "% |\n\n";
}

// How the progress line's time to go compared with the truth in a tier's run.
void time_to_go_text(std::ostream& md, const ojson& t) {
  md << " The time to go its progress line showed, from " << fixed(100 * EstimateAccuracy::kSkip, 0)
     << "% of the wall until the last " << fixed(100 * EstimateAccuracy::kTail, 0) << "% ("
     << t["samples"].dump() << " estimates, one a second at most), was within a factor "
     << fixed(t["worst_factor"].get<double>(), 2) << " of the true time to go";
  std::string sep = " (";
  for (const auto& p : t["at"]) {
    md << sep << fixed(100 * p[0].get<double>(), 0) << "%: " << seconds(p[1].get<double>())
       << " shown, " << seconds(p[2].get<double>()) << " true";
    sep = "; ";
  }
  md << (sep == "; " ? ")" : "") << ".";
}

// The command of a timing label, without the machine another machine's run is kept under
// ("make studies on X" -> "make studies").
std::string command_of(const std::string& label) {
  return label.substr(0, label.find(" on "));
}

// The paragraph of one tier's last run ("(make reproduce)" in timings.json).
void tier_paragraph(std::ostream& md, const std::string& label, const ojson& r,
                    const BenchFigures& bench) {
  // A field the entry lacks (written before it was recorded, or edited) reads as 0.
  auto number = [&](const char* key) { return number_or_zero(r, key); };
  auto count = [&](const char* key) { return std::to_string(std::llround(number(key))); };
  const double wall = number("wall_seconds");
  const int threads = std::max(1, static_cast<int>(number("threads")));
  const double cpu = number("compute_seconds");  // each distinct case once
  const double work = number("particle_steps");
  // The kernel's speed says what the tier's work would take only on the machine it was
  // benchmarked on.
  const double kernel =
      bench.machine == machine_of(r) ? bench.median("BM_StepInstrumented", "gimp") : 0.0;
  md << "**`" << label << "`.** The last run that computed cases ran " << count("cases")
     << " cases (" << count("computed") << " computed; " << sci(work)
     << " particle-steps, each run counted once, ";
  if (const ReportRuns reports = report_runs_of(r); reports.recorded) {
    md << "follow-up runs and the " << reports.runs << " runs its reports made themselves included";
  } else {  // recorded before those runs were counted in the tier
    md << "follow-up runs included, the runs its reports made themselves not: those are in the "
          "table above";
  }
  md << ") of " << count("experiments") << " experiments on " << threads << " threads ("
     << machine_of(r) << ") in **" << seconds(wall) << "** wall.";
  if (cpu > 0) {
    md << " Their CPU time, " << seconds(cpu) << ", on " << threads
       << " threads kept fully busy would take " << seconds(cpu / threads)
       << (wall > 0 ? " (" + fixed(100 * cpu / threads / wall, 0) + "% of the wall)"
                    : std::string(""));
  }
  if (kernel > 0) {
    md << "; at the step kernel's speed with every observer as benchmarked above on the same "
          "machine (BM_StepInstrumented, GIMP, "
       << fixed(kernel, 2) << " ns per particle-step), it would take "
       << seconds(work * kernel * 1e-9 / threads);
  }
  md << ".";
  if (r.contains("time_to_go") && r["time_to_go"].is_object()) time_to_go_text(md, r["time_to_go"]);
  md << "\n\n";
}

// The paragraph of the last fresh build of the tool ("(make)" in timings.json, mpmstab
// build-time).
void build_paragraph(std::ostream& md, const std::string& label, const ojson& r) {
  md << "**`" << label << "`.** The last fresh build of the tool (from configuring a new build "
     << "folder to the linked tool, the installation of Debian packages excluded) took **"
     << seconds(number_or_zero(r, "wall_seconds")) << "** wall with "
     << (has_number(r, "threads") ? r["threads"].dump() : std::string("an unrecorded number of"))
     << " compile jobs (" << machine_of(r) << ").\n\n";
}

void write_experiment_times(std::ostream& md, const std::vector<Spec>& specs, const fs::path& out,
                            const BenchFigures& bench) {
  md << "## The cost of every experiment\n\nFrom [timings.json](timings.json), the machine's "
        "measurements of the cases and of their follow-up runs, the latter read from the records "
        "in its cache when its timings were published (every other result file is the same on "
        "any machine). "
        "Particle-steps (particles x steps, of every run of an edge search) are the "
        "deterministic work; CPU time is the sum of the runs' own run times. Both, and the median "
        "ns per particle-step, count the experiment's cases and its follow-up runs: the runs its "
        "study asks for once its cases "
        "are done (an ensemble's members, an edge's longer runs, the verifying runs of the "
        "advice), as the experiment's published results ask for them and as that cache "
        "(cache/ beside timings.json, not committed) held their records; a follow-up run the "
        "cache lacked is "
        "counted in the follow-up runs column and said so, but adds no work. The runs of its "
        "report are those its report computed itself while it was written (the advice sample's "
        "searches, whose runs follow from the runs before them), counted by the writing of the "
        "report that computed them and not again when it is written from the cache; their work "
        "and CPU time are in the row's. Cases that differ "
        "only in eq. (108)'s options, at a policy that does not step by eq. (108), share one run "
        "(its trajectory is theirs): each counts its share of that run's particle-steps and "
        "time. Wall time is the "
        "span from the experiment's first case's start to its last case's end in the run that "
        "computed them, its follow-up runs not included (`make reproduce` runs every "
        "experiment's cases in one queue, so the spans overlap).";
  const ojson timings = read_timings(out);
  // The machines that measured the table's cases (timings.json records each experiment's).
  std::set<std::string> machines;
  for (const auto& spec : specs)
    if (spec.study->has_cases && timings.contains(spec.name))
      machines.insert(machine_of(timings[spec.name]));
  if (!machines.empty()) {
    md << " The times below were measured on ";
    for (auto it = machines.begin(); it != machines.end(); ++it)
      md << (it == machines.begin() ? "" : std::next(it) == machines.end() ? " and " : ", ") << *it;
    md << (machines.size() > 1 ? " (each experiment's in timings.json)" : "")
       << "; the kernel benchmark above in a run of its own (its date, host and clock given "
          "there).";
  }
  md << "\n\n| experiment | cases | follow-up runs | runs of its report | particle-steps | CPU "
        "time | wall time | median ns per particle-step |\n|---|---|---|---|---|---|---|---|\n";
  FollowUps follow;
  for (const auto& spec : specs)
    if (spec.study->has_cases)
      follow[spec.name] =
          timings.contains(spec.name) ? follow_up_of(timings[spec.name]) : FollowUpWork{};
  experiment_rows(md, specs, timings, follow);
  costliest_groups(md, specs, timings, follow);
  bool any = false;
  for (const auto& [key, r] : timings.items()) {
    const auto label = timing_label(key);
    if (!label) continue;
    any = true;
    if (command_of(*label) == "make") {
      build_paragraph(md, *label, r);
    } else {
      tier_paragraph(md, *label, r, bench);
    }
  }
  if (any) {
    md << "The table's CPU times and particle-steps count a run shared by two experiments (a "
          "case or a follow-up run) in each.\n";
  } else {
    md << "`make reproduce` and `make studies` print their own wall time when they end and "
          "record it in timings.json.\n";
  }
}

// One row of the tier runs as a Slurm job array (cluster_timings.json, mpmstab cluster-time). A
// row recorded before the follow-up runs had an array of their own has no follow-up column.
void cluster_row(std::ostream& md, const ojson& r) {
  auto number = [&](const char* key) { return number_or_zero(r, key); };
  auto count = [&](const char* key) { return std::to_string(std::llround(number(key))); };
  const bool follow = r.contains("follow_seconds");
  const double array = number("array_records"), follow_records = number("follow_records"),
               render = number("render_records");
  const double all = array + follow_records + render;
  md << "| " << text(r, "tier") << " | " << count("nodes") << " x " << count("cpus_per_node")
     << " | " << count("tasks_at_once") << " | " << count("shards") << " | "
     << seconds(number("array_seconds")) << " | "
     << (follow ? seconds(number("follow_seconds")) : std::string("–")) << " | "
     << seconds(number("render_seconds")) << " | **" << seconds(number("wall_seconds")) << "** | "
     << count("array_records") << " / " << (follow ? count("follow_records") : std::string("–"))
     << " / " << count("render_records") << " (" << fixed(all > 0 ? 100 * render / all : 0.0, 0)
     << "% in the render) | " << machine_of(r) << " | " << text(r, "commit").substr(0, 7) << " |\n";
}

// The tier runs as a Slurm job array on the throwaway cluster (make studies-cluster), from
// <out>/cluster_timings.json; nothing when it is absent.
void write_cluster_times(std::ostream& md, const fs::path& out) {
  const auto text_of = read_if_present(out / "cluster_timings.json");
  if (!text_of) return;
  const ojson all = parse_json_strict<ojson>(*text_of, out / "cluster_timings.json");
  md << "\n## A tier as a Slurm job array\n\nFrom [cluster_timings.json](cluster_timings.json), "
        "which `make studies-cluster NODES=n` and `make reproduce-cluster NODES=n` "
        "(tests/cluster/tier_cluster.sh) write only after "
        "the tier it ran came out byte for byte as committed: the whole tier as one Slurm job "
        "array over all its cases (`mpmstab slurm --tier`, each case in the shard of its key), "
        "from an empty cache; then a second array over the follow-up runs that those records "
        "decide (those of every study that reads no other experiment's results, each run in the "
        "shard of its key); then one job that gathers both arrays' records and renders the tier "
        "(`make tier`), computing what remains (the follow-up runs of the studies that read "
        "other experiments, the searches of the advice sample). The cluster is a throwaway one "
        "on the machine named: its nodes are slurmd daemons sharing that machine's CPUs, so two "
        "nodes of one CPU have the CPUs one node of two has, and tasks at once bounds the array "
        "tasks that run together (each array's throttle). Cases: from submission to the last "
        "task's end of the first array; follow-ups: from then to the last task's end of the "
        "second (– where the run had no second array: its render computed every follow-up "
        "run); render: from then to the render job's end; total: all three. Records: the runs "
        "computed in each.\n\n"
        "| tier | nodes x CPUs | tasks at once | shards | cases | follow-ups | render | total "
        "wall | records computed: cases / follow-ups / render | machine | commit |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  if (all.is_object())
    for (const auto& [key, r] : all.items())
      if (r.is_object()) cluster_row(md, r);
}

// How many cases a tier run computed (0 where it did not record it).
double computed_cases(const ojson& e) {
  return e.contains("computed") && e["computed"].is_number() ? e["computed"].get<double>() : 0.0;
}

// This machine's timings (the cache's) with the tier runs of other machines that the published
// file holds: a tier run of this machine replaces the published one of the same CPU unless it
// computed fewer cases (a run that found most of its cases in the cache does not measure the
// tier); one of another CPU is kept as "(<label> on <cpu>)", so that the published file keeps
// the last tier run of each machine (README's table shows them all).
ojson merged_timings(const ojson& measured, const ojson& published) {
  ojson out = ojson::object();
  // A tier run that computed no case (every one from the cache) measured nothing: not published.
  for (const auto& [key, e] : measured.items())
    if (!timing_label(key) || !e.is_object() || !e.contains("computed") || computed_cases(e) > 0)
      out[key] = e;
  for (const auto& [key, e] : published.items()) {
    const auto published_label = timing_label(key);
    if (!published_label || !e.is_object()) continue;
    if (!e.contains("cpu") || !e["cpu"].is_string()) continue;
    if (e.contains("computed") && computed_cases(e) == 0) continue;  // measured nothing
    // A machine is its CPU and the kernels' version it ran: /proc/cpuinfo names an AVX2-only
    // EPYC and one with AVX-512 alike.
    const std::string machine = machine_of(e);
    const std::string label = command_of(*published_label);
    const std::string current = reproduce_timing_key(label);
    const bool same_machine = out.contains(current) && machine_of(out[current]) == machine;
    if (same_machine) {
      // Superseded by this machine's run, unless that run computed fewer of the tier's cases.
      if (computed_cases(e) > computed_cases(out[current])) out[current] = e;
      continue;
    }
    // Kept as it was where this machine has no run of the tier; else renamed after its machine.
    out[out.contains(current) ? reproduce_timing_key(label + " on " + machine) : key] = e;
  }
  return out;
}

}  // namespace

FollowUpWork follow_up_work(const Spec& spec, const fs::path& out) {
  FollowUpWork w;
  const std::vector<RunParams> runs = expected_follow_ups(spec, out);
  if (runs.empty()) return w;
  // A run is counted once in the experiment: a follow-up that repeats one of its cases (a case
  // that is one run, as the cache keys it) or another follow-up adds nothing.
  std::set<std::string> counted;
  if (case_search(spec).empty())
    for (const CaseSpec& c : spec.cases)
      counted.insert(case_key(c.params));
  const ResultCache cache(out / "cache");
  for (const RunParams& p : runs) {
    if (!counted.insert(case_key(p)).second) continue;
    ++w.runs;
    const std::optional<ojson> record = cache.load(p);
    if (!record || !record->contains("timing") || !(*record)["timing"].is_object()) continue;
    const ojson& t = (*record)["timing"];
    if (!t.contains("wall_seconds") || !t["wall_seconds"].is_number()) continue;
    ++w.cached;
    w.particle_steps += record_particle_steps(*record);
    w.seconds += t["wall_seconds"].get<double>();
    if (t.contains("ns_per_particle_step") && t["ns_per_particle_step"].is_number())
      w.ns_per_particle_step.push_back(t["ns_per_particle_step"].get<double>());
  }
  return w;
}

std::string machine_of(const ojson& timing) {
  const std::string cpu = text(timing, "cpu"), kernels = text(timing, "kernels");
  if (cpu.empty()) return "CPU not recorded";
  return kernels.empty() || kernels == "not recorded" ? cpu : cpu + ", " + kernels + " kernels";
}

void write_performance(const std::vector<Spec>& specs, const fs::path& bench, const fs::path& out) {
  // The machine's timings of the runs in `out`, published as <out>/timings.json with the other
  // machines' tier runs it already held.
  if (const auto text = read_if_present(machine_timings(out))) {
    ojson measured = parse_json_strict<ojson>(*text, machine_timings(out));
    // Each experiment's follow-up runs, from this machine's cache, beside its cases' timings:
    // performance.md then reads one machine's measurements per experiment from timings.json
    // alone, whatever cache the machine that writes it has.
    for (const auto& spec : specs)
      if (spec.study->has_cases && measured.contains(spec.name) && measured[spec.name].is_object())
        measured[spec.name]["follow_up"] = to_json(follow_up_work(spec, out));
    const ojson merged = merged_timings(measured, read_timings(out));
    write_if_changed(out / "timings.json", merged.dump(1) + "\n");
  }
  std::ostringstream md;
  md << "# Performance\n\nWhat a result costs: the step kernel measured with Google Benchmark "
        "(`make bench`, `tests/bench_step.cpp`), what each measured quantity adds to it, and the "
        "wall time of every experiment of `make reproduce`.\n\n";
  write_benchmark(md, bench);
  write_experiment_times(md, specs, out, bench_figures(bench));
  write_cluster_times(md, out);
  write_if_changed(out / "performance.md", md.str());
}

std::string kernel_brief(const fs::path& bench) {
  const std::string text = read_if_present(bench).value_or("");
  if (text.empty())
    return "No benchmark figures: " + bench.generic_string() + " is missing (`make bench`).\n";
  const ojson doc = parse_json_strict<ojson>(text, bench);
  const BenchFigures b = read_figures(doc);
  const ojson& ctx = doc["context"];
  std::ostringstream md;
  md << "Measured " << bench_machine(ctx)
     << "; ns per particle-step, median (coefficient of variation):\n\n"
     << "| benchmark | GIMP | MPM |\n|---|---|---|\n";
  for (const char* name : {"BM_StepBaseline", "BM_Step", "BM_StepChecked", "BM_StepInstrumented"}) {
    md << "| `" << name << "` |";
    for (const char* m : {"gimp", "mpm"}) {
      const Figure* f = b.find(name, m);
      md << " " << (f ? fixed(f->median, 2) + " (" + fixed(100 * f->cv, 1) + "%)" : "–") << " |";
    }
    md << "\n";
  }
  write_kernel_summary(md, b);
  return md.str();
}

}  // namespace mpmstab
