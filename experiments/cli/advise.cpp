// `mpmstab advise`: the cheapest checked setting for a problem in dimensionless form, answered
// from results/advice.json by the rule of advice.hpp (the one advice.md answers by), and with
// --confirm, the setting run on the problem and at its corners.
#include <cmath>
#include <iostream>
#include <sstream>

#include "advice.hpp"
#include "args.hpp"
#include "base/params.hpp"
#include "commands.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "report_util.hpp"
#include "run/run.hpp"
#include "scenes/validate.hpp"
#include "strict_json.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kAdviseHelp =
    R"(Usage: mpmstab advise --A <A/L> --cT <c T/L> --error <target> [options]

Prints the cheapest checked setting (method, transfer, update order, cells, C = c dt/h) for a
problem of the bar in dimensionless form: amplitude A/L, run length c T/L (wave passes), and a
target error over time (the largest displacement error over steps and particles) as a fraction
of A. It answers from the settings of the advice study (results/advice.json; no runs) by the
rule of results/advice.md and docs/design.md, "Advice: regions and corners": the setting's
checked region must hold A/L and 4 x c T/L, the scene and the boundary, and its error (the
largest over its corners) must be at most the target / 2. It prints the setting's predicted
error / A, its cost in particle-steps on the problem, the region and the margins to the
spectral limit and to the target. A problem outside every checked region, or a target no
region reaches, is refused with exit status 2 and a message naming what is outside.
The settings' Courant numbers are a fixed grid and, for each method and grid the balance study
measures, the C at which its time and space errors balance (results/advice.md).

Required:
  --A <x>            amplitude over the bar's length, > 0
  --cT <x>           run length c T / L, > 0
  --error <x>        target error over time / A, in (0, 1]

Options:
  --scene bar|steffen        the paper's bar (default) or the neo-Hookean scene
  --bc dirichlet|periodic    boundaries (default dirichlet)
  --methods <list>           comma-separated: a basis (gimp), a method (gimp/apic,
                             gimp/musl) or basis/transfer/update; default every method
  --data <file>              the advice data (default results/advice.json)
  --json                     one JSON object: method, transfer, update, cells, courant,
                             predicted_error_over_A, particle_steps, region, margins
  --confirm                  run the setting on the problem, at 4 x its c T, on 8 x its
                             cells and, where its region holds them, with periodic
                             boundaries, on the neo-Hookean scene and on a jittered layout
                             (each at 4 x c T), and say whether each meets the target;
                             exit status 1 if one does not
)";

