#include "variants.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "csv.hpp"
#include "paper_table1.hpp"
#include "report_util.hpp"
#include "scenes.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

std::optional<double> median(const std::vector<double>& v) {
  if (v.empty()) return std::nullopt;
  return quantile(v, 0.5);
}

std::string opt_ratio(const std::optional<double>& v) {
  return v ? ratio(*v) : "–";
}

std::string of(int k, int n) {
  return std::to_string(k) + " of " + std::to_string(n);
}

// "4 of 5", "4 of 5, 3 of them meaningless": the cells of a class that agree under a variant.
std::string agree_text(const VariantClassOutcome& o, int n) {
  return of(o.agree, n) +
         (o.meaningless ? ", " + std::to_string(o.meaningless) + " of them meaningless" : "");
}

// "no cell that agrees", "1 cell that agrees", "3 cells that agree" (under the default).
std::string breaking(int n) {
  return (n == 0 ? std::string("no") : std::to_string(n)) +
         (n == 1 || n == 0 ? " cell that agrees" : " cells that agree") + " under the default";
}

std::string cells_word(int n) {
  return std::to_string(n) + (n == 1 ? " cell" : " cells");
}

// A variant's name as the reports show it.
std::string named(const VariantOutcome& v) {
  return "`" + v.name + "`";
}

// The disagreement classes, in report order.
std::vector<const ComparisonClass*> disagreement_classes() {
  std::vector<const ComparisonClass*> out;
  for (const auto& k : comparison_classes()) {
    if (k.kind == ClassKind::verdict || k.kind == ClassKind::error) out.push_back(&k);
  }
  return out;
}

}  // namespace

bool agrees_as(const CellVerdict& v, ClassKind kind) {
  switch (kind) {
    case ClassKind::verdict:
      return v.same_verdict();
    case ClassKind::error:
      return v.cls == "agree-stable";
    case ClassKind::agreement:
      return v.agrees();
    case ClassKind::unreadable:
      return false;
  }
  return false;
}

Accounts accounts_for(const VariantClassOutcome& o, int class_cells) {
  if (o.covered == 0) return Accounts::not_applicable;
  if (o.agree > 0 && 2 * o.agree >= class_cells) return Accounts::yes;
  return o.agree > 0 ? Accounts::partly : Accounts::no;
}

VariantsStudy study_variants(const Spec& spec, const std::vector<ojson>& rows,
                             const std::map<Table1Key, PaperCell>& paper,
                             const CourantEdges& edges) {
  VariantsStudy s;
  auto verdict_of = [&](std::size_t i) {
    const auto it = paper.find(paper_key(spec.cases[i]));
    return classify(rows[i], it == paper.end() ? nullptr : &it->second, edges,
                    spec.cases[i].error_at);
  };
  for (std::size_t j = 0; j < spec.variants.size(); ++j) {
    if (spec.variants[j].baseline) {
      s.baseline = j;
      break;
    }
  }
  // The class of every cell under the default run.
  std::map<Table1Key, CellVerdict> under_default;
  const VariantSpec& base = spec.variants.at(s.baseline);
  for (std::size_t i = base.first_case; i < base.first_case + base.cases; ++i) {
    const CellVerdict v = verdict_of(i);
    ++s.class_cells[v.cls];
    ++s.cells;
    under_default.emplace(paper_key(spec.cases[i]), v);
  }
  for (const VariantSpec& vs : spec.variants) {
    VariantOutcome o;
    o.name = vs.name;
    o.description = vs.description;
    o.change = vs.change;
    o.changes = vs.changes;
    o.baseline = vs.baseline;
    for (std::size_t i = vs.first_case; i < vs.first_case + vs.cases; ++i) {
      const CaseSpec& c = spec.cases[i];
      const std::string column(to_string(c.paper_method));
      const CellVerdict v = verdict_of(i);
      const double wall = rows[i]["wall_seconds"].get<double>();
      auto& m = o.by_method[column];
      ++m.cells;
      m.counts.add(v);
      m.wall_seconds += wall;
      o.wall_seconds += wall;
      ++o.cells;
      if (v.agrees()) ++o.agreeing;
      if (v.error_ratio) o.error_ratios.emplace_back(column, *v.error_ratio);
      const auto d = under_default.find(paper_key(c));
      if (d == under_default.end()) continue;
      const ComparisonClass* k = find_class(d->second.cls);
      auto& co = o.by_class[d->second.cls];
      ++co.covered;
      if (k && agrees_as(v, k->kind)) {
        ++co.agree;
        if (rows[i]["stable"] == true && rows[i]["meaningless"] == true) ++co.meaningless;
      }
      if (d->second.agrees()) {
        ++o.agreeing_under_default;
        if (!v.agrees()) ++o.breaks;
      }
    }
    s.variants.push_back(std::move(o));
  }
  return s;
}

