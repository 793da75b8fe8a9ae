// A figure: one run whose history or final state a gnuplot script draws.
#include <sstream>

#include "base/params.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"
#include "sweep.hpp"

namespace mpmstab::studies::figure {
namespace {

using ojson = nlohmann::ordered_json;

// The figure, then the run in one table row: its parameters, verdict, errors and cost.
std::string figure_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  const ojson& r = rows.front();
  const auto& p = spec.cases.front().params;
  std::ostringstream md;
  md << "## Results\n\n![" << spec.title << "](" << spec.name << ".png)\n\n";
  md << "Vector version: [" << spec.name << ".svg](" << spec.name << ".svg); data: [" << spec.name
     << "_data.csv](" << spec.name << "_data.csv).\n\n";
  md << "| method | E | A | dt | c dt/h | steps | verdict | max error at end | max error over "
        "time | dt_stable min | crossings | particle-steps "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  md << "| " << to_string(p.method) << " | " << shortest(p.E) << " | " << shortest(p.A) << " | "
     << param(p.dt) << " | " << sci(RunRow(r).courant.value()) << " | " << r["steps"].dump()
     << " of " << *step_count(p.T, p.dt) << " | " << verdict(r) << " | " << opt_sci(r["max_error"])
     << " | " << opt_sci(RunRow(r).error_over_time) << " | " << opt_sci(r["dt_stable_min"]) << " | "
     << (r["crossings"].is_null() ? std::string("–") : r["crossings"].dump()) << " | " << work(r)
     << " |\n";
  return md.str();
}

std::string figure_data_csv(const ojson& record, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines;
  auto cell = [](const ojson& v) {
    return v.is_null() ? std::string() : shortest(v.get<double>());
  };
  if (record.contains("final_state")) {
    const ojson& f = record["final_state"];
    csv << "# particle state at t = " << shortest(f["time"].get<double>()) << "\n";
    csv << "X,x,u,u_exact,v,v_exact,sigma,sigma_exact\n";
    for (std::size_t i = 0; i < f["X"].size(); ++i) {
      const ojson& x = f["x"][i];
      const std::string u =
          x.is_null() ? std::string() : shortest(x.get<double>() - f["X"][i].get<double>());
      csv << cell(f["X"][i]) << ',' << cell(x) << ',' << u << ',' << cell(f["u_exact"][i]) << ','
          << cell(f["v"][i]) << ',' << cell(f["v_exact"][i]) << ',' << cell(f["sigma"][i]) << ','
          << cell(f["sigma_exact"][i]) << '\n';
    }
  } else if (record.contains("history")) {
    csv << "step,time,error,dt_stable,crossings\n";
    for (const auto& h : record["history"])
      csv << h["step"].dump() << ',' << cell(h["time"]) << ',' << cell(h["error"]) << ','
          << cell(h["dt_stable"]) << ',' << (h["crossings"].is_null() ? "" : h["crossings"].dump())
          << '\n';
  }
  return csv.str();
}

std::string figure_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const ojson& r = rows.front();
  return "![" + spec.title + "](" + spec.name + ".png)\n\n**What it shows.** This run " +
         (survived(r) ? "reached T" : "did not reach T") + ": " + verdict(r) + "; " +
         r["steps"].dump() + " steps, max error over time " + opt_sci(RunRow(r).error_over_time) +
         ", eq. (108) minimum " + opt_sci(r["dt_stable_min"]) +
         " against dt = " + param(r["dt"].get<double>()) + ". Details: [" + spec.name + ".md](" +
         spec.name + ".md).\n\n";
}

// What the data file holds: the rows drawn (history steps or particles), for the title, and the
// history of a history figure.
ojson figure_json(const ojson& record) {
  if (record.contains("final_state"))
    return {{"drawn", record["final_state"]["X"].size()}, {"drawn_what", "particles"}};
  // The history itself too: other studies (the comparison with the paper's figures) read it.
  if (record.contains("history"))
    return {{"drawn", record["history"].size()},
            {"drawn_what", "recorded steps"},
            {"history", record["history"]}};
  return {{"drawn", 0}, {"drawn_what", "rows"}};
}

// The run in one line under the figure's title, with what the figure draws.
std::string figure_subtitle(const Spec&, const ojson& doc) {
  const auto& c = doc["cases"][0];
  std::string drawn;
  if (doc.contains("study"))
    drawn = doc["study"]["drawn"].dump() + " " + doc["study"]["drawn_what"].get<std::string>() +
            " drawn; ";
  std::string subtitle = RunRow(c).method + ", E = " + shortest(c["E"].get<double>()) +
                         ", A = " + shortest(c["A"].get<double>()) +
                         ", dt = " + shortest(c["dt"].get<double>()) + ", " + c["cells"].dump() +
                         " cells x " + c["ppc"].dump() + " ppc, " + c["bc"].get<std::string>() +
                         "; " + drawn;
  const RunRow run(c);
  if (run.outcome == "unstable") {
    return subtitle + "unstable: " + run.failure_reason.value_or("") + " at step " +
           c["failure_step"].dump();
  }
  if (run.under_a_wave_pass()) return subtitle + under_a_wave_pass_word(*run.wave_passes);
  return subtitle + (run.outcome == "meaningless" ? "meaningless: survived to T, error reached A"
                                                  : "stable to T");
}

const StudyRegistration kFigure{{
    .name = "figure",
    .summary = "one run whose history or final state a gnuplot script draws",
    .one_case = true,
    .records = {.error_over_time = true},
    .figure = true,
    .report =
        [](const ReportContext& c) {
          const ojson& record = c.outcome.records.front();
          return StudyReport{.markdown = figure_markdown(c.spec, c.rows),
                             .data_csv = figure_data_csv(record, c.csv_header),
                             .json = figure_json(record)};
        },
    .index = figure_index,
    .figure_subtitle = figure_subtitle,
    .figure_dt = [](const ojson& doc) { return shortest(doc["cases"][0]["dt"].get<double>()); },
}};

}  // namespace
}  // namespace mpmstab::studies::figure
