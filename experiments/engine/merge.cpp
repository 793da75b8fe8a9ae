#include "merge.hpp"

#include <algorithm>
#include <fstream>

#include "cache.hpp"
#include "strict_json.hpp"

namespace mpmstab {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

// Lists the first few items and the count of the rest.
std::string listing(const std::vector<std::string>& items, std::size_t shown = 10) {
  std::string s;
  for (std::size_t i = 0; i < items.size() && i < shown; ++i)
    s += "\n  " + items[i];
  if (items.size() > shown) s += "\n  ... and " + std::to_string(items.size() - shown) + " more";
  return s;
}

}  // namespace

fs::path shard_manifest(const fs::path& dir, const std::string& name, const Shard& shard) {
  return dir / (name + ".shard-" + std::to_string(shard.index) + "-of-" +
                std::to_string(shard.count) + ".json");
}

SweepOutcome merge_shards(const Spec& spec, const std::vector<fs::path>& dirs) {
  if (!spec.study->has_cases) {
    throw MergeError(spec.path.string() + " has no cases to merge: the " + spec.study->name +
                     " study is written from its inputs (mpmstab sweep " + spec.path.string() +
                     ")");
  }
  const std::string search = case_search(spec);
  std::vector<ResultCache> caches;
  for (const auto& d : dirs)
    caches.emplace_back(d / "cache");

  SweepOutcome out;
  out.merged = true;
  out.records.resize(spec.cases.size());
  std::vector<std::string> missing, conflicts;
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    const RunParams& p = spec.cases[i].params;
    std::optional<ojson> chosen;
    std::size_t chosen_dir = 0;
    for (std::size_t d = 0; d < caches.size(); ++d) {
      CacheLookup found = caches[d].lookup(p, search);
      if (found.rejected) ++out.rejected;
      auto record = std::move(found.record);
      if (!record) continue;
      if (!chosen) {
        chosen = std::move(record);
        chosen_dir = d;
      } else if (deterministic_part(*record) != deterministic_part(*chosen)) {
        conflicts.push_back("cases[" + std::to_string(i) + "] " + describe_case(p, search) + ": " +
                            dirs[chosen_dir].string() + " and " + dirs[d].string() + " disagree");
      }
    }
    if (!chosen) {
      missing.push_back("cases[" + std::to_string(i) + "] " + describe_case(p, search) + " (key " +
                        case_key(p, search) + ")");
      continue;
    }
    out.records[i] = std::move(*chosen);
    ++out.cached;
    if (out.records[i]["result"]["outcome"] == "unstable") ++out.unstable;
  }
  if (!missing.empty() || !conflicts.empty()) {
    std::string message;
    if (!missing.empty()) {
      message += std::to_string(missing.size()) + " of " + std::to_string(spec.cases.size()) +
                 " cases are in none of the folders (a shard that did not run or did not "
                 "finish?):" +
                 listing(missing);
    }
    if (!conflicts.empty()) {
      if (!message.empty()) message += "\n";
      message += std::to_string(conflicts.size()) +
                 " cases have results that disagree between folders (different solver builds?):" +
                 listing(conflicts);
    }
    throw MergeError(message);
  }

  // The merged sweep took as long as its longest shard.
  for (const auto& d : dirs) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(d, ec)) {
      const std::string file = entry.path().filename().string();
      if (file.rfind(spec.name + ".shard-", 0) != 0 || entry.path().extension() != ".json")
        continue;
      try {
        const ojson manifest = read_json_file(entry.path());
        out.wall_seconds = std::max(out.wall_seconds, manifest.at("wall_seconds").get<double>());
      } catch (const std::exception&) {
        // An unreadable manifest only loses the wall time, not a result.
      }
    }
  }
  return out;
}

std::unique_ptr<FollowUps> follow_ups_from_records(const Spec& spec, const SweepOutcome& cases) {
  if (!spec.study->follow_up || !spec.study->inputs.empty()) return nullptr;
  return follow_ups(spec, cases, fs::path());  // no input is read
}

}  // namespace mpmstab