ojson study_to_json(const VariantsStudy& s) {
  ojson j;
  j["criterion"] =
      "a variant accounts for a class when at least half of the class's cells (its class under "
      "the default run) agree with the paper under it: the stability verdict for the verdict "
      "classes, max errors within a factor 3 for the error classes";
  j["default"] = s.variants.at(s.baseline).name;
  j["cells"] = s.cells;
  ojson variants = ojson::array();
  for (const auto& v : s.variants) {
    ojson e;
    e["name"] = v.name;
    e["change"] = v.change;
    e["changes"] = v.changes;
    e["cells"] = v.cells;
    e["agreeing"] = v.agreeing;
    e["agreeing_under_default"] = v.agreeing_under_default;
    e["breaks"] = v.breaks;
    e["wall_seconds"] = v.wall_seconds;
    ojson by_method = ojson::object();
    for (const auto& [column, m] : v.by_method) {
      const auto err = median(m.counts.error_ratios);
      const auto dts = median(m.counts.dt_stable_ratios);
      by_method[column] = {{"cells", m.cells},
                           {"verdicts_agree", m.counts.verdicts_agree},
                           {"verdicts_compared", m.counts.verdicts_compared},
                           {"errors_within_3", m.counts.errors_within},
                           {"errors_compared", m.counts.errors_compared},
                           {"median_error_ratio", err ? ojson(*err) : ojson(nullptr)},
                           {"median_dt_stable_ratio", dts ? ojson(*dts) : ojson(nullptr)},
                           {"wall_seconds", m.wall_seconds}};
    }
    e["by_method"] = by_method;
    variants.push_back(e);
  }
  j["variants"] = variants;
  ojson classes = ojson::object();
  for (const ComparisonClass* k : disagreement_classes()) {
    const auto n_it = s.class_cells.find(k->id);
    const int n = n_it == s.class_cells.end() ? 0 : n_it->second;
    ojson per = ojson::array();
    for (const auto& v : s.variants) {
      const auto it = v.by_class.find(k->id);
      const VariantClassOutcome o = it == v.by_class.end() ? VariantClassOutcome{} : it->second;
      const Accounts a = accounts_for(o, n);
      per.push_back({{"name", v.name},
                     {"changes", v.changes},
                     {"baseline", v.baseline},
                     {"covered", o.covered},
                     {"agree", o.agree},
                     {"meaningless", o.meaningless},
                     {"breaks", v.breaks},
                     {"accounts", a == Accounts::yes              ? "yes"
                                  : a == Accounts::partly         ? "partly"
                                  : a == Accounts::not_applicable ? "not applicable"
                                                                  : "no"}});
    }
    classes[k->id] = {{"title", k->title}, {"cells", n}, {"variants", per}};
  }
  j["classes"] = classes;
  return j;
}

