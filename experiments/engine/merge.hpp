// Gathering a sweep that ran in shards (mpmstab sweep --shard i/N), possibly on many machines,
// into the outcome a single-machine sweep has, so that the same reports are written from it.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "report.hpp"
#include "spec.hpp"
#include "sweep.hpp"

namespace mpmstab {

// Cases that cannot be merged: missing from every folder, or present in several with results
// that disagree. what() lists them (the first few of each, then the counts).
class MergeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The manifest a shard leaves beside its records: <dir>/<name>.shard-<i>-of-<N>.json.
std::filesystem::path shard_manifest(const std::filesystem::path& dir, const std::string& name,
                                     const Shard& shard);

// Reads the record of every case of `spec` from <dir>/cache of the given folders. A case found
// in several folders must agree in everything but the machine measurements; the record of the
// first folder that has it is used. wall_seconds of the outcome is the longest sweep among the
// shard manifests found (0 if none). Throws MergeError, also for a study without cases.
SweepOutcome merge_shards(const Spec& spec, const std::vector<std::filesystem::path>& dirs);

// The follow-up runs (Study::follow_up) of `spec`, chosen from its cases' records (`cases`, as
// merge_shards gathers them) as make reproduce chooses them, where the records alone decide
// them: for a study that reads no other experiment's results. Null for one that does (its
// follow-up runs wait until those are written, in make reproduce) and for one that asks for
// none. A tier's second job array computes them (mpmstab reproduce --follow-ups --shard I/N), and
// mpmstab merge --records-only --with-follow-ups gathers them.
std::unique_ptr<FollowUps> follow_ups_from_records(const Spec& spec, const SweepOutcome& cases);

}  // namespace mpmstab
