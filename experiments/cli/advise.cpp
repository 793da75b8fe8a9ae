// `mpmstab advise`: a setting for a problem in dimensionless form, verified on the problem by the
// search of advice_verify.hpp from the settings of results/advice.json, within a budget of
// particle-steps.
#include <cmath>
#include <iostream>
#include <sstream>

#include "args.hpp"
#include "base/params.hpp"
#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "commands.hpp"
#include "files.hpp"
#include "report_util.hpp"
#include "run/run.hpp"
#include "scenes/validate.hpp"
#include "strict_json.hpp"

namespace mpmstab::cli {

namespace {

// The help, with the default budget from AdviceDomain.
std::string advise_help() {
  return R"(Usage: mpmstab advise --A <A/L> --cT <c T/L> --error <target> [options]

Answers a problem of the bar (or the neo-Hookean scene) in dimensionless form, amplitude A/L,
run length c T/L (wave passes) and a target error over time (the largest displacement error over
steps and particles) as a fraction of A, with a setting (method, transfer, update order, cells,
particles per cell, C = c dt/h, start) verified on that problem (docs/studies.md, "Advice:
verified on the problem").

The candidates are the advice study's settings (results/advice.json) and their methods and
Courant numbers on finer grids, to 800 cells, each with 2 and with 4 particles per cell and with
the exact and the half-step start. They are taken cheapest first in particle-steps (particles x
steps) of their run on the problem. A candidate is skipped only where a run of the study that
matches the problem (a run of the candidate itself, with 2 particles per cell from the exact
start, on the same scene, boundary and layout, at an amplitude within a factor 3 of A and a
jitter within a factor 2, to a length covering c T) predicts that it fails, or where the
problem's own runs already show it cannot pass (a run of the same method, particles per cell
and start on at least its cells at no larger C measured an error above the target, or one on its
cells at no larger C was unstable). Every other prediction is distant: it orders candidates, it
never excludes one. Each candidate not skipped is run on the problem, to 4 x c T and on twice
the cells at the same C; the answer is the first whose every verifying run ends stable within
the target: the cheapest that passed among the candidates not skipped. It prints each candidate
rejected and why, the answer's verifying runs, how many were tried and skipped, the
particle-steps spent, and the answer's survival and accuracy edges in C measured on the problem
beside its small-amplitude (Bloch) limit. A problem outside the domain, too short for a
verdict, whose every candidate is skipped or fails (the smallest error the search measured is
named), or whose next candidate would take the particle-steps spent past the budget is refused
with exit status 2, naming the bound. The budget counts particle-steps, not seconds: the same
problem gets the same answer or refusal on any machine (the seconds are printed beside, in the
text only).

Required:
  --A <x>            amplitude over the bar's length, 1e-4 to 0.05
  --cT <x>           run length c T / L, > 0 and at most 1000
  --error <x>        target error over time / A, 1e-3 to 1

Options:
  --scene bar|steffen        the paper's bar (default) or the neo-Hookean scene
  --bc dirichlet|periodic    boundaries (default dirichlet)
  --jitter <j>               particles moved by up to j / 2 of their spacing, 0 to 0.5
                             (default 0: the uniform layout)
  --methods <list>           comma-separated: a basis (gimp), a method (gimp/apic,
                             gimp/musl) or basis/transfer/update; default every method
  --budget <particle-steps>  bound on the particle-steps of the verifying runs and the
                             margins' probes (default )" +
         sci(kAdviceDomain.budget_particle_steps) + R"(); a candidate whose runs would pass it
                             is not run
  --no-margins               do not measure the survival and accuracy edges
  --no-verify                the cheapest candidate whose prediction meets the target, run
                             on nothing: said plainly to be unverified
  --data <file>              the advice data (default results/advice.json)
  --json                     one JSON object with the same content (without the seconds)
)";
}

std::vector<OptionSpec> options() {
  return {{"A"},
          {"cT"},
          {"error"},
          {"scene"},
          {"bc"},
          {"jitter"},
          {"methods"},
          {"budget"},
          {"data"},
          {"json", false},
          {"no-verify", false},
          {"no-margins", false},
          {"help", false}};
}

double positive(const Args& args, const char* name) {
  const auto v = args.value(name);
  if (!v) throw UsageError(std::string("--") + name + " is required");
  const double x = parse_double(*v, name);
  if (!(x > 0))
    throw UsageError(std::string("--") + name + ": must be > 0, got " + std::string(*v));
  return x;
}

// A --methods entry: basis[/transfer][/update] or basis/update, each part a name the solver
// knows (a transfer may carry its parameter, "blend(0.99)"); an unknown part is named, with
// every name it could have been.
void check_method_filter(const std::string& item) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(item);
  while (std::getline(in, part, '/'))
    parts.push_back(part);
  if (item.back() == '/') parts.emplace_back();
  const std::string bases = choices_text(names_of<Method>());
  const std::string transfers = choices_text(names_of<Transfer>());
  const std::string updates = choices_text(names_of<UpdateOrder>());
  const std::string form = " in '" + item +
                           "' (an entry is basis, basis/transfer, basis/update or "
                           "basis/transfer/update)";
  if (parts.size() > 3) throw UsageError("--methods: too many parts" + form);
  if (!parse_method(parts[0]))
    throw UsageError("--methods: unknown method '" + parts[0] + "'" + form + "; the bases are " +
                     bases);
  if (parts.size() == 2 && !parse_transfer(transfer_name(parts[1])) &&
      !parse_update_order(parts[1]))
    throw UsageError("--methods: unknown transfer or update '" + parts[1] + "'" + form +
                     "; the transfers are " + transfers + ", the updates " + updates);
  if (parts.size() == 3) {
    if (!parse_transfer(transfer_name(parts[1])))
      throw UsageError("--methods: unknown transfer '" + parts[1] + "'" + form +
                       "; the transfers are " + transfers);
    if (!parse_update_order(parts[2]))
      throw UsageError("--methods: unknown update '" + parts[2] + "'" + form +
                       "; the updates are " + updates);
  }
}

