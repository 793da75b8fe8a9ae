// The per-case result cache. A case is keyed by a hash of its canonical parameters (including
// what it records) and the solver version; a finished case is stored as <dir>/<key>.json and is
// not computed again while its key is unchanged.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "params.hpp"

namespace mpmstab {

// Every parameter that can change a result, in a fixed order and exact (shortest round-trip)
// notation, plus the solver version.
std::string canonical_parameters(const RunParams& p);

// 16 hex digits: FNV-1a (64 bit) of canonical_parameters(p).
std::string case_key(const RunParams& p, const std::string& search = "");

class ResultCache {
 public:
  explicit ResultCache(std::filesystem::path dir) : dir_(std::move(dir)) {}

  // The stored record of this case, if present and made from exactly these parameters.
  // `search` names what was computed from the parameters beyond one run ("" or "edge").
  std::optional<nlohmann::ordered_json> load(const RunParams& p,
                                             const std::string& search = "") const;
  // Stores a record atomically. Throws std::runtime_error when the folder is not writable.
  void store(const RunParams& p, nlohmann::ordered_json record,
             const std::string& search = "") const;

  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace mpmstab
