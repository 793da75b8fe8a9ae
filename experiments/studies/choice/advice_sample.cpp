// The advice sample: `mpmstab advise` as a user runs it, over its whole domain. Problems drawn at
// random (seeded) over every attribute the command takes are answered by its search, with its
// default budget and without the margins; every run goes through the result cache (cached_run),
// so that the report, rendered again, computes nothing. Each answer is then verified again by
// separate runs (they also record the bound of eq. (108): their own cache keys), by the same rule.
// The report counts the answers and the refusals per layout and per target decade, the answers
// that fail again, and the work each search took. Its cases are the advice study's (cases_from).
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "cached_run.hpp"
#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "parallel.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab::studies::advice_sample {
namespace {

using ojson = nlohmann::ordered_json;

// The draw: its own seed and size, over the whole domain (advice_verify.hpp, draw_problems).
constexpr SampleRule kDraw{.seed = 20261129, .problems = 30};
// The share of the drawn problems the search is expected to answer (the claim's threshold).
constexpr double kAnsweredShare = 0.8;

// ---------------------------------------------------------------------------------------------
// Findings: each drawn problem, the search's answer or refusal, and the answer verified again

struct Searched {
  VerifyProblem problem;
  Verified search;
  std::optional<Trial> again;  // the answer's verifying runs made again, separately
};

// Every drawn problem searched on as many threads as the process has CPUs (make studies on its
// machine's, the render job of a tier on a cluster on those Slurm gave it), each taking the next
// problem as it finishes one (each search is a sequence; the problems are independent, and each
// run's result does not depend on which thread made it).
std::vector<Searched> searched(const std::vector<CheckedSetting>& settings,
                               const std::filesystem::path& out) {
  const ResultCache cache(out / "cache");
  const RunFn run_fn = [&](const RunParams& p) { return cached_run(cache, p); };
  const RunFn separate = [&](const RunParams& p) {
    RunParams q = p;
    q.observe.dt_stable = true;
    return cached_run(cache, q);
  };
  std::vector<Searched> all;
  for (const VerifyProblem& vp : draw_problems(kDraw))
    all.push_back({.problem = vp});
  auto one = [&](Searched& s) {
    s.search =
        verified_advice(settings, s.problem, kAdviceDomain.budget_particle_steps, false, run_fn);
    if (s.search.answer) s.again = verify(s.search.answer->candidate, s.problem, separate);
  };
  for_each_in_parallel(all.size(), available_cpus(), [&](std::size_t i) { one(all[i]); });
  return all;
}

struct Tally {
  int drawn = 0, answered = 0, misses = 0;
  std::map<std::string, int> refused;  // by the bound that decided it
  std::vector<double> work;            // particle-steps of each answered search
  void add(const Searched& s) {
    ++drawn;
    if (!s.search.answer) {
      ++refused[s.search.bound];
      return;
    }
    ++answered;
    misses += s.again && !s.again->passed;
    work.push_back(s.search.particle_steps);
  }
};

// "uniform", or the jittered layout's bracket between the advice study's corner jitters.
std::string layout_of(const VerifyProblem& v) {
  if (v.jitter == 0) return "uniform";
  double low = 0;
  for (const double j : kRegionRule.jitters) {
    if (v.jitter <= j)
      return "jittered, " + (low > 0 ? value_text(low) + " to " : "up to ") + value_text(j);
    low = j;
  }
  return "jittered, above " + value_text(low);
}

// "1e-3 to 1e-2": the decade a value lies in.
std::string decade(double x) {
  const double low = std::pow(10.0, std::floor(std::log10(x) + 1e-12));
  return value_text(low) + " to " + value_text(low * 10);
}

// Where the drawn problems lie, in words.
std::string drawn_on(const std::vector<Searched>& all) {
  std::vector<double> A, cT, target, jitter;
  for (const auto& s : all) {
    A.push_back(s.problem.problem.A);
    cT.push_back(s.problem.problem.cT);
    target.push_back(s.problem.problem.target);
    jitter.push_back(s.problem.jitter);
  }
  return std::to_string(all.size()) + " problems: A/L " + span(A) + ", c T/L " + span(cT) +
         ", target " + span(target) + " A, jitter " + span(jitter) +
         "; bar and steffen, walls and periodic";
}

// ---------------------------------------------------------------------------------------------
// Claims

std::vector<Claim> sample_claims(const Tally& all, const std::string& on) {
  Claim answered = claim("answers-across-the-domain",
                         "mpmstab advise answers at least {share} of the problems drawn over its "
                         "whole domain, within its default budget",
                         "{answered} of {drawn} answered");
  answered.number("share", kAnsweredShare)
      .count("answered", all.answered)
      .count("drawn", all.drawn)
      .on(on);
  answered.holds = all.drawn > 0 && all.answered >= kAnsweredShare * all.drawn;
  Claim held = claim("answers-hold-again",
                     "Every answer passes its verifying runs again when they are made separately",
                     "{held} of {answered} answers");
  held.every("held", all.answered - all.misses, "answered", all.answered).on(on);
  return {answered, held};
}

// ---------------------------------------------------------------------------------------------
// Rendering

void draw_text(std::ostream& md, const Tally& all) {
  const AdviceDomain& d = kAdviceDomain;
  md << "## Results\n\n**The draw** (docs/studies.md, \"Advice: verified on the problem\"). "
     << kDraw.problems << " problems from the seed " << kDraw.seed
     << " (std::mt19937_64): A/L log-uniform from " << value_text(d.A_min) << " to "
     << value_text(d.A_max) << ", c T/L from " << value_text(kDraw.cT_low) << " to "
     << value_text(d.cT_max) << ", the target from " << value_text(d.target_min) << " to "
     << value_text(d.target_max)
     << " A, each rounded to two significant digits; the bar or the neo-Hookean scene, walls or "
        "periodic boundaries, a uniform or a jittered layout (jitter uniform from "
     << value_text(kDraw.jitter_low) << " to " << value_text(d.jitter_max)
     << " of the spacing), each with even odds. Each is answered by `mpmstab advise` with its "
        "default budget, "
     << sci(d.budget_particle_steps)
     << " particle-steps, without the margins; each answer's verifying runs are then made again "
        "as separate runs and judged by the same rule.\n\n";
  std::vector<double> w = all.work;
  std::sort(w.begin(), w.end());
  md << "**Reading.** Of " << all.drawn << " problems drawn, " << all.answered << " are answered";
  for (const auto& [bound, n] : all.refused)
    md << ", " << n << " refused on the bound " << bound;
  md << "; " << all.misses << " of the " << all.answered
     << " answers fail when their verifying runs are made again.";
  if (!w.empty())
    md << " A search that answered took " << sci(w.front()) << " to " << sci(w.back())
       << " particle-steps (median " << sci(w[w.size() / 2]) << ").";
  md << "\n\n";
}

void per_attribute_table(std::ostream& md, const std::vector<Searched>& all) {
  md << "| attribute | value | problems | answered | refused | answers that fail again |\n"
        "|---|---|---|---|---|---|\n";
  using Of = std::string (*)(const VerifyProblem&);
  for (const auto& [name, of] :
       {std::pair<const char*, Of>{"layout", layout_of},
        {"target / A", [](const VerifyProblem& v) { return decade(v.problem.target); }}}) {
    std::map<std::string, Tally> per;
    for (const auto& s : all)
      per[of(s.problem)].add(s);
    for (const auto& [value, t] : per)
      md << "| " << name << " | " << value << " | " << t.drawn << " | " << t.answered << " | "
         << t.drawn - t.answered << " | " << t.misses << " |\n";
  }
  md << "\n";
}

std::string runs_text(const Trial& t) {
  std::string s;
  for (const auto& r : t.runs)
    s += (s.empty() ? "" : ", ") +
         (r.outcome == "stable" && r.error_over_A ? sci(*r.error_over_A) : r.outcome);
  return s;
}

void problems_table(std::ostream& md, const std::vector<Searched>& all) {
  md << "## Every problem drawn\n\n| # | A/L | c T/L | target / A | scene | boundary | layout | "
        "answer, or the refusal | its verifying runs: error over time / A | candidates tried "
        "| particle-steps | made again |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Searched& s = all[i];
    const Problem& p = s.problem.problem;
    md << "| " << i + 1 << " | " << value_text(p.A) << " | " << value_text(p.cT) << " | "
       << value_text(p.target) << " | " << p.scene << " | " << p.bc << " | "
       << (s.problem.jitter > 0 ? "jittered " + value_text(s.problem.jitter)
                                : std::string("uniform"))
       << " | " << (s.search.answer ? candidate_name(s.search.answer->candidate) : s.search.refusal)
       << " | " << (s.search.answer ? runs_text(*s.search.answer) : std::string("–")) << " | "
       << s.search.rejected.size() + (s.search.answer ? 1 : 0) << " | "
       << sci(s.search.particle_steps) << " | "
       << (s.again ? (s.again->passed ? "passes" : "**fails** (" + s.again->why + ")")
                   : std::string("–"))
       << " |\n";
  }
}

