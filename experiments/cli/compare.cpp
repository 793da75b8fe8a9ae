// `mpmstab compare`: the comparison with the paper, a study without cases of its own, from the
// results of the experiments it reads.
#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "report.hpp"
#include "study.hpp"

namespace mpmstab::cli {

namespace {

// The study this command writes.
constexpr std::string_view kStudy = "comparison";

int derive(const Spec& derived, const std::filesystem::path& out,
           const nlohmann::ordered_json& options) {
  try {
    write_derived_reports(derived, out, options);  // reads every input before it writes
  } catch (const MissingInput& e) {
    throw UsageError(e.what());
  }
  return 0;
}

}  // namespace

int cmd_compare(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"out"}, {"error-at"}, {"help", false}});
  if (args.flag("help")) {
    std::cout
        << "Usage: mpmstab compare <comparison spec> [--out DIR] [--error-at T|max_over_time]\n"
           "       mpmstab compare <table1 spec> [<supporting spec>...] [--out DIR] [...]\n\n"
           "Writes DIR/comparison.md and DIR/comparison.csv: every Table 1 cell against the "
           "paper,\nwith its verdict, its class of disagreement and the supporting experiments "
           "read from\nDIR/<name>.json. The comparison spec (experiments/comparison.json) "
           "names them as its\ninputs, each of which must have been run: table1, peers, "
           "courant, walls, crossing,\neq108, fig1, fig2, fig3, fig2_variants and "
           "fig3_variants. In the second form the inputs\nare the specs given, the first "
           "being the one compared with the paper; a section whose\nexperiment is not among "
           "them says so. `mpmstab sweep <comparison spec>` writes the same\nfiles.\n\n"
           "Options:\n"
           "  --out DIR       folder of the results and of the comparison (default results)\n"
           "  --error-at X    which of our errors is compared with the paper's \"Max Error\": "
           "T, the max\n"
           "                  error at the final time (max_error, the default), or "
           "max_over_time, the\n"
           "                  largest over the run (max_error_over_time, which every run "
           "records).\n"
           "                  Without it, each case's error_at in the spec decides (default "
           "T).\n";
    return 0;
  }
  nlohmann::ordered_json options = nlohmann::ordered_json::object();
  if (auto v = args.value("error-at")) {
    const auto error_at = parse_error_at(*v);
    if (!error_at) {
      throw UsageError("--error-at: unknown value '" + std::string(*v) +
                       "' (expected T or max_over_time)");
    }
    options["error_at"] = std::string(to_string(*error_at));
  }
  auto specs = load_specs(args.positional());
  const auto out = output_folder(args);
  // The comparison's own spec, or (as before it had one) the specs of its inputs, the experiment
  // compared with the paper first.
  if (specs.size() == 1 && !specs.front().study->has_cases) {
    const Spec& derived = specs.front();
    return derive(derived, out, options);
  }
  const Study* study = find_study(kStudy);
  const std::string& first = study->inputs.front().name;
  if (specs.front().study->name != first) {
    throw UsageError(specs.front().path.string() + ": the first spec must be a " + first + " spec");
  }
  std::vector<std::string> roles = {first};
  for (std::size_t i = 1; i < specs.size(); ++i)
    roles.push_back(specs[i].name);
  // Only the inputs given are read: a section whose experiment is not among them says so.
  Spec derived;
  derived.name = study->name;
  derived.study = study;
  try {
    write_derived_reports(derived, roles, specs, out, options);
  } catch (const MissingInput& e) {
    throw UsageError(e.what());
  }
  return 0;
}

}  // namespace mpmstab::cli
