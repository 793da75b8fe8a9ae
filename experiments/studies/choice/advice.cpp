// The advice study: settings (a method, a grid, a Courant number), each run on a base problem and,
// where that run is accurate, at its corners (advice_rule.hpp). advice.json stores them for
// `mpmstab advise` to predict from (advice_verify.hpp); advice.md lists them, answering nothing.
#include <map>
#include <sstream>

#include "base/accuracy.hpp"
#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab::studies::advice {
namespace {

using ojson = nlohmann::ordered_json;

// ---------------------------------------------------------------------------------------------
// Follow-ups: the corner runs of each setting worth checking

// A run as a corner of its setting reads it.
CornerRun corner_of(const ojson& r, CornerKind kind, double length) {
  CornerRun c{.kind = kind, .length = length, .A = r["A"].get<double>()};
  c.cells = r["cells"].get<int>();
  c.jitter = r.value("jitter", 0.0);
  c.outcome = outcome(r);
  if (const auto e = RunRow(r).error_over_time) c.error_over_A = *e / c.A;
  return c;
}

// A setting is run at its corners where its base run is accurate and within the limit's margin.
bool worth_checking(const ojson& base) {
  const CornerRun c = corner_of(base, CornerKind::base, kRegionRule.lengths.front());
  const RunRow run(base);
  return c.passes() && run.courant_spectral &&
         *run.courant <= *run.courant_spectral / kRegionRule.limit_margin;
}

// What a corner run is for: its corner (kind and length).
std::string corner_role(const Corner& k) {
  return "corner " + std::string(to_string(k.kind)) +
         (k.kind == CornerKind::jittered ? " " + shortest(k.jitter) : std::string()) +
         " at c T/L " + shortest(k.length);
}

// Every corner of every setting worth checking.
std::vector<FollowUp> advice_follow_up(const FollowUpContext& c) {
  std::vector<FollowUp> runs;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    if (!worth_checking(c.rows[i])) continue;
    for (auto& corner : region_corners(c.spec.cases.at(i).params))
      runs.push_back({.of = i, .role = corner_role(corner), .params = std::move(corner.params)});
  }
  return runs;
}

// ---------------------------------------------------------------------------------------------
// Findings: the settings, their corners and regions, and what the corners say

// A setting from its base run's row, that run its first corner; its transfer "fmpm(2)".
CheckedSetting setting_of(const ojson& r) {
  std::string transfer = text(r, "transfer");
  for (const char* order : {"flip_fraction", "xpic_order", "fmpm_order"})
    if (has_number(r, order)) transfer += "(" + shortest(r[order].get<double>()) + ")";
  CheckedSetting s{.method = RunRow(r).method,
                   .transfer = transfer,
                   .update = text(r, "update"),
                   .cells = r["cells"].get<int>(),
                   .ppc = r["ppc"].get<int>(),
                   .courant = r["cfl_factor"].get<double>()};
  s.courant_spectral = RunRow(r).courant_spectral;
  s.corners.push_back(corner_of(r, CornerKind::base, kRegionRule.lengths.front()));
  return s;
}

// Every setting of the spec with its corner runs (its row's follow-ups) and its regions.
std::vector<CheckedSetting> checked_settings(const ReportContext& c) {
  std::vector<CheckedSetting> out;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    CheckedSetting s = setting_of(c.rows[i]);
    if (worth_checking(c.rows[i])) {
      for (const auto& k : region_corners(c.spec.cases.at(i).params))
        for (const ojson* run : follow_ups_of(c.follow_up, i, corner_role(k)))
          s.corners.push_back(corner_of(*run, k.kind, k.length));
    }
    s.regions = regions_of(s);
    out.push_back(std::move(s));
  }
  return out;
}

// What the report, its claims, the index paragraph and the subtitle say, found once.
struct Findings {
  std::vector<CheckedSetting> settings;  // with their corners and regions (none for the index)
  // Per setting, the runs its regions exclude, then its base run to a longer length if it fails.
  std::vector<std::vector<CornerRun>> failed;
  int cases = 0, checked = 0;             // the settings, and those run again at their corners
  int with_region = 0, to_longest = 0;    // with a region (to some length), with one to the longest
  int finer_fails = 0, finer_tested = 0;  // accurate base, finer corner not accurate
  int longer_fails = 0, longer_tested = 0;  // accurate base, base to the longer length not
  int scene_fails = 0, scene_tested = 0;    // largest A passes on the bar, neo-Hookean fails
  Coverage finer_on, longer_on, scene_on;   // the runs each count reads
};