VerifyProblem problem_from(const Args& args) {
  VerifyProblem vp;
  Problem& p = vp.problem;
  p.A = positive(args, "A");
  p.cT = positive(args, "cT");
  p.target = positive(args, "error");
  if (p.A >= 1) throw UsageError("--A: A/L must be below 1");
  if (p.target > 1) throw UsageError("--error: a target error over time / A must be at most 1");
  if (auto s = args.value("scene")) {
    if (*s != "bar" && *s != "steffen")
      throw UsageError("--scene: must be bar or steffen (the scenes advice is checked on)");
    p.scene = std::string(*s);
  }
  if (auto b = args.value("bc")) {
    if (*b != "dirichlet" && *b != "periodic")
      throw UsageError("--bc: must be dirichlet or periodic");
    p.bc = std::string(*b);
  }
  if (auto m = args.value("methods")) {
    std::string list(*m), item;
    std::istringstream in(list);
    while (std::getline(in, item, ',')) {
      if (item.empty() || item.size() > 40)
        throw UsageError("--methods: an empty or overlong entry in '" + list + "'");
      check_method_filter(item);
      p.methods.push_back(item);
    }
  }
  if (auto j = args.value("jitter")) {
    vp.jitter = parse_double(*j, "jitter");
    if (!(vp.jitter >= 0)) throw UsageError("--jitter: must be >= 0, got " + std::string(*j));
  }
  if (const std::string outside = outside_domain(vp); !outside.empty()) throw UsageError(outside);
  return vp;
}

std::vector<CheckedSetting> load(const std::filesystem::path& file) {
  const nlohmann::ordered_json doc = read_json_file(file);
  try {
    return checked_settings_of(doc);
  } catch (const InputError& e) {
    throw InputError(file, e.what());
  }
}

}  // namespace

int cmd_advise(const std::vector<std::string_view>& argv) {
  const Args args(argv, options());
  if (args.flag("help")) {
    std::cout << advise_help();
    return 0;
  }
  if (!args.positional().empty())
    throw UsageError("unexpected argument '" + std::string(args.positional().front()) + "'");
  // 1. The problem, checked against the domain.
  const VerifyProblem vp = problem_from(args);
  double budget = kAdviceDomain.budget_particle_steps;
  if (args.value("budget")) budget = positive(args, "budget");
  if (args.flag("no-verify") && (args.value("budget") || args.flag("no-margins")))
    throw UsageError("--no-verify runs nothing: --budget and --no-margins do not apply");
  // 2. The settings of the advice study.
  const std::filesystem::path data = args.value("data")
                                         ? std::filesystem::path(std::string(*args.value("data")))
                                         : std::filesystem::path("results") / "advice.json";
  const std::vector<CheckedSetting> settings = load(data);
  const bool json = args.flag("json");
  // 3. The lookup alone, where asked for.
  if (args.flag("no-verify")) {
    const std::vector<Candidate> list = candidates(settings, vp);
    const Candidate* c = predicted_cheapest(list, vp.problem.target);
    if (!c)
      throw UsageError("--error: no candidate is predicted to meet " +
                       value_text(vp.problem.target) + " A (or none gets a verdict)");
    if (json)
      std::cout << unverified_json(*c, vp).dump(2) << "\n";
    else
      std::cout << unverified_text(*c, vp);
    return 0;
  }
  // 4. The search: candidates verified on the problem, cheapest first.
  const Verified v = verified_advice(settings, vp, budget, !args.flag("no-margins"),
                                     [](const RunParams& params) { return run(params); });
  if (json) {
    std::cout << verified_json(v, vp).dump(2) << "\n";
  } else {
    std::cout << verified_text(v, vp);
  }
  if (!v.answer) {
    std::cerr << "mpmstab advise: " << v.refusal << "\n";
    return 2;
  }
  return 0;
}

}  // namespace mpmstab::cli
