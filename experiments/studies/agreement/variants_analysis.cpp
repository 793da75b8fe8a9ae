// The variants study's numbers: every cell of every variant read against the paper by the
// comparison's rules, tallied per column of the paper and per class of disagreement, and the
// same tallies as the "study" object of variants.json.
#include <optional>

#include "agreement/variants.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "shared/paper_table1.hpp"

namespace mpmstab {

namespace studies::variants_analysis {
namespace {

using ojson = nlohmann::ordered_json;

// The comparison's verdict on row i of a variants spec: the row against the paper cell of its
// base case.
struct CellReader {
  const Spec& spec;
  const std::vector<ojson>& rows;
  const std::map<Table1Key, PaperCell>& paper;
  const CourantEdges& edges;

  CellVerdict operator()(std::size_t i) const {
    const auto it = paper.find(paper_key(spec.cases[i]));
    return classify(rows[i], it == paper.end() ? nullptr : &it->second, edges,
                    spec.cases[i].error_at);
  }
};

// The index of the default variant (the first marked baseline; 0 when none is).
std::size_t baseline_index(const Spec& spec) {
  for (std::size_t j = 0; j < spec.variants.size(); ++j)
    if (spec.variants[j].baseline) return j;
  return 0;
}

// Whether a cell of a class agrees with the paper in the sense of that class: the stability
// verdict for the verdict classes, max errors within a factor 3 for the error classes, and full
// agreement for the agreement classes.
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

// Adds case i to a variant's tallies: per column of the paper, per class of its cell under the
// default run, and whether it breaks a cell that agrees under the default.
void tally_case(VariantOutcome& o, const CellReader& read, std::size_t i,
                const std::map<Table1Key, CellVerdict>& under_default) {
  const CaseSpec& c = read.spec.cases[i];
  const ojson& row = read.rows[i];
  const std::string column(to_string(c.paper_method));
  const CellVerdict v = read(i);
  const double work = particle_steps(row);
  auto& m = o.by_method[column];
  ++m.cells;
  m.counts.add(v);
  m.particle_steps += work;
  o.particle_steps += work;
  ++o.cells;
  if (v.agrees()) ++o.agreeing;
  if (v.error_ratio) o.error_ratios.emplace_back(column, *v.error_ratio);
  const auto d = under_default.find(paper_key(c));
  if (d == under_default.end()) return;
  const ComparisonClass* k = find_class(d->second.cls);
  auto& co = o.by_class[d->second.cls];
  ++co.covered;
  if (k && agrees_as(v, k->kind)) {
    ++co.verdict_agree;
    if (outcome(row) == "meaningless") ++co.meaningless;
    if (v.error_ratio) co.error_ratios.push_back(*v.error_ratio);
    co.agree += v.agrees();
    if (const RunRow run(row); v.agrees() && run.outcome == "stable" && run.accuracy()) {
      co.agreeing_error_over_A.push_back(*run.error_over_A());
      co.agreeing_not_accurate += *run.accuracy() != Accuracy::accurate;
    }
  }
  if (d->second.agrees()) {
    ++o.agreeing_under_default;
    if (!v.agrees()) ++o.breaks;
  }
}

// One variant's outcome over the cells it ran.
VariantOutcome variant_outcome(const VariantSpec& vs, const CellReader& read,
                               const std::map<Table1Key, CellVerdict>& under_default) {
  VariantOutcome o;
  o.name = vs.name;
  o.description = vs.description;
  o.change = vs.change;
  o.changes = vs.changes;
  o.baseline = vs.baseline;
  for (std::size_t i = vs.first_case; i < vs.first_case + vs.cases; ++i)
    tally_case(o, read, i, under_default);
  return o;
}

// The median of a list of ratios, none when it is empty.
std::optional<double> median_ratio(const std::vector<double>& ratios) {
  if (ratios.empty()) return std::nullopt;
  return quantile(ratios, 0.5);
}

// What the reading and the figure say, from the tallies: the medians, each variant's verdict
// per class, the variant of the largest net gain, those that change nothing, the runs drawn.
void conclude(VariantsStudy& s) {
  auto gain = [](const VariantOutcome& v) { return v.agreeing - v.agreeing_under_default; };
  for (std::size_t j = 0; j < s.variants.size(); ++j) {
    VariantOutcome& v = s.variants[j];
    for (auto& [column, m] : v.by_method) {
      m.median_error_ratio = median_ratio(m.counts.error_ratios);
      m.median_dt_stable_ratio = median_ratio(m.counts.dt_stable_ratios);
      s.drawn += m.counts.errors_compared;
    }
    bool same = true;  // every cell of an agreement class still agrees, none of another does
    for (auto& [cls, o] : v.by_class) {
      o.accounts = accounts_for(o, class_cell_count(s, cls));
      o.mostly_meaningless = 2 * o.meaningless > o.verdict_agree;
      const ComparisonClass* k = find_class(cls);
      if (k && k->kind == ClassKind::agreement && o.agree != o.covered) same = false;
      if (k && k->kind != ClassKind::agreement && o.agree != 0) same = false;
    }
    if (v.baseline) continue;
    if (same) s.unchanged.push_back(j);
    if (!s.largest_gain || gain(v) > gain(s.variants[*s.largest_gain])) s.largest_gain = j;
  }
}

// One variant's totals and its per-column agreement with the paper.
ojson variant_json(const VariantOutcome& v) {
  ojson e;
  e["name"] = v.name;
  e["change"] = v.change;
  e["changes"] = v.changes;
  e["cells"] = v.cells;
  e["agreeing"] = v.agreeing;
  e["agreeing_under_default"] = v.agreeing_under_default;
  e["breaks"] = v.breaks;
  e["particle_steps"] = v.particle_steps;
  ojson by_method = ojson::object();
  for (const auto& [column, m] : v.by_method) {
    const auto& err = m.median_error_ratio;
    const auto& dts = m.median_dt_stable_ratio;
    by_method[column] = {{"cells", m.cells},
                         {"verdicts_agree", m.counts.verdicts_agree},
                         {"verdicts_compared", m.counts.verdicts_compared},
                         {"errors_within_factor", m.counts.errors_within},
                         {"errors_compared", m.counts.errors_compared},
                         {"median_error_ratio", err ? ojson(*err) : ojson(nullptr)},
                         {"median_dt_stable_ratio", dts ? ojson(*dts) : ojson(nullptr)},
                         {"particle_steps", m.particle_steps}};
  }
  e["by_method"] = by_method;
  return e;
}

// One class of disagreement: its cells and what every variant makes of them.
ojson class_json(const VariantsStudy& s, const ComparisonClass& k) {
  const int n = class_cell_count(s, k.id);
  ojson per = ojson::array();
  for (const auto& v : s.variants) {
    const VariantClassOutcome o = class_outcome(v, k.id);
    per.push_back({{"name", v.name},
                   {"changes", v.changes},
                   {"baseline", v.baseline},
                   {"covered", o.covered},
                   {"agree", o.agree},
                   {"verdict_agree", o.verdict_agree},
                   {"meaningless", o.meaningless},
                   {"breaks", v.breaks},
                   {"accounts", o.accounts == Accounts::yes              ? "yes"
                                : o.accounts == Accounts::partly         ? "partly"
                                : o.accounts == Accounts::not_applicable ? "not applicable"
                                                                         : "no"}});
  }
  return {{"title", k.title}, {"cells", n}, {"variants", per}};
}

}  // namespace
}  // namespace studies::variants_analysis

std::vector<const ComparisonClass*> variants_disagreement_classes() {
  std::vector<const ComparisonClass*> out;
  for (const auto& k : comparison_classes())
    if (k.kind == ClassKind::verdict || k.kind == ClassKind::error) out.push_back(&k);
  return out;
}

int class_cell_count(const VariantsStudy& s, const std::string& class_id) {
  const auto it = s.class_cells.find(class_id);
  return it == s.class_cells.end() ? 0 : it->second;
}

VariantClassOutcome class_outcome(const VariantOutcome& v, const std::string& class_id) {
  const auto it = v.by_class.find(class_id);
  return it == v.by_class.end() ? VariantClassOutcome{} : it->second;
}

Accounts accounts_for(const VariantClassOutcome& o, int class_cells) {
  if (o.covered == 0) return Accounts::not_applicable;
  if (o.agree > 0 && 2 * o.agree >= class_cells) return Accounts::yes;
  return o.agree > 0 ? Accounts::partly : Accounts::no;
}

VariantsStudy study_variants(const Spec& spec, const std::vector<nlohmann::ordered_json>& rows,
                             const std::map<Table1Key, PaperCell>& paper,
                             const CourantEdges& edges) {
  using namespace studies::variants_analysis;
  const CellReader read{spec, rows, paper, edges};
  VariantsStudy s;
  s.baseline = baseline_index(spec);
  // The class of every cell under the default run.
  std::map<Table1Key, CellVerdict> under_default;
  const VariantSpec& base = spec.variants.at(s.baseline);
  for (std::size_t i = base.first_case; i < base.first_case + base.cases; ++i) {
    const CellVerdict v = read(i);
    ++s.class_cells[v.cls];
    ++s.cells;
    under_default.emplace(paper_key(spec.cases[i]), v);
  }
  for (const VariantSpec& vs : spec.variants)
    s.variants.push_back(variant_outcome(vs, read, under_default));
  s.runs = rows.size();
  conclude(s);
  return s;
}

nlohmann::ordered_json study_to_json(const VariantsStudy& s) {
  using namespace studies::variants_analysis;
  nlohmann::ordered_json j;
  j["criterion"] =
      "a variant accounts for a class when at least half of the class's cells (its class under "
      "the default run) agree with the paper under it: the stability verdict for the verdict "
      "classes, max errors within a factor " +
      agreement_factor() + " for the error classes";
  j["default"] = s.variants.at(s.baseline).name;
  j["cells"] = s.cells;
  nlohmann::ordered_json variants = nlohmann::ordered_json::array();
  for (const auto& v : s.variants)
    variants.push_back(variant_json(v));
  j["variants"] = variants;
  nlohmann::ordered_json classes = nlohmann::ordered_json::object();
  for (const ComparisonClass* k : variants_disagreement_classes())
    classes[k->id] = class_json(s, *k);
  j["classes"] = classes;
  return j;
}

}  // namespace mpmstab
