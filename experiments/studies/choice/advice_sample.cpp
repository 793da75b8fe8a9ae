// The advice sample: what the prediction alone is worth. For problems drawn at random over the
// domain of `mpmstab advise` (seeded), the lookup (`advise --no-verify`'s answer) is run through
// its verifying runs; the report counts how often it fails them, overall, per method, attribute
// and setting. Its cases are the advice study's (cases_from); its follow-ups, the verifying runs.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab::studies::advice_sample {
namespace {

using ojson = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// Findings: each drawn problem, its lookup and what its verifying runs gave

enum class SampleStatus { no_lookup, over_cap, passes, misses };

struct SampleProblem {
  VerifyProblem problem;
  std::optional<Candidate> lookup;
  SampleStatus status = SampleStatus::no_lookup;
  std::vector<VerifyingRun> runs;  // where verified
  std::string why;                 // the first run that failed, where it misses
};

std::vector<CheckedSetting> sample_settings(const StudyInputs& inputs) {
  const auto in = inputs.find("advice");
  if (in == inputs.end() || !in->second.present()) return {};
  return checked_settings_of(in->second.doc);
}

// The problems and their lookups in draw order (a candidate points into `settings`).
std::vector<SampleProblem> lookups(const std::vector<CheckedSetting>& settings) {
  std::vector<SampleProblem> out;
  for (const VerifyProblem& vp : draw_problems()) {
    SampleProblem sp{.problem = vp};
    const std::vector<Candidate> list = candidates(settings, vp);
    if (!list.empty() && list.front().predicted_error_over_A &&
        *list.front().predicted_error_over_A <= vp.problem.target) {
      sp.lookup = list.front();
      sp.status = sp.lookup->verify_particle_steps <= kSampleRule.verify_cap
                      ? SampleStatus::passes
                      : SampleStatus::over_cap;
    }
    out.push_back(std::move(sp));
  }
  return out;
}

// What a verifying run of the sample is for: its problem (by its index in the draw) and its check.
std::string verifying_role(std::size_t problem, const std::string& what) {
  return "problem " + std::to_string(problem + 1) + ": " + what;
}

std::vector<FollowUp> sample_follow_up(const FollowUpContext& c) {
  const std::vector<CheckedSetting> settings = sample_settings(c.inputs);
  const std::vector<SampleProblem> problems = lookups(settings);
  std::vector<FollowUp> out;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const SampleProblem& sp = problems[i];
    if (sp.status != SampleStatus::passes) continue;
    for (auto& [what, params] : verifying_params(*sp.lookup, sp.problem))
      out.push_back({.role = verifying_role(i, what), .params = params});
  }
  return out;
}