// The findings from the rows and the settings (from the follow-ups, advice.json, or none).
Findings find(const std::vector<ojson>& rows, std::vector<CheckedSetting> settings) {
  Findings n{.settings = std::move(settings), .cases = int(rows.size())};
  for (const auto& r : rows)
    n.checked += worth_checking(r);
  const double shorter = kRegionRule.lengths.front(), longer = kRegionRule.lengths.back();
  // A corner run in a coverage: its amplitude, length (c T, at E = kAdviceE), grid and scene.
  const auto cover = [](Coverage& on, std::initializer_list<const CornerRun*> runs) {
    for (const CornerRun* c : runs)
      on.add(ojson{{"A", c->A},
                   {"cT", c->length},
                   {"cells", c->cells},
                   {"scene", c->kind == CornerKind::other_scene ? "steffen" : "bar"}});
  };
  for (const auto& s : n.settings) {
    auto& failed = n.failed.emplace_back();
    for (const auto& r : s.regions) {
      failed.insert(failed.end(), r.excluded.begin(), r.excluded.end());
      n.to_longest += r.length == longer;
    }
    for (const auto& c : s.corners)
      if (c.kind == CornerKind::base && c.length != shorter && !c.passes()) failed.push_back(c);
    if (s.corners.size() <= 1) continue;
    n.with_region += !s.regions.empty();
    const CornerRun* base = &s.corners.front();  // the base run to the shorter length
    if (const CornerRun* f = s.corner(CornerKind::finer, shorter)) {
      ++n.finer_tested;
      n.finer_fails += !f->passes();
      cover(n.finer_on, {base, f});
    }
    if (const CornerRun* b = s.corner(CornerKind::base, longer)) {
      ++n.longer_tested;
      n.longer_fails += !b->passes();
      cover(n.longer_on, {base, b});
    }
    for (const double length : kRegionRule.lengths) {
      const CornerRun* large = s.corner(CornerKind::largest_A, length);
      const CornerRun* scene = s.corner(CornerKind::other_scene, length);
      if (!large || !scene) continue;
      cover(n.scene_on, {large, scene});
      if (!large->passes()) continue;
      ++n.scene_tested;
      n.scene_fails += !scene->passes();
    }
  }
  return n;
}

// ---------------------------------------------------------------------------------------------
// Claims

// A claim that some of the `tested` fail: it holds when one does.
Claim some_fail(Claim c, int fails, int tested, const Coverage& on) {
  c.count("fails", fails).count("tested", tested);
  c.holds = fails > 0;
  return c.on(on);
}

std::vector<Claim> advice_claims(const Findings& n) {
  Claim finer = claim("fixed-courant-fails-finer",
                      "A Courant number accurate on its grid is not accurate on every finer grid: "
                      "some setting accurate on its grid is not at {refine}x the cells",
                      "{fails} of {tested} checked settings fail at {refine}x the cells");
  finer.count("refine", kRegionRule.refine);
  Claim longer = claim("accurate-base-fails-longer",
                       "A setting accurate to c T/L = {short} is not always accurate to {long}",
                       "{fails} of {tested} checked settings fail to the longer length");
  longer.value("short", value_text(kRegionRule.lengths.front()))
      .value("long", value_text(kRegionRule.lengths.back()));
  Claim scene = claim("bar-does-not-cover-neo-hookean",
                      "A setting accurate on the bar at the largest amplitude is not always "
                      "accurate on the neo-Hookean scene there",
                      "{fails} of {tested} such corners fail on the neo-Hookean scene");
  return {some_fail(finer, n.finer_fails, n.finer_tested, n.finer_on),
          some_fail(longer, n.longer_fails, n.longer_tested, n.longer_on),
          some_fail(scene, n.scene_fails, n.scene_tested, n.scene_on)};
}

// ---------------------------------------------------------------------------------------------
// Text

std::string error_text(const std::optional<double>& e) {
  return e ? sci(*e) + " A" : std::string("–");
}