std::vector<OptionSpec> options() {
  return {{"A"},       {"cT"},   {"error"},       {"scene"},          {"bc"},
          {"methods"}, {"data"}, {"json", false}, {"confirm", false}, {"help", false}};
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

Problem problem_from(const Args& args) {
  Problem p;
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
  return p;
}

std::vector<CheckedSetting> load(const std::filesystem::path& file) {
  const nlohmann::ordered_json doc = read_json_file(file);
  if (!doc.is_object() || !doc.contains("study") || !doc["study"].is_object() ||
      !doc["study"].contains("settings") || !doc["study"]["settings"].is_array())
    throw InputError(file, "study.settings: missing (not the advice study's results)");
  std::vector<CheckedSetting> out;
  const auto& list = doc["study"]["settings"];
  for (std::size_t i = 0; i < list.size(); ++i) {
    try {
      out.push_back(checked_setting_from_json(list[i]));
    } catch (const InputError& e) {
      throw InputError(file, "study.settings[" + std::to_string(i) + "]: " + e.what());
    }
  }
  return out;
}

// The setting as the parameters of a run of the problem (E = 1: c = 1, T = c T).
RunParams run_of(const CheckedSetting& s, const Problem& p) {
  RunParams r;
  r.method = *parse_method(s.method);
  const std::string transfer = transfer_name(s.transfer);
  std::optional<double> order;
  if (transfer != s.transfer) order = std::stod(s.transfer.substr(transfer.size() + 1));
  r.transfer = *parse_transfer(transfer);
  if (order && r.transfer == Transfer::fmpm) r.fmpm_order = int(*order);
  if (order && r.transfer == Transfer::xpic) r.xpic_order = int(*order);
  if (order && r.transfer == Transfer::blend) r.flip_fraction = *order;
  r.update = *parse_update_order(s.update);
  r.E = kAdviceE;
  r.A = p.A;
  r.T = p.cT;
  r.cells = s.cells;
  r.ppc = s.ppc;
  r.scene = *parse_scene(p.scene);
  r.bc = *parse_boundary(p.bc);
  r.stepping.policy = TimeStepPolicy::cfl;
  r.stepping.cfl_factor = s.courant;
  r.observe = Observe{};
  r.observe.dt_stable = false;
  r.observe.crossings = false;
  return r;
}

// The runs --confirm makes, each named.
std::vector<std::pair<std::string, RunParams>> confirming(const CheckedSetting& s,
                                                          const Region& region, const Problem& p) {
  const RegionRule& rule = kRegionRule;
  const RunParams base = run_of(s, p);
  std::vector<std::pair<std::string, RunParams>> out{{"the problem", base}};
  RunParams longer = base;
  longer.T = base.T * rule.length_factor;
  out.emplace_back(shortest(rule.length_factor) + " x c T", longer);
  RunParams finer = base;
  finer.cells = base.cells * rule.refine;
  out.emplace_back(std::to_string(rule.refine) + " x the cells", finer);
  if (region.periodic && base.bc != Boundary::periodic) {
    RunParams q = longer;
    q.bc = Boundary::periodic;
    out.emplace_back("periodic, " + shortest(rule.length_factor) + " x c T", q);
  }
  if (region.other_scene && base.scene != SceneKind::steffen) {
    RunParams q = longer;
    q.scene = SceneKind::steffen;
    out.emplace_back("neo-Hookean, " + shortest(rule.length_factor) + " x c T", q);
  }
  if (region.jittered) {
    RunParams q = longer;
    q.layout.jitter = rule.jitter;
    out.emplace_back(
        "jittered " + shortest(rule.jitter) + ", " + shortest(rule.length_factor) + " x c T", q);
  }
  return out;
}

// Runs the confirming runs; true when every one meets the target.
bool confirm(std::ostream& out, const Answer& a, const Problem& p) {
  bool all = true;
  out << "confirming runs (each must end stable with an error over time at most "
      << value_text(p.target) << " A):\n";
  for (const auto& [name, params] : confirming(*a.setting, *a.region, p)) {
    if (const auto issues = validate(params); !issues.empty())
      throw UsageError("--confirm: the run '" + name + "' is not valid: " + issues.front().key +
                       ": " + issues.front().message);
    const RunResult r = run(params);
    const bool stable = r.outcome && *r.outcome == Outcome::stable;
    const double e = r.max_error_over_time.value_or(NAN) / params.A;
    const bool pass = stable && e <= p.target;
    all = all && pass;
    out << "  " << name << ": " << (r.outcome ? to_string(*r.outcome) : "no verdict")
        << ", error over time " << sci(e) << " A: " << (pass ? "passes" : "FAILS") << "\n";
  }
  return all;
}

}  // namespace

int cmd_advise(const std::vector<std::string_view>& argv) {
  const Args args(argv, options());
  if (args.flag("help")) {
    std::cout << kAdviseHelp;
    return 0;
  }
  if (!args.positional().empty())
    throw UsageError("unexpected argument '" + std::string(args.positional().front()) + "'");
  const Problem p = problem_from(args);
  const std::filesystem::path data = args.value("data")
                                         ? std::filesystem::path(std::string(*args.value("data")))
                                         : std::filesystem::path("results") / "advice.json";
  const std::vector<CheckedSetting> settings = load(data);
  const Answer a = advise(settings, p);
  if (!a.setting) throw UsageError(a.refusal);
  if (args.flag("json")) {
    std::cout << answer_json(a, p).dump(2) << "\n";
  } else {
    std::cout << answer_text(a, p);
  }
  if (args.flag("confirm") && !confirm(args.flag("json") ? std::cerr : std::cout, a, p)) return 1;
  return 0;
}

}  // namespace mpmstab::cli
