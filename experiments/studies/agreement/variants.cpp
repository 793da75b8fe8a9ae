// The variants study's registration: its report reads the courant scan when it has been run.
// The numbers are computed in variants_analysis.cpp, the report written in variants_report.cpp.
#include <sstream>

#include "agreement/variants.hpp"
#include "shared/paper_table1.hpp"
#include "study.hpp"

namespace mpmstab {

namespace studies::variants {
namespace {

using ojson = nlohmann::ordered_json;

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

// The figure draws one point per cell where both the paper and the variant's run are stable and
// the paper's error is readable (kind 0 rows of the data file, counted in the study JSON), and a
// median per variant and method; its subtitle says which cells it selects, why, and where the
// others are.
std::string variants_subtitle(const Spec& spec, const ojson& doc) {
  std::size_t drawn = 0, variants = 0;
  if (doc.contains("study") && doc["study"].contains("variants")) {
    for (const auto& v : doc["study"]["variants"]) {
      ++variants;
      for (const auto& [column, m] : v["by_method"].items())
        drawn += m["errors_compared"].get<std::size_t>();
    }
  }
  const std::size_t runs = doc["cases"].size();
  std::string s = "Drawn: the " + std::to_string(drawn) + " of " + std::to_string(runs) +
                  " runs (" + std::to_string(variants) +
                  " variants of the Table 1 cells) where the paper and our run are both stable "
                  "and the paper's error is readable, since a ratio needs two errors; the other " +
                  std::to_string(runs - drawn) + " are compared by verdict in " + spec.name + ".md";
  return s;
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
    .figure_subtitle = variants_subtitle,
}};

}  // namespace
}  // namespace studies::variants

}  // namespace mpmstab