// A corner run in a table: "A/L 0.05 to c T/L 10: 3.1e-3 A", "neo-Hookean to c T/L 100: unstable".
std::string corner_text(const CornerRun& c) {
  std::string what(corner_words(c.kind));
  if (c.kind == CornerKind::smallest_A || c.kind == CornerKind::largest_A)
    what = "A/L " + value_text(c.A);
  if (c.kind == CornerKind::finer) what = std::to_string(c.cells) + " cells";
  return what + " to c T/L " + value_text(c.length) + ": " +
         (c.outcome == "stable" ? error_text(c.error_over_A) : c.outcome);
}

std::string rule_text() {
  const RegionRule& r = kRegionRule;
  std::ostringstream md;
  md << "**What is run** (docs/studies.md, \"Advice: verified on the problem\"). A setting is a "
        "method, a grid and a Courant number C = c dt/h. Its base run is the bar with walls at "
        "A/L = "
     << value_text(r.amplitudes[1]) << " to c T/L = " << value_text(r.lengths.front())
     << " (E only rescales time). Where the base run is accurate (error over time below "
     << shortest(kAccurateFraction) << " A) and C is at most the spectral limit / "
     << shortest(r.limit_margin)
     << ", the setting is run again: on the bar with walls at A/L = " << value_text(r.amplitudes[0])
     << ", " << value_text(r.amplitudes[1]) << " and " << value_text(r.amplitudes[2])
     << "; at A/L = " << value_text(r.amplitudes[2])
     << " with periodic boundaries, on the neo-Hookean scene and on layouts jittered by "
     << listing(std::vector<double>(r.jitters.begin(), r.jitters.end()))
     << " of the particle spacing (the jitter `mpmstab advise` answers runs to "
     << value_text(kAdviceDomain.jitter_max)
     << "); each to c T/L = " << value_text(r.lengths.front()) << " and "
     << value_text(r.lengths.back()) << "; and on " << r.refine
     << " times the cells at the same C, A/L = " << value_text(r.amplitudes[1])
     << ", to c T/L = " << value_text(r.lengths.front())
     << ".\n\n**What these runs are for.** `mpmstab advise` predicts a candidate's error on a "
        "problem from the runs below that match the problem's scene, boundary and layout, tries "
        "the candidates predicted to meet its target cheapest first, and answers only with one "
        "it has run on that problem (to c T, to "
     << shortest(kAdviceDomain.length_factor) << " x c T and on " << kAdviceDomain.grid_factor
     << " times the cells). This report "
        "answers no problem. The box beside each setting (the amplitudes, lengths, boundaries, "
        "scene, layout and grids whose runs ended stable and accurate, its error the largest of "
        "theirs) describes where its runs passed; the error between those runs was not measured "
        "here, and no answer is given from the box. How often the prediction alone misses on "
        "problems drawn at random over the domain, per setting beside its box: "
        "[advice_sample.md](advice_sample.md).\n\n";
  return md.str();
}

std::string settings_table(const Findings& n) {
  std::ostringstream md;
  md << "## Every setting, its runs and where they passed\n\n"
     << "| method | cells | C | spectral limit / C | base error / A | runs passed in (largest "
        "error / A) | failed runs |\n|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < n.settings.size(); ++i) {
    const CheckedSetting& s = n.settings[i];
    md << "| " << s.method_text() << " | " << s.cells << " | " << shortest(s.courant) << " | "
       << (s.courant_spectral ? ratio(*s.courant_spectral / s.courant) : std::string("–")) << " | "
       << (s.corners.front().outcome == "stable" ? error_text(s.corners.front().error_over_A)
                                                 : s.corners.front().outcome)
       << " | ";
    if (s.regions.empty()) {
      const CornerRun& base = s.corners.front();
      std::string why =
          "the base run is " + (base.outcome == "stable" ? "not accurate" : base.outcome);
      if (base.passes())
        why = s.courant_spectral
                  ? "C is beyond the spectral limit / " + shortest(kRegionRule.limit_margin)
                  : "its spectral limit is not recorded";
      md << (s.corners.size() > 1 ? "none: the base run to the longer length fails too"
                                  : "none: not checked (" + why + ")")
         << " | – |\n";
      continue;
    }
    std::string regions, failed;
    for (const auto& r : s.regions)
      regions +=
          (regions.empty() ? "" : "<br>") + region_text(r) + " (" + sci(r.error_over_A) + ")";
    for (const auto& c : n.failed[i])
      failed += (failed.empty() ? "" : "<br>") + corner_text(c);
    md << regions << " | " << (failed.empty() ? "–" : failed) << " |\n";
  }
  return md.str() + "\n";
}

