// The per-case result cache. A case is keyed by a hash of its canonical parameters (including
// what it records) and the solver version; a finished case is stored as <dir>/<key>.json and is
// not computed again while its key is unchanged.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "base/params.hpp"

namespace mpmstab {

// Every parameter that can change a result, in a fixed order and exact (shortest round-trip)
// notation, plus the solver version.
std::string canonical_parameters(const RunParams& p);

// 16 hex digits: FNV-1a (64 bit) of canonical_parameters(p).
std::string case_key(const RunParams& p, const std::string& search = "");

// 16 hex digits: FNV-1a (64 bit) of `text`.
std::string fnv1a_hex(std::string_view text);

// What a lookup found.
struct CacheLookup {
  std::optional<nlohmann::ordered_json> record;  // a record that passed every check
  // A file was there but failed a check (not JSON, another case's parameters, a checksum that
  // does not match its content, not a record's shape): it is not used, the case is computed
  // again and overwrites it.
  bool rejected = false;
};

// Each stored record carries "canonical" (the case's canonical parameters with the solver
// version and the search) and "checksum": fnv1a_hex of the canonical parameters and of the
// record's content without the checksum. A record edited by hand, truncated, or stored under
// another case's key fails it. The checksum detects accidents and edits, not a forger who
// recomputes it (the cache is a local folder, not a trust boundary).
class ResultCache {
 public:
  explicit ResultCache(std::filesystem::path dir) : dir_(std::move(dir)) {}

  // The stored record of this case, if present, made from exactly these parameters and intact.
  // `search` names what was computed from the parameters beyond one run ("" or "edge").
  CacheLookup lookup(const RunParams& p, const std::string& search = "") const;
  // The checks of lookup on the text of a stored record read from `file`. Never throws.
  static CacheLookup check(std::string_view text, const std::filesystem::path& file,
                           const RunParams& p, const std::string& search = "");
  std::optional<nlohmann::ordered_json> load(const RunParams& p,
                                             const std::string& search = "") const {
    return lookup(p, search).record;
  }
  // Stores a record atomically. Throws std::runtime_error when the folder is not writable.
  void store(const RunParams& p, nlohmann::ordered_json record,
             const std::string& search = "") const;

  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

}  // namespace mpmstab