ojson sample_json(const std::vector<Searched>& all, const Tally& t) {
  ojson list = ojson::array();
  for (const auto& s : all) {
    const Problem& p = s.problem.problem;
    ojson j = {{"A", p.A},         {"cT", p.cT}, {"error", p.target},
               {"scene", p.scene}, {"bc", p.bc}, {"jitter", s.problem.jitter}};
    j["answer"] = s.search.answer ? ojson(candidate_name(s.search.answer->candidate)) : nullptr;
    j["bound"] = s.search.answer ? ojson(nullptr) : ojson(s.search.bound);
    j["particle_steps"] = s.search.particle_steps;
    j["passes_again"] = s.again ? ojson(s.again->passed) : ojson(nullptr);
    list.push_back(j);
  }
  return {{"rule", {{"seed", kDraw.seed}, {"problems", kDraw.problems}}},
          {"drawn", t.drawn},
          {"answered", t.answered},
          {"misses", t.misses},
          {"problems", list}};
}

StudyReport sample_report(const ReportContext& c) {
  const auto in = c.inputs.find("advice");
  const std::vector<CheckedSetting> settings = in != c.inputs.end() && in->second.present()
                                                   ? checked_settings_of(in->second.doc)
                                                   : std::vector<CheckedSetting>{};
  const std::vector<Searched> all = searched(settings, c.out);
  Tally t;
  for (const auto& s : all)
    t.add(s);
  std::ostringstream md;
  draw_text(md, t);
  per_attribute_table(md, all);
  problems_table(md, all);
  return StudyReport{.markdown = md.str() + "\n",
                     .json = sample_json(all, t),
                     .claims = sample_claims(t, drawn_on(all))};
}

const StudyRegistration kAdviceSample{{
    .name = "advice_sample",
    .summary = "how often `mpmstab advise` answers over its whole domain, and whether its answers "
               "hold, on problems drawn at random",
    .records = {.error_over_time = true},
    .inputs = {{.name = "advice", .required = true}},
    .report = sample_report,
    .index =
        [](const Spec& spec, const std::vector<ojson>&, const ojson&) {
          return "**What it shows.** How often `mpmstab advise` answers problems drawn at random "
                 "over its whole domain, per layout and per target decade, whether its answers "
                 "pass again when their verifying runs are made separately, and the work each "
                 "search took: [" +
                 spec.name + ".md](" + spec.name + ".md).\n\n";
        },
}};

}  // namespace
}  // namespace mpmstab::studies::advice_sample