namespace {

// The plain-words reading of one class, generated from the numbers.
std::string class_reading(const VariantsStudy& s, const ComparisonClass& k) {
  const auto n_it = s.class_cells.find(k.id);
  const int n = n_it == s.class_cells.end() ? 0 : n_it->second;
  if (n == 0) return "No cell of Table 1 is in this class under the default run.";
  std::vector<std::string> yes, partly, no, not_run, mostly_meaningless;
  for (const auto& v : s.variants) {
    if (v.baseline) continue;
    const auto it = v.by_class.find(k.id);
    const VariantClassOutcome o = it == v.by_class.end() ? VariantClassOutcome{} : it->second;
    const std::string breaks = v.breaks ? ", breaking " + breaking(v.breaks) : "";
    switch (accounts_for(o, n)) {
      case Accounts::yes:
        yes.push_back(named(v) + " (" + agree_text(o, n) + breaks + ")");
        if (2 * o.meaningless > o.agree) {
          mostly_meaningless.push_back(named(v) + " (" + of(o.meaningless, o.agree) + ")");
        }
        break;
      case Accounts::partly:
        partly.push_back(named(v) + " (" + agree_text(o, n) + breaks + ")");
        break;
      case Accounts::no:
        no.push_back(named(v));
        break;
      case Accounts::not_applicable:
        not_run.push_back(named(v));
        break;
    }
  }
  auto join = [](const std::vector<std::string>& v) {
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out += (i == 0 ? "" : i + 1 == v.size() ? " and " : ", ") + v[i];
    return out;
  };
  const std::string what = k.kind == ClassKind::verdict
                               ? "the paper's stability verdict"
                               : "a max error within a factor 3 of the paper's";
  std::ostringstream md;
  if (!yes.empty()) {
    md << "Can account for this class (at least half of its " << cells_word(n) << " reach " << what
       << "): " << join(yes) << ". ";
    if (!mostly_meaningless.empty()) {
      md << "But most of the runs that survive under " << join(mostly_meaningless)
         << " are meaningless (their error over time reached A): they match the paper's verdict, "
            "not an answer of the size of its Max Error. ";
    }
  } else {
    md << "No variant accounts for this class: none brings half of its " << cells_word(n) << " to "
       << what << ". ";
  }
  if (!partly.empty()) md << "Partly (some, fewer than half): " << join(partly) << ". ";
  if (!no.empty())
    md << "Cannot account for it (no cell reaches " << what << "): " << join(no) << ". ";
  if (!not_run.empty()) md << "Not applicable (ran none of its cells): " << join(not_run) << ".";
  std::string text = md.str();
  while (!text.empty() && text.back() == ' ')
    text.pop_back();
  return text;
}

std::string method_title(const std::string& column) {
  return column == "mpm" ? "MPM" : column == "gimp" ? "GIMP" : column;
}

}  // namespace

