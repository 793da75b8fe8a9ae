// `mpmstab cluster-time`: the wall time of a tier run as a Slurm job array (mpmstab slurm --tier)
// on the throwaway cluster of `make studies-cluster`, which measures it, recorded in the committed
// DIR/cluster_timings.json that results/performance.md shows.
#include <cmath>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "files.hpp"
#include "provenance.hpp"
#include "strict_json.hpp"

namespace mpmstab::cli {

namespace {

using ojson = nlohmann::ordered_json;

constexpr const char* kClusterTimeHelp =
    R"help(Usage: mpmstab cluster-time --tier paper|studies --nodes N --cpus-per-node C
                           --at-once M --shards S --array-seconds A --follow-seconds F
                           --render-seconds R --seconds T --array-records X
                           --follow-records Z --render-records Y [--out DIR]

Records one run of a tier as a Slurm job array (mpmstab slurm --tier) in DIR/cluster_timings.json
(DIR default results), under the key "<tier> tier, N nodes", replacing the last run of that tier
on that many nodes, with this machine's CPU, the kernels' instruction set and the commit.
tests/cluster/tier_cluster.sh (make studies-cluster) calls it, only once the tier's files came out
byte for byte as committed; results/performance.md shows the file (make timings).

  --nodes N           Slurm nodes (slurmd daemons) of the cluster
  --cpus-per-node C   CPUs of each node
  --at-once M         array tasks allowed to run at once (the array's throttle)
  --shards S          tasks of each array
  --array-seconds A   from submission to the last task's end of the cases' array
  --follow-seconds F  from then to the last task's end of the follow-up runs' array
  --render-seconds R  from then to the render job's end (merge of the records, make tier)
  --seconds T         from submission to the render job's end
  --array-records X   case records the cases' array computed
  --follow-records Z  records the follow-up array computed (the follow-up runs the cases'
                      records decide)
  --render-records Y  records the render job computed (the other follow-up runs, searches)
)help";

double seconds_option(const Args& args, std::string_view name) {
  const auto v = args.value(name);
  if (!v) throw UsageError("--" + std::string(name) + " is required");
  const double s = parse_double(*v, name);
  if (!std::isfinite(s) || s < 0)
    throw UsageError("--" + std::string(name) + ": must be seconds >= 0, got " + std::string(*v));
  return s;
}

std::int64_t count_of(const Args& args, std::string_view name, std::int64_t least) {
  const auto v = args.value(name);
  if (!v) throw UsageError("--" + std::string(name) + " is required");
  const std::int64_t n = parse_int(*v, name);
  if (n < least || n > 100000000)
    throw UsageError("--" + std::string(name) + ": must be in [" + std::to_string(least) +
                     ", 1e8], got " + std::string(*v));
  return n;
}

// The file's entries (an absent file: none); a file that is not such an object is refused.
ojson recorded(const std::filesystem::path& path) {
  const auto text = read_if_present(path);
  if (!text) return ojson::object();
  ojson all = parse_json_strict<ojson>(*text, path);
  if (!all.is_object()) throw UsageError(path.string() + ": not a JSON object");
  return all;
}

}  // namespace

int cmd_cluster_time(const std::vector<std::string_view>& argv) {
  const Args args(argv, {{"tier"},
                         {"nodes"},
                         {"cpus-per-node"},
                         {"at-once"},
                         {"shards"},
                         {"array-seconds"},
                         {"follow-seconds"},
                         {"render-seconds"},
                         {"seconds"},
                         {"array-records"},
                         {"follow-records"},
                         {"render-records"},
                         {"out"},
                         {"help", false}});
  if (args.flag("help")) {
    std::cout << kClusterTimeHelp;
    return 0;
  }
  if (!args.positional().empty()) throw UsageError("cluster-time takes no positional argument");
  const std::string tier(args.value("tier").value_or(""));
  if (tier != "paper" && tier != "studies")
    throw UsageError("--tier: expected paper or studies, got '" + tier + "'");
  const std::int64_t nodes = count_of(args, "nodes", 1);
  ojson entry = {{"tier", tier},
                 {"nodes", nodes},
                 {"cpus_per_node", count_of(args, "cpus-per-node", 1)},
                 {"tasks_at_once", count_of(args, "at-once", 1)},
                 {"shards", count_of(args, "shards", 1)},
                 {"array_seconds", seconds_option(args, "array-seconds")},
                 {"follow_seconds", seconds_option(args, "follow-seconds")},
                 {"render_seconds", seconds_option(args, "render-seconds")},
                 {"wall_seconds", seconds_option(args, "seconds")},
                 {"array_records", count_of(args, "array-records", 0)},
                 {"follow_records", count_of(args, "follow-records", 0)},
                 {"render_records", count_of(args, "render-records", 0)}};
  const Provenance p = current_provenance(1);
  entry["commit"] = p.commit;
  entry["dirty"] = p.dirty;
  entry["cpu"] = p.cpu;
  entry["kernels"] = p.kernels;
  entry["date"] = p.date;
  const auto out = output_folder(args);
  const auto path = out / "cluster_timings.json";
  ojson all = recorded(path);
  make_output_folder(out);
  // The entries in key order.
  std::map<std::string, ojson> sorted;
  for (auto& [k, v] : all.items())
    sorted[k] = v;
  sorted[tier + " tier, " + std::to_string(nodes) + (nodes == 1 ? " node" : " nodes")] = entry;
  ojson doc = ojson::object();
  for (auto& [k, v] : sorted)
    doc[k] = std::move(v);
  write_if_changed(path, doc.dump(1) + "\n");
  std::cerr << "[cluster-time] " << tier << " tier on " << nodes
            << " node(s): " << entry["wall_seconds"].get<double>() << " s -> " << path.string()
            << "\n";
  return 0;
}

}  // namespace mpmstab::cli