std::string reading(const Findings& n) {
  std::ostringstream md;
  md << "**Reading.** Of " << n.cases << " settings, " << n.checked
     << " have an accurate base run within the spectral limit's margin and were run at their "
        "corners; "
     << n.with_region << " passed to at least one length. " << n.finer_fails << " of "
     << n.finer_tested << " checked settings are not accurate on " << kRegionRule.refine
     << " times their cells at the same C; " << n.longer_fails << " of " << n.longer_tested
     << " are not accurate to c T/L = " << value_text(kRegionRule.lengths.back()) << "; "
     << n.scene_fails << " of " << n.scene_tested
     << " corners accurate on the bar at the largest amplitude are not on the neo-Hookean "
        "scene.\n\n";
  return md.str();
}

std::string advice_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Findings n = find(rows, {});
  std::ostringstream md;
  md << "**What it shows.** Of the " << n.cases << " settings of its fixed grid of C, " << n.checked
     << " have an accurate base run within the spectral limit's margin and were run again at "
        "other amplitudes, lengths, boundaries, on the neo-Hookean scene, jittered and on a finer "
        "grid. `mpmstab advise` predicts from these runs and answers a problem only with a "
        "setting it has run on that problem. Details: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Figure

// Per setting: its method's panel, cells, C, its longest region (0: none) and error / A there.
std::string figure_csv(const std::vector<CheckedSetting>& settings) {
  std::ostringstream csv;
  csv << "panel,method,cells,courant,region_cT,error_over_A\n";
  std::map<std::string, int> panel;
  for (const auto& s : settings) {
    const std::string name = s.method_text();
    const auto it = panel.emplace(name, int(panel.size())).first;  // the method's panel
    const Region* longest = s.regions.empty() ? nullptr : &s.regions.back();
    csv << it->second << ',' << name << ',' << s.cells << ',' << shortest(s.courant) << ','
        << (longest ? longest->length : 0.0) << ','
        << (longest ? sci(longest->error_over_A, 3) : std::string("nan")) << '\n';
  }
  return csv.str();
}

// The report, from the findings: the rule, the reading, every setting and the figure's data.
StudyReport advice_report(const ReportContext& c) {
  const Findings n = find(c.rows, checked_settings(c));
  std::ostringstream md;
  md << "## Results\n\n"
     << rule_text() << reading(n) << settings_table(n)
     << "The figure marks each setting by the longest length to which its runs passed (none: "
        "its base run did not pass to either length).\n";
  ojson list = ojson::array();
  for (const auto& s : n.settings)
    list.push_back(to_json(s));
  const RegionRule& r = kRegionRule;
  ojson rule = {{"amplitudes", r.amplitudes},
                {"lengths", r.lengths},
                {"refine", r.refine},
                {"jitters", r.jitters},
                {"limit_margin", r.limit_margin},
                {"accurate_fraction", kAccurateFraction}};
  return StudyReport{.markdown = md.str(),
                     .data_csv = figure_csv(n.settings),
                     .json = {{"rule", rule}, {"settings", list}},
                     .claims = advice_claims(n)};
}

const StudyRegistration kAdvice{{
    .name = "advice",
    .summary = "the runs `mpmstab advise` predicts from: each setting at other amplitudes, "
               "lengths, boundaries, scenes, layouts and grids",
    .records = {.error_over_time = true},
    .figure = true,
    .follow_up = advice_follow_up,
    .report = advice_report,
    .index = advice_index,
    // "120 settings; 90 run again beyond their base run; 60 whose runs passed to c T/L = 100".
    .figure_subtitle =
        [](const Spec&, const ojson& doc) {
          const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
          const Findings n = find(rows, checked_settings_of(doc));
          return std::to_string(n.cases) + " settings; " + std::to_string(n.checked) +
                 " run again beyond their base run; " + std::to_string(n.to_longest) +
                 " whose runs passed to c T/L = " + value_text(kRegionRule.lengths.back());
        },
}};

}  // namespace
}  // namespace mpmstab::studies::advice