std::string variants_markdown(const Spec& spec, const VariantsStudy& s, bool have_courant) {
  std::ostringstream md;
  const VariantOutcome& def = s.variants.at(s.baseline);
  md << "## Results\n\n";

  // The reading, computed.
  md << "**Reading** (computed from the rows). Under the default, " << of(def.agreeing, def.cells)
     << " cells agree fully with the paper (the same stability verdict and, where both are "
        "stable, max errors within a factor 3). ";
  const VariantOutcome* gain = nullptr;
  for (const auto& v : s.variants) {
    if (v.baseline) continue;
    const int g = v.agreeing - v.agreeing_under_default;
    if (!gain || g > gain->agreeing - gain->agreeing_under_default) gain = &v;
  }
  if (gain) {
    const int g = gain->agreeing - gain->agreeing_under_default;
    if (g > 0) {
      md << "The largest net gain over the default is " << named(*gain) << " (" << gain->change
         << "): " << gain->agreeing << " of its " << gain->cells << " cells agree, against "
         << gain->agreeing_under_default << " under the default (" << gain->breaks << " broken). ";
    } else {
      md << "No variant raises the number of cells in full agreement above the default's. ";
    }
  }
  std::vector<std::string> unchanged;
  for (const auto& v : s.variants) {
    if (v.baseline) continue;
    bool same = true;
    for (const auto& [cls, o] : v.by_class) {
      const ComparisonClass* k = find_class(cls);
      if (k && k->kind == ClassKind::agreement && o.agree != o.covered) same = false;
      if (k && k->kind != ClassKind::agreement && o.agree != 0) same = false;
    }
    if (same) unchanged.push_back(named(v));
  }
  if (!unchanged.empty()) {
    md << "Neither fixing nor breaking any cell: ";
    for (std::size_t i = 0; i < unchanged.size(); ++i)
      md << (i == 0 ? "" : i + 1 == unchanged.size() ? " and " : ", ") << unchanged[i];
    md << ". ";
  }
  std::vector<std::string> accounted, not_accounted;
  for (const ComparisonClass* k : disagreement_classes()) {
    const auto n_it = s.class_cells.find(k->id);
    if (n_it == s.class_cells.end() || n_it->second == 0) continue;
    std::string by;
    for (const auto& v : s.variants) {
      const auto it = v.by_class.find(k->id);
      if (!v.baseline && it != v.by_class.end() &&
          accounts_for(it->second, n_it->second) == Accounts::yes) {
        by += (by.empty() ? "" : ", ") + named(v);
      }
    }
    std::string cls = "[";
    cls.append(k->id).append("](#").append(k->id).append(")");
    if (by.empty()) {
      not_accounted.push_back(cls);
    } else {
      accounted.push_back(cls + " by " + by);
    }
  }
  auto list_of = [](const std::vector<std::string>& v) {
    std::string out;
    for (std::size_t i = 0; i < v.size(); ++i)
      out += (i == 0 ? "" : "; ") + v[i];
    return out.empty() ? std::string("none") : out;
  };
  md << "Classes of disagreement that a variant accounts for (criterion below): "
     << list_of(accounted) << ". Classes that none accounts for: " << list_of(not_accounted)
     << ".\n\n";

  md << "**How the cells are read.** Every row is compared with the paper cell of its base case "
        "by the rules of [comparison.md](comparison.md): the stability verdict (the paper's `*` "
        "against ours), and where both are stable the max error within a factor 3 (the "
        "comparator's rule |a − b| <= (2/3) max(|a|, |b|), `core/compare.hpp`). Cells whose "
        "paper value is unreadable are not compared. A variant that changes the method (cpGIMP) "
        "is still compared with the paper's GIMP column. Our error is the max error at T unless "
        "the variant's `error_at` says otherwise. Medians are over the cells where both are "
        "stable (max error) or where ours is stable and the paper prints dt_stable. Wall time: "
        "the sum of the wall times of the variant's runs; runs with the same parameters in two "
        "variants (the `error_at` variant and the default, for example) are computed once and "
        "counted in both. A cell's class is its class in comparison.md, that is under the "
        "default run"
     << (have_courant ? ""
                      : " (the Courant scan, courant.json, was not available: the class "
                        "above-our-edge could not be told apart)")
     << ". Variants were chosen before any was run; none is tuned to a cell.\n\n";
  md << "![" << spec.title << "](" << spec.name << ".png)\n\nVector version: [" << spec.name
     << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv](" << spec.name
     << "_data.csv).\n\n";

  md << "### Every variant\n\n"
        "| variant | change | what it is | cells in full agreement | agreeing under the default "
        "that it breaks | wall time |\n|---|---|---|---|---|---|\n";
  for (const auto& v : s.variants) {
    md << "| " << named(v) << " | " << v.change << " | " << v.description << " | "
       << of(v.agreeing, v.cells) << " | " << of(v.breaks, v.agreeing_under_default) << " | "
       << seconds(v.wall_seconds) << " |\n";
  }
  md << "\n### Per variant and method\n\nVerdicts: cells whose stability verdict agrees with the "
        "paper's, of the cells with a readable paper value. Within 3x: of the cells where both "
        "are stable. Ratios are ours / paper.\n\n"
        "| variant | method | cells | verdicts agree | max error within 3x | median max error "
        "ratio | median dt_stable ratio | wall time |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& v : s.variants) {
    for (const char* column : {"mpm", "gimp"}) {
      const auto it = v.by_method.find(column);
      if (it == v.by_method.end()) continue;
      const auto& m = it->second;
      md << "| " << named(v) << " | " << method_title(column) << " | " << m.cells << " | "
         << of(m.counts.verdicts_agree, m.counts.verdicts_compared) << " | "
         << of(m.counts.errors_within, m.counts.errors_compared) << " | "
         << opt_ratio(median(m.counts.error_ratios)) << " | "
         << opt_ratio(median(m.counts.dt_stable_ratios)) << " | " << seconds(m.wall_seconds)
         << " |\n";
    }
  }

  md << "\n## What can account for each class of disagreement\n\n"
        "For each class of [comparison.md](comparison.md) and each variant: how many of the "
        "class's cells agree with the paper under the variant (for the classes where the "
        "stability verdicts differ: the verdict; for the classes where both are stable: the max "
        "error within a factor 3), and how many cells that agree fully under the default it "
        "breaks (over all its cells). **Criterion:** a variant *accounts* for a class when at "
        "least half of the class's cells agree under it, and *partly* accounts when it brings "
        "some, but fewer than half, into agreement. As in comparison.md, a run that reaches T is "
        "stable even when its error over time reached A; such runs are counted as *meaningless* "
        "beside the agreeing cells. The sentences below are generated from the tables.\n\n";
  for (const ComparisonClass* k : disagreement_classes()) {
    const auto n_it = s.class_cells.find(k->id);
    const int n = n_it == s.class_cells.end() ? 0 : n_it->second;
    md << "<a id=\"" << k->id << "\"></a>\n### " << k->title << " (" << cells_word(n) << ")\n\n"
       << "Cells listed in [comparison.md](comparison.md#" << k->id << ").\n\n";
    if (n > 0) {
      md << "| variant | change | cells run | agree with the paper | breaks |\n"
            "|---|---|---|---|---|\n";
      for (const auto& v : s.variants) {
        if (v.baseline) continue;
        const auto it = v.by_class.find(k->id);
        const VariantClassOutcome o = it == v.by_class.end() ? VariantClassOutcome{} : it->second;
        md << "| " << named(v) << " | " << v.change << " | " << o.covered << " | "
           << (o.covered ? agree_text(o, o.covered) : std::string("–")) << " | " << v.breaks
           << " |\n";
      }
      md << "\n";
    }
    md << class_reading(s, *k) << "\n\n";
  }
  return md.str();
}