// The verdicts of the follow-up runs, three a verified lookup, each by what it was asked for.
std::vector<SampleProblem> findings(const std::vector<CheckedSetting>& settings,
                                    const std::vector<ojson>& follow_up) {
  std::vector<SampleProblem> out = lookups(settings);
  for (std::size_t i = 0; i < out.size(); ++i) {
    SampleProblem& sp = out[i];
    if (sp.status != SampleStatus::passes) continue;
    for (auto& [what, params] : verifying_params(*sp.lookup, sp.problem)) {
      const auto asked = follow_ups_of(follow_up, FollowUp::kNoCase, verifying_role(i, what));
      if (asked.size() != 1) throw std::logic_error("advice_sample: a follow-up is missing");
      const double target = sp.problem.problem.target;
      VerifyingRun v = verifying_run_of(what, *asked.front(), target);
      if (!v.passes && sp.status == SampleStatus::passes) {
        sp.status = SampleStatus::misses;
        sp.why = failure_words(v, target);
      }
      sp.runs.push_back(std::move(v));
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Counts

struct Tally {
  int drawn = 0, no_lookup = 0, over_cap = 0, verified = 0, misses = 0;
  void add(const SampleProblem& sp) {
    ++drawn;
    no_lookup += sp.status == SampleStatus::no_lookup;
    over_cap += sp.status == SampleStatus::over_cap;
    verified += sp.status == SampleStatus::passes || sp.status == SampleStatus::misses;
    misses += sp.status == SampleStatus::misses;
  }
};

std::string rate(const Tally& t) {
  if (t.verified == 0) return "–";
  return std::to_string(t.misses) + " of " + std::to_string(t.verified) + " (" +
         fixed(100.0 * t.misses / t.verified, 0) + "%)";
}

// "1e-3 to 1e-2": the decade a value lies in.
std::string decade(double x) {
  const double low = std::pow(10.0, std::floor(std::log10(x) + 1e-12));
  return value_text(low) + " to " + value_text(low * 10);
}

// The attributes a miss rate is given per, each with its value for a problem.
struct Attribute {
  const char* name;
  std::string (*of)(const VerifyProblem&);
};
const Attribute kAttributes[] = {
    {"scene", [](const VerifyProblem& v) { return v.problem.scene; }},
    {"boundary", [](const VerifyProblem& v) { return v.problem.bc; }},
    {"layout",
     [](const VerifyProblem& v) { return std::string(v.jitter > 0 ? "jittered" : "uniform"); }},
    {"A/L", [](const VerifyProblem& v) { return decade(v.problem.A); }},
    {"c T/L", [](const VerifyProblem& v) { return decade(v.problem.cT); }},
    {"target / A", [](const VerifyProblem& v) { return decade(v.problem.target); }},
};

// ---------------------------------------------------------------------------------------------
// Claims

std::vector<Claim> sample_claims(const Tally& all, const std::vector<ojson>& verifying) {
  Claim miss = claim("lookup-misses",
                     "The prediction alone is not an answer: the cheapest candidate it ranks "
                     "first fails its verifying runs on some drawn problem",
                     "{misses} of {verified} verified lookups fail ({drawn} problems drawn)");
  miss.count("misses", all.misses)
      .count("verified", all.verified)
      .count("drawn", all.drawn)
      .over(all.verified);
  miss.holds = all.misses > 0;
  miss.on(coverage_of(verifying));
  return {miss};
}

// ---------------------------------------------------------------------------------------------
// Rendering

// How the problems were drawn and what the lookups gave, in two paragraphs.
void draw_text(std::ostream& md, const Tally& all) {
  const SampleRule& rule = kSampleRule;
  const AdviceDomain& d = kAdviceDomain;
  md << "## Results\n\n**The draw** (docs/studies.md, \"Advice: verified on the problem\"). "
     << rule.problems << " problems from the seed " << rule.seed
     << " (std::mt19937_64): A/L log-uniform from " << value_text(d.A_min) << " to "
     << value_text(d.A_max) << ", c T/L from " << value_text(rule.cT_low) << " to "
     << value_text(d.cT_max) << ", the target from " << value_text(d.target_min) << " to "
     << value_text(d.target_max)
     << " A, each rounded to two significant digits; the bar or the neo-Hookean scene, walls or "
        "periodic boundaries, a uniform or a jittered layout (jitter uniform from "
     << value_text(rule.jitter_low) << " to " << value_text(d.jitter_max)
     << " of the spacing), each with even odds. The lookup of a problem is the candidate the "
        "prediction ranks first (`mpmstab advise --no-verify`); it is verified by the runs "
        "`mpmstab advise` makes (the problem, "
     << shortest(d.length_factor) << " x c T, " << d.grid_factor
     << " times the cells at the same C) where they cost at most " << sci(rule.verify_cap)
     << " particle-steps in all. A lookup misses when one of them is not stable within the "
        "target.\n\n";
  md << "**Reading.** Of " << all.drawn << " problems drawn, " << all.no_lookup
     << " have no candidate predicted to meet their target and " << all.over_cap
     << " a lookup whose verifying runs pass the cap; of the " << all.verified
     << " lookups verified, " << all.misses
     << " miss. A miss is what `mpmstab advise` catches before it answers; its answer is the "
        "first candidate that passes.\n\n";
}

// The lookups' misses per method, then per attribute of the problem.
void per_method_tables(std::ostream& md, const std::vector<SampleProblem>& problems) {
  std::map<std::string, Tally> per_method;
  for (const auto& sp : problems)
    if (sp.lookup) per_method[sp.lookup->from->method_text()].add(sp);
  md << "## Misses per method of the lookup\n\n| method | lookups | over the cap | misses of "
        "verified |\n|---|---|---|---|\n";
  for (const auto& [method, t] : per_method)
    md << "| " << method << " | " << t.drawn << " | " << t.over_cap << " | " << rate(t) << " |\n";
  md << "\n## Misses per attribute of the problem\n\n| attribute | value | problems | no lookup "
        "| over the cap | misses of verified |\n|---|---|---|---|---|---|\n";
  for (const Attribute& a : kAttributes) {
    std::map<std::string, Tally> per;
    for (const auto& sp : problems)
      per[a.of(sp.problem)].add(sp);
    for (const auto& [value, t] : per)
      md << "| " << a.name << " | " << value << " | " << t.drawn << " | " << t.no_lookup << " | "
         << t.over_cap << " | " << rate(t) << " |\n";
  }
}

// Per setting: the box where its runs passed, and what the sample found inside and out of it.
void per_setting_table(std::ostream& md, const std::vector<SampleProblem>& problems) {
  std::map<const CheckedSetting*, Tally> per_setting;
  for (const auto& sp : problems)
    if (sp.lookup) per_setting[sp.lookup->from].add(sp);
  md << "\n## Each setting the lookup chose: where its runs passed, and the sampled miss "
        "rate\n\nThe box is where the advice study's runs of the setting ended stable and "
        "accurate (advice.md); the sampled problems of a setting include its finer grids and "
        "problems outside that box.\n\n| setting | box of its passed runs (largest error / A) | "
        "lookups | misses of verified |\n|---|---|---|---|\n";
  std::vector<std::pair<const CheckedSetting*, Tally>> ordered(per_setting.begin(),
                                                               per_setting.end());
  std::sort(ordered.begin(), ordered.end(), [](const auto& a, const auto& b) {
    return setting_name(*a.first) < setting_name(*b.first);
  });
  for (const auto& [s, t] : ordered) {
    std::string box;
    for (const auto& r : s->regions)
      box += (box.empty() ? "" : "<br>") + region_text(r) + " (" + sci(r.error_over_A) + ")";
    md << "| " << setting_name(*s) << " | " << (box.empty() ? "none" : box) << " | " << t.drawn
       << " | " << rate(t) << " |\n";
  }
}

// What verification costs against the run it protects.
void cost_text(std::ostream& md, const std::vector<SampleProblem>& problems) {
  std::vector<double> ratios;
  for (const auto& sp : problems)
    if (sp.lookup) ratios.push_back(sp.lookup->verify_particle_steps / sp.lookup->particle_steps);
  std::sort(ratios.begin(), ratios.end());
  md << "\n## What verification costs\n\n";
  if (!ratios.empty())
    md << "The three verifying runs of a lookup take " << significant(ratios.front(), 3) << " to "
       << significant(ratios.back(), 3) << " times the particle-steps of the problem's own run "
       << "(median " << significant(ratios[ratios.size() / 2], 3)
       << "); `mpmstab advise` adds the problem runs of the candidates it rejects before its "
          "answer.\n\n";
}

// The draw, every problem.
void problems_table(std::ostream& md, const std::vector<SampleProblem>& problems) {
  md << "## Every problem drawn\n\n| # | A/L | c T/L | target / A | scene | boundary | layout | "
        "lookup | predicted / A | verifying runs: error over time / A | result |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const SampleProblem& sp = problems[i];
    const Problem& p = sp.problem.problem;
    md << "| " << i + 1 << " | " << value_text(p.A) << " | " << value_text(p.cT) << " | "
       << value_text(p.target) << " | " << p.scene << " | " << p.bc << " | "
       << (sp.problem.jitter > 0 ? "jittered " + value_text(sp.problem.jitter)
                                 : std::string("uniform"))
       << " | " << (sp.lookup ? candidate_name(*sp.lookup) : std::string("–")) << " | "
       << (sp.lookup ? sci(*sp.lookup->predicted_error_over_A) : std::string("–")) << " | ";
    std::string errors;
    for (const auto& r : sp.runs)
      errors += (errors.empty() ? "" : ", ") +
                (r.outcome == "stable" && r.error_over_A ? sci(*r.error_over_A) : r.outcome);
    md << (errors.empty() ? "–" : errors) << " | ";
    switch (sp.status) {
      case SampleStatus::no_lookup:
        md << "no candidate predicted to meet the target";
        break;
      case SampleStatus::over_cap:
        md << "not run: its verifying runs take " << sci(sp.lookup->verify_particle_steps)
           << " particle-steps, above the cap";
        break;
      case SampleStatus::passes:
        md << "passes";
        break;
      case SampleStatus::misses:
        md << "**misses** (" << sp.why << ")";
    }
    md << " |\n";
  }
}

ojson sample_json(const std::vector<SampleProblem>& problems, const Tally& all) {
  ojson list = ojson::array();
  for (const auto& sp : problems) {
    const Problem& p = sp.problem.problem;
    ojson j = {{"A", p.A},         {"cT", p.cT}, {"error", p.target},
               {"scene", p.scene}, {"bc", p.bc}, {"jitter", sp.problem.jitter}};
    const char* status[] = {"no_lookup", "over_cap", "passes", "misses"};
    j["status"] = status[int(sp.status)];
    if (sp.lookup) {
      j["lookup"] = candidate_name(*sp.lookup);
      j["predicted_error_over_A"] = *sp.lookup->predicted_error_over_A;
      j["verify_particle_steps"] = sp.lookup->verify_particle_steps;
    }
    ojson runs = ojson::array();
    for (const auto& r : sp.runs)
      runs.push_back({{"what", r.what},
                      {"outcome", r.outcome},
                      {"error_over_A", r.error_over_A ? ojson(*r.error_over_A) : ojson(nullptr)}});
    j["runs"] = runs;
    list.push_back(j);
  }
  const SampleRule& rule = kSampleRule;
  return {{"rule",
           {{"seed", rule.seed},
            {"problems", rule.problems},
            {"cT_low", rule.cT_low},
            {"jitter_low", rule.jitter_low},
            {"verify_cap", rule.verify_cap}}},
          {"drawn", all.drawn},
          {"no_lookup", all.no_lookup},
          {"over_cap", all.over_cap},
          {"verified", all.verified},
          {"misses", all.misses},
          {"problems", list}};
}

StudyReport sample_report(const ReportContext& c) {
  const std::vector<CheckedSetting> settings = sample_settings(c.inputs);
  const std::vector<SampleProblem> problems = findings(settings, c.follow_up);
  Tally all;
  for (const auto& sp : problems)
    all.add(sp);
  std::ostringstream md;
  draw_text(md, all);
  per_method_tables(md, problems);
  per_setting_table(md, problems);
  cost_text(md, problems);
  problems_table(md, problems);
  return StudyReport{.markdown = md.str() + "\n",
                     .json = sample_json(problems, all),
                     .claims = sample_claims(all, c.follow_up)};
}

const StudyRegistration kAdviceSample{{
    .name = "advice_sample",
    .summary = "how often the prediction alone fails verification, on problems drawn at random",
    .records = {.error_over_time = true},
    .inputs = {{.name = "advice", .required = true}},
    .follow_up = sample_follow_up,
    .report = sample_report,
    .index =
        [](const Spec& spec, const std::vector<ojson>&) {
          return "**What it shows.** How often the prediction alone (`mpmstab advise --no-verify`) "
                 "fails the runs `mpmstab advise` verifies with, on problems drawn at random over "
                 "its domain, per method and per attribute of the problem: [" +
                 spec.name + ".md](" + spec.name + ".md).\n\n";
        },
}};

}  // namespace
}  // namespace mpmstab::studies::advice_sample
