// `mpmstab check` and `mpmstab bless`: the regression gate (engine/regression.hpp).
#include <cmath>
#include <iostream>

#include "commands.hpp"
#include "regression.hpp"

namespace mpmstab::cli {

namespace {

const std::vector<OptionSpec> kRegressionOptions = {
    {"reference"}, {"results"}, {"jobs"}, {"rtol"}, {"budget"}, {"reason"}, {"help", false}};

constexpr const char* kCheckHelp = R"(Usage: mpmstab check <spec.json>... [options]
       mpmstab bless <spec.json>... --reason "..." [options]

check reruns the fast subset of every given experiment (its cases needing at most its spec's
check_budget, or --budget, particle-steps, computed afresh, never from the cache), compares
them with the blessed values in --reference (<name>.csv), and compares the tables a study
declares as blessed outputs (the comparison's verdicts, --results/comparison.csv) with their
blessed expectations (<name>_verdicts.csv). Every failing cell is printed with its parameters, the column,
the expected and obtained values, the relative difference and the tolerance. Exit status 1
when anything differs.

bless rewrites the blessed values that changed and appends the date, the commit, the reason
and, per blessed table, how many rows and values changed to --reference/BLESSED.md. It refuses
to run without a reason.

Options:
  --reference DIR  blessed values (default reference/regression)
  --results DIR    where the studies wrote their blessed outputs (default results)
  --jobs N         cases run in parallel (default: the CPUs it may run on)
  --rtol X         relative tolerance of floating-point columns (default 0: the runs are
                   deterministic, so any difference is a real change)
  --budget X       particle-steps of the largest case in the fast subset, for every spec
                   (default: each spec's check_budget, else 2e7)
)";

RegressionOptions regression_options(const Args& args) {
  RegressionOptions o;
  o.jobs = default_jobs();
  if (auto v = args.value("reference")) o.reference = std::string(*v);
  if (auto v = args.value("results")) o.results = std::string(*v);
  if (auto v = args.value("jobs")) {
    const auto jobs = parse_int(*v, "jobs");
    if (jobs < 1 || jobs > 1024) throw UsageError("--jobs: must be in [1, 1024]");
    o.jobs = static_cast<int>(jobs);
  }
  if (auto v = args.value("rtol")) {
    o.rtol = parse_double(*v, "rtol");
    if (!(o.rtol >= 0 && o.rtol < 1)) throw UsageError("--rtol: must be in [0, 1)");
  }
  if (auto v = args.value("budget")) {
    o.budget = parse_double(*v, "budget");
    o.budget_given = true;
    if (!(o.budget > 0 && std::isfinite(o.budget))) throw UsageError("--budget: must be > 0");
  }
  return o;
}

}  // namespace

int cmd_check(const std::vector<std::string_view>& argv) {
  const Args args(argv, kRegressionOptions);
  if (args.flag("help")) {
    std::cout << kCheckHelp;
    return 0;
  }
  if (args.value("reason")) throw UsageError("--reason belongs to mpmstab bless");
  const auto specs = load_specs(args.positional());
  return run_check(specs, regression_options(args));
}

int cmd_bless(const std::vector<std::string_view>& argv) {
  const Args args(argv, kRegressionOptions);
  if (args.flag("help")) {
    std::cout << kCheckHelp;
    return 0;
  }
  const std::string reason(args.value("reason").value_or(""));
  if (reason.find_first_not_of(" \t\n") == std::string::npos) {
    throw UsageError("--reason: a blessing needs a reason, e.g. make bless REASON=\"...\"");
  }
  // One line of the audit log: a line break could forge an entry of its own.
  for (const unsigned char c : reason) {
    if (c < 0x20 || c == 0x7f) {
      throw UsageError("--reason: must be one line without control characters (found byte " +
                       std::to_string(static_cast<int>(c)) + ")");
    }
  }
  const auto specs = load_specs(args.positional());
  return run_bless(specs, regression_options(args), reason);
}

}  // namespace mpmstab::cli