std::string variants_data_csv(const VariantsStudy& s, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines
      << "# x: the variant's position; method: 0 mpm, 1 gimp; kind: 0 one cell (both stable), 1 "
         "the median of the variant's cells, 2 the tic of the variant (ratio 1, not drawn)\n"
         "x,method,kind,ratio,variant\n";
  for (std::size_t j = 0; j < s.variants.size(); ++j) {
    const auto& v = s.variants[j];
    for (const auto& [column, r] : v.error_ratios) {
      csv << j + 1 << ',' << (column == "mpm" ? 0 : 1) << ",0," << shortest(r) << ',' << v.name
          << "\n";
    }
    for (const auto& [column, m] : v.by_method) {
      if (const auto med = median(m.counts.error_ratios)) {
        csv << j + 1 << ',' << (column == "mpm" ? 0 : 1) << ",1," << shortest(*med) << ',' << v.name
            << "\n";
      }
    }
  }
  // The tics last: gnuplot keeps the last label given at a position.
  for (std::size_t j = 0; j < s.variants.size(); ++j)
    csv << j + 1 << ",1,2,1," << s.variants[j].name << "\n";
  return csv.str();
}

std::string variants_line(const ojson& study, const std::string& class_id,
                          const std::string& report_link) {
  if (!study.contains("classes") || !study["classes"].contains(class_id)) return "";
  const ojson& c = study["classes"][class_id];
  const int n = c["cells"].get<int>();
  const std::string anchor = report_link + "#" + class_id;
  std::ostringstream md;
  md << "**Implementation choices** ([" << anchor << "](" << anchor << ")): ";
  if (n == 0) {
    md << "no cell in this class.\n\n";
    return md.str();
  }
  auto best = [&](int changes) -> const ojson* {
    const ojson* b = nullptr;
    for (const auto& v : c["variants"]) {
      if (v["baseline"] == true || v["changes"].get<int>() != changes || v["covered"] == 0)
        continue;
      if (!b || v["agree"].get<int>() > (*b)["agree"].get<int>() ||
          (v["agree"] == (*b)["agree"] && v["breaks"].get<int>() < (*b)["breaks"].get<int>())) {
        b = &v;
      }
    }
    return b;
  };
  auto describe = [&](const char* what, const char* none, const ojson* v) {
    if (!v) return std::string(what) + ": none ran these cells";
    const int agree = (*v)["agree"].get<int>();
    if (agree == 0)
      return std::string(none) + " brings any of its " + cells_word(n) + " into agreement";
    const int meaningless = (*v)["meaningless"].get<int>();
    return std::string(what) + ": `" + (*v)["name"].get<std::string>() + "`, " + of(agree, n) +
           " cells agree" +
           (meaningless ? " (" + std::to_string(meaningless) + " of them meaningless)" : "") +
           ", breaking " + breaking((*v)["breaks"].get<int>());
  };
  md << describe("best single change", "no single change", best(1)) << "; "
     << describe("best pair", "no pair", best(2)) << ". ";
  std::string yes;
  for (const auto& v : c["variants"]) {
    if (v["accounts"] == "yes")
      yes += (yes.empty() ? "`" : ", `") + v["name"].get<std::string>() + "`";
  }
  md << "Accounting for the class (at least half its cells agree): "
     << (yes.empty() ? std::string("none of the variants") : yes) << ".\n\n";
  return md.str();
}

