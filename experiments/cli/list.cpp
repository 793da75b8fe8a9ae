// `mpmstab list`: every experiment spec of a folder, in the order they run (after the
// experiments whose results they read): the one list make reproduce, make check and make
// figures follow.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <set>

#include "commands.hpp"

namespace mpmstab::cli {

namespace {

constexpr const char* kListHelp =
    R"(Usage: mpmstab list [DIR] [--tier paper|studies] [--figures] [--studies]

Prints the path of every experiment spec in DIR (default experiments), one per line, in the
order they run: each after the experiments whose results its study reads, then by the spec's
index_order, then by name. Specs whose name differs from their file name are refused.

  --tier T   only the experiments of tier T (the spec's "tier"): paper, what make reproduce
             runs (the paper's tables and figures, and the comparison with the experiments it
             cites), or studies, what make studies runs (everything else), with the experiments
             of the paper tier they read before them. A paper experiment that reads a studies
             experiment is refused (exit status 2).
  --figures  only the experiments whose study draws a figure
  --studies  instead, every study the program knows: its name, what it shows, and the specs
             of DIR that use it
)";

// Depth-first, inputs first; `visiting` catches a cycle.
void visit(const Spec& s, const std::map<std::string, const Spec*>& by_name,
           std::set<std::string>& done, std::set<std::string>& visiting,
           std::vector<const Spec*>& order) {
  if (done.count(s.name)) return;
  if (!visiting.insert(s.name).second) {
    throw UsageError(s.path.string() + ": its inputs read it back (a cycle)");
  }
  for (const auto& decl : s.study->inputs) {
    const auto it = by_name.find(decl.name);
    if (it != by_name.end()) visit(*it->second, by_name, done, visiting, order);
  }
  visiting.erase(s.name);
  done.insert(s.name);
  order.push_back(&s);
}

std::vector<Spec> specs_in(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) throw UsageError(dir.string() + " is not a folder");
  std::vector<std::string> paths;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.path().extension() == ".json") paths.push_back(entry.path().string());
  }
  std::sort(paths.begin(), paths.end());
  std::vector<std::string_view> views(paths.begin(), paths.end());
  std::vector<Spec> specs = load_specs(views);
  for (const auto& s : specs) {
    if (s.path.stem() != s.name) {
      throw UsageError(s.path.string() + ": name '" + s.name + "' differs from the file name");
    }
  }
  return specs;
}

std::vector<const Spec*> run_order(const std::vector<Spec>& specs) {
  std::vector<const Spec*> sorted;
  for (const auto& s : specs)
    sorted.push_back(&s);
  // index_order is finite (the spec's reader refuses any other): < orders it.
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Spec* a, const Spec* b) { return a->index_order < b->index_order; });
  std::map<std::string, const Spec*> by_name;
  for (const Spec* s : sorted)
    by_name[s->name] = s;
  std::set<std::string> done, visiting;
  std::vector<const Spec*> order;
  for (const Spec* s : sorted)
    visit(*s, by_name, done, visiting, order);
  return order;
}

// The experiments a tier runs, in run order: its own and every experiment they read, directly
// or through another. A paper experiment must read only paper experiments.
std::vector<const Spec*> tier_order(const std::vector<const Spec*>& order, Tier tier) {
  std::map<std::string, const Spec*> by_name;
  for (const Spec* s : order)
    by_name[s->name] = s;
  std::set<std::string> wanted;
  std::vector<const Spec*> stack;
  for (const Spec* s : order)
    if (s->tier == tier) stack.push_back(s);
  while (!stack.empty()) {
    const Spec* s = stack.back();
    stack.pop_back();
    if (!wanted.insert(s->name).second) continue;
    for (const auto& decl : s->study->inputs) {
      const auto it = by_name.find(decl.name);
      if (it == by_name.end()) continue;
      if (s->tier == Tier::paper && it->second->tier != Tier::paper)
        throw UsageError(s->path.string() + ": a paper experiment reads '" + decl.name +
                         "', of the studies tier (make reproduce would depend on make studies)");
      stack.push_back(it->second);
    }
  }
  std::vector<const Spec*> out;
  for (const Spec* s : order)
    if (wanted.count(s->name)) out.push_back(s);
  return out;
}

std::string records_text(const Study& study) {
  const auto& r = study.records;
  std::string text;
  for (const auto& [on, name] :
       {std::pair{r.error_over_time, "error_over_time"}, std::pair{r.dt_stable, "dt_stable"},
        std::pair{r.crossings, "crossings"}, std::pair{r.history, "history"},
        std::pair{r.final_state, "final_state"}}) {
    if (on) text += (text.empty() ? "" : ", ") + std::string(name);
  }
  return text.empty() ? "nothing beyond each run's verdict and final error" : text;
}

void print_studies(const std::vector<Spec>& specs) {
  for (const Study* study : all_studies()) {
    std::cout << study->name << ": " << study->summary << "\n";
    if (study->has_cases) std::cout << "  reads: " << records_text(*study) << "\n";
    for (const auto& input : study->inputs) {
      std::cout << "  input: " << input.name << (input.required ? " (required)" : "") << "\n";
    }
    for (const auto& s : specs) {
      if (s.study == study) std::cout << "  " << s.path.generic_string() << "\n";
    }
  }
}

// The specs in run order, of one tier ("paper" or "studies") when given.
std::vector<const Spec*> listed(const std::vector<Spec>& specs,
                                std::optional<std::string_view> tier) {
  if (tier && *tier != "paper" && *tier != "studies")
    throw UsageError("--tier: unknown value '" + std::string(*tier) +
                     "' (expected paper or studies)");
  std::vector<const Spec*> order = run_order(specs);
  // Every paper experiment reads only paper experiments, whichever tier is asked for.
  tier_order(order, Tier::paper);
  if (tier) order = tier_order(order, *tier == "paper" ? Tier::paper : Tier::studies);
  return order;
}

}  // namespace

std::vector<std::string> tier_spec_paths(const std::filesystem::path& dir, std::string_view tier) {
  const std::vector<Spec> specs = specs_in(dir);
  std::vector<std::string> paths;
  for (const Spec* s : listed(specs, tier))
    paths.push_back(s->path.generic_string());
  return paths;
}

int cmd_list(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"tier"}, {"figures", false}, {"studies", false}, {"help", false}});
  if (args.flag("help")) {
    std::cout << kListHelp;
    return 0;
  }
  if (args.positional().size() > 1) throw UsageError("list takes one folder");
  // The options are checked before any spec is read.
  const auto tier = args.value("tier");
  if (tier) listed({}, tier);
  const std::filesystem::path dir =
      args.positional().empty() ? "experiments" : std::string(args.positional().front());
  const std::vector<Spec> specs = specs_in(dir);
  if (args.flag("studies")) {
    print_studies(specs);
    return 0;
  }
  for (const Spec* s : listed(specs, tier)) {
    if (!args.flag("figures") || s->study->figure) std::cout << s->path.generic_string() << "\n";
  }
  return 0;
}

}  // namespace mpmstab::cli
