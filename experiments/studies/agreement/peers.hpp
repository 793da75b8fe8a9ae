// The peers study's numbers: each case against the peer's measured value (peers.cpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "spec.hpp"

namespace mpmstab {

// One case of ours against the peer's value of the same case.
struct PeerCase {
  const nlohmann::ordered_json* row = nullptr;  // our flat record
  std::string basis;                            // the peer's: linear or GIMP
  std::string ours_outcome, peer_outcome, peer_failure;
  std::optional<std::int64_t> peer_step;
  std::optional<double> peer_error, peer_over_time;
  std::optional<double> error_ratio, over_time_ratio;  // ours / peer
  bool outcome_agrees = false, step_agrees = false;
  bool errors_judged = false, errors_agree = false;
  bool agrees = false;  // within every tolerance
};

namespace studies::peers {
// The cases of one basis of the peer: how many agree in each respect, and ours / peer max error
// at T over the cases whose errors are judged.
struct BasisFindings {
  std::string basis;
  int cases = 0, outcomes = 0, failing = 0, steps = 0, within = 0, judged = 0;
  std::optional<double> lo, median, hi;
};

// Every case against the peer, and what the report, its JSON and the index count of them.
struct Findings {
  std::vector<PeerCase> cases;
  int unmatched = 0;                 // our cases without a peer value
  int agree = 0;                     // of the cases, within every tolerance
  std::vector<BasisFindings> bases;  // linear, then GIMP
};
}  // namespace studies::peers
using PeersStudy = studies::peers::Findings;

// The findings: every row against the peer values in spec.reference (rows must outlive them).
PeersStudy study_peers(const Spec& spec, const std::vector<nlohmann::ordered_json>& rows);
std::string peers_markdown(const Spec& spec, const PeersStudy& s, const std::filesystem::path& out);
// <name>_data.csv: per case, whether it agrees (make check compares it with the blessed verdicts).
std::string peers_verdicts_csv(const PeersStudy& s, const std::string& header_lines);
nlohmann::ordered_json peers_json(const PeersStudy& s);

}  // namespace mpmstab