namespace {

// The variants study reads the courant scan (for the class above-our-edge) when it has been run
// into the same folder.
StudyReport variants_report(const ReportContext& c) {
  CourantEdges edges;
  const StudyInput& courant = c.inputs.at("courant");
  if (courant.present()) {
    edges =
        courant_edges(std::vector<ojson>(courant.doc["cases"].begin(), courant.doc["cases"].end()));
  }
  const VariantsStudy study = study_variants(c.spec, c.rows, read_paper_table1(c.spec), edges);
  return StudyReport{.markdown = variants_markdown(c.spec, study, courant.present()),
                     .data_csv = variants_data_csv(study, c.csv_header),
                     .json = study_to_json(study)};
}

std::string variants_index(const Spec& spec, const std::vector<ojson>&) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** "
     << spec.variants.size()
     << " variants of Table 1's cells, each a documented implementation choice (or a pair) "
        "changed from the default; per variant and method the agreement with the paper and "
        "the cost, and which choices can or cannot account for each class of disagreement: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kVariants{{
    .name = "variants",
    .summary = "Table 1's cells under documented implementation choices, against the paper",
    .needs_reference = true,
    .takes_variants = true,
    .records = {.error_over_time = true, .dt_stable = true},
    .study_columns = true,
    .inputs = {{.name = "courant"}},
    .figure = true,
    .report = variants_report,
    .index = variants_index,
    .figure_subtitle = [](const Spec& spec,
                          const ojson& doc) { return first_scene_subtitle(spec.name, doc); },
}};

}  // namespace

}  // namespace mpmstab
