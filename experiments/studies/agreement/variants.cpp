// The variants study's registration: its report reads the courant scan when it has been run.
// The numbers are computed in variants_analysis.cpp, the report written in variants_report.cpp.
#include <sstream>

#include "agreement/variants.hpp"
#include "shared/paper_table1.hpp"
#include "study.hpp"

namespace mpmstab::studies::variants {
namespace {

using ojson = nlohmann::ordered_json;

// The findings from the rows; the courant scan, an input of the report only, tells apart the
// failure classes (above-our-edge), which neither the index nor the subtitle prints.
Findings find(const Spec& spec, const std::vector<ojson>& rows, const CourantEdges& edges = {}) {
  return study_variants(spec, rows, read_paper_table1(spec), edges);
}

// The variants study reads the courant scan (for the class above-our-edge) when it has been run
// into the same folder.
StudyReport variants_report(const ReportContext& c) {
  const StudyInput& courant = c.inputs.at("courant");
  const CourantEdges edges = courant.present()
                                 ? courant_edges(std::vector<ojson>(courant.doc["cases"].begin(),
                                                                    courant.doc["cases"].end()))
                                 : CourantEdges{};
  const Findings f = find(c.spec, c.rows, edges);
  return StudyReport{.markdown = variants_markdown(c.spec, f, courant.present()),
                     .data_csv = variants_data_csv(f, c.csv_header),
                     .json = study_to_json(f)};
}

std::string variants_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** "
     << find(spec, rows).variants.size()
     << " variants of Table 1's cells, each a documented implementation choice (or a pair) "
        "changed from the default; per variant and method the agreement with the paper and "
        "the cost, and which choices can or cannot account for each class of disagreement: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

// The figure draws one point per cell where both the paper and the variant's run are stable and
// the paper's error is readable (kind 0 rows of the data file), and a median per variant and
// method; its subtitle says which cells it selects, why, and where the others are.
std::string variants_subtitle(const Spec& spec, const ojson& doc) {
  const Findings f = find(spec, std::vector<ojson>(doc["cases"].begin(), doc["cases"].end()));
  return "Drawn: the " + std::to_string(f.drawn) + " of " + std::to_string(f.runs) + " runs (" +
         std::to_string(f.variants.size()) +
         " variants of the Table 1 cells) where the paper and our run are both stable and the "
         "paper's error is readable, since a ratio needs two errors; the other " +
         std::to_string(f.runs - f.drawn) + " are compared by verdict in " + spec.name + ".md";
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
}  // namespace mpmstab::studies::variants
