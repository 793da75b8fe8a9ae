// The spectral studies' reports (experiments/studies/stability/spectral.cpp, spectral_edge.cpp),
// from synthetic rows: a scheme is confirmed only when its run below the limit stays bounded and
// its run above it grows; a measured edge agrees only within 5% of the limit.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "claims.hpp"
#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::study_row;

ojson spectral_row(const char* method, double safety, double error_over_A) {
  ojson r = study_row(method, 1);
  r["A"] = 1e-6;
  r["cells"] = 50;
  r["T"] = 20;
  r["dt_cfl"] = 0.02;
  r["policy"] = "spectral";
  r["safety"] = safety;
  r["courant_spectral"] = 0.7564;
  r["spectral_analysis"] = "bloch";
  r["dt_stable_min"] = 0.0874 * 0.02;
  r["max_error_over_time"] = error_over_A * 1e-6;
  return r;
}

TEST(SpectralStudy, ConfirmsALimitOnlyWhenBelowStaysBoundedAndAboveGrows) {
  std::vector<ojson> rows = {spectral_row("mpm", 0.95, 0.5), spectral_row("mpm", 1.05, 40),
                             spectral_row("gimp", 0.95, 0.5), spectral_row("gimp", 1.05, 2.0)};
  test_support::meaningless_row(rows[3]);
  rows[3]["max_error_over_time"] = 2e-6;
  const std::string md = test_support::study_report("spectral", rows).markdown;
  // The schemes' runs say where they lie: the tiny amplitude, one run length, one grid.
  EXPECT_NE(md.find("for 1 of 2 schemes (A = 1e-6; c T = 1; 50 cells; bar); not for `gimp`"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| mpm | 0.7564 | bloch | – | 0.0874 | bounded (error 5.0e-1 A) | grew "
                    "(error 4.0e1 A) | yes |"),
            std::string::npos)
      << md;
  // A run whose error reaches A but stays within 3 A is bounded, and marked meaningless.
  EXPECT_NE(md.find("| gimp | 0.7564 | bloch | – | 0.0874 | bounded (error 5.0e-1 A) | bounded "
                    "(error 2.0 A, meaningless) | **no** |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("usl 0.756 to 0.756 (the CFL number is 1)."), std::string::npos) << md;
  EXPECT_NE(md.find("Eq. (108) at the same state lies at 0.116 to 0.116 times the limit, at E = "
                    "1 on 50 cells (200 particles) only"),
            std::string::npos)
      << md;
}

const Claim& claim_of(const StudyReport& r, const std::string& id) {
  for (const auto& c : r.claims)
    if (c.id == id) return c;
  throw std::runtime_error("no claim " + id);
}

bool holds(const StudyReport& r, const std::string& id) {
  return claim_of(r, id).holds;
}

// The limit is confirmed for a scheme only when both of its runs agree, and the claim says so.
TEST(SpectralStudy, ConfirmationClaimCountsTheSchemes) {
  std::vector<ojson> rows = {spectral_row("mpm", 0.95, 0.5), spectral_row("mpm", 1.05, 40),
                             spectral_row("gimp", 0.95, 0.5), spectral_row("gimp", 1.05, 40)};
  auto report = test_support::study_report("spectral", rows);
  EXPECT_TRUE(holds(report, "spectral-limit-confirmed"));
  EXPECT_EQ(render(claim_of(report, "spectral-limit-confirmed"),
                   claim_of(report, "spectral-limit-confirmed").evidence),
            "2 of 2 schemes, runs at 0.95 and 1.05 times the limit");
  rows[3]["max_error_over_time"] = 0.5e-6;  // gimp's run above the limit stays bounded
  report = test_support::study_report("spectral", rows);
  EXPECT_FALSE(holds(report, "spectral-limit-confirmed"));
  EXPECT_NE(report.markdown.find("for 1 of 2 schemes (A = 1e-6; c T = 1; 50 cells; bar); not for "
                                 "`gimp`"),
            std::string::npos);
  EXPECT_EQ(claim_of(report, "spectral-limit-confirmed").measured_on,
            "A = 1e-6; c T = 1; 50 cells; bar");
}

// A run of the E study: gimp (or mpm) at 2 particles per cell on `cells` cells, at 0.95 times the
// limit, whose eq. (108) minimum is `ratio` times the limit.
ojson eq108_row(const char* method, double E, int cells, double ratio) {
  ojson r = spectral_row(method, 0.95, 0.5);
  r["E"] = E;
  r["T"] = 20 / std::sqrt(E);
  r["cells"] = cells;
  r["particles"] = 2 * cells;
  r["dt_cfl"] = 1.0 / cells / std::sqrt(E);
  r["dt_stable_min"] = ratio * 0.7564 * r["dt_cfl"].get<double>();
  return r;
}

// Eq. (108) against the limit at other E: the rows at another E are not schemes of the table,
// they measure how the ratio moves; the per-E table, the ranges and the claims read them and flip
// with them.
TEST(SpectralStudy, Eq108RatioPerEIsReadFromTheRowsAndItsClaimsFlipWithThem) {
  // E = 1 at the ratio of eq. (108) at rest (0.0874 / 0.7564 = 0.1155), E = 64 at 0.3.
  std::vector<ojson> rows = {spectral_row("gimp", 0.95, 0.5), spectral_row("gimp", 1.05, 40),
                             spectral_row("mpm", 0.95, 0.5),  spectral_row("mpm", 1.05, 40),
                             eq108_row("gimp", 64, 50, 0.3),  eq108_row("mpm", 64, 50, 0.25)};
  auto report = test_support::study_report("spectral", rows);
  const std::string& md = report.markdown;
  EXPECT_NE(md.find("for 2 of 2 schemes"), std::string::npos) << md;  // E = 64: no scheme
  EXPECT_NE(md.find("| 1 | 1 | gimp | 0.7564 | 0.0874 | 0.116 | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 64 | 8 | gimp | 0.7564 | 0.2269 | 0.300 | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 64 | 8 | mpm | 0.7564 | 0.1891 | 0.250 | – |"), std::string::npos) << md;
  EXPECT_NE(md.find("The ratio per E, over the bases and particles per cell: E = 1, 0.116 to "
                    "0.116; E = 64, 0.250 to 0.300."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("up to a factor 2.60 (gimp at 2 particles per cell: 0.116 at E = 1, 0.300 at "
                    "E = 64)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("(at 2 particles per cell with USL and FLIP, 0.116 to 0.300 over E = 1 to 64)"),
            std::string::npos)
      << md;
  EXPECT_TRUE(holds(report, "eq108-below-limit-every-E"));
  EXPECT_TRUE(holds(report, "eq108-not-homogeneous"));
  const Claim& below = claim_of(report, "eq108-below-limit-every-E");
  EXPECT_EQ(render(below, below.evidence),
            "4 of 4 runs; the largest ratio is 0.300, gimp at E = 64, ppc 2");
  // At E = 1 the rows sit at eq. (108)'s value at rest; at E = 64 they do not.
  EXPECT_FALSE(holds(report, "eq108-at-rest"));

  // A ratio above 1 at E = 64 flips the first claim.
  rows[4] = eq108_row("gimp", 64, 50, 1.2);
  report = test_support::study_report("spectral", rows);
  EXPECT_FALSE(holds(report, "eq108-below-limit-every-E"));
  EXPECT_EQ(render(claim_of(report, "eq108-below-limit-every-E"),
                   claim_of(report, "eq108-below-limit-every-E").evidence),
            "3 of 4 runs; the largest ratio is 1.200, gimp at E = 64, ppc 2");
  // The same ratio at both E: homogeneous, the second claim does not hold.
  rows[4] = eq108_row("gimp", 64, 50, 0.0874 / 0.7564);
  rows[5] = eq108_row("mpm", 64, 50, 0.0874 / 0.7564);
  report = test_support::study_report("spectral", rows);
  EXPECT_FALSE(holds(report, "eq108-not-homogeneous"));
  // Without the E = 64 rows every run is at rest: the state claim holds.
  rows.resize(4);
  EXPECT_TRUE(holds(test_support::study_report("spectral", rows), "eq108-at-rest"));
}

// The particle count: the same E and particles per cell on other grids; a ratio that does not
// move with the grid, then one that falls as 1/sqrt(particles).
TEST(SpectralStudy, Eq108AgainstTheParticleCountIsReadFromTheRows) {
  std::vector<ojson> rows = {spectral_row("gimp", 0.95, 0.5), spectral_row("gimp", 1.05, 40)};
  rows[0]["particles"] = rows[1]["particles"] = 100;
  for (int cells : {25, 100, 200})
    rows.push_back(eq108_row("gimp", 1, cells, 0.0874 / 0.7564));
  auto report = test_support::study_report("spectral", rows);
  EXPECT_NE(report.markdown.find("for 1 of 1 schemes"), std::string::npos) << report.markdown;
  EXPECT_NE(report.markdown.find("| gimp | 25 | 50 | 0.116 | 0.817 |"), std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| gimp | 200 | 400 | 0.116 | 2.311 |"), std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("Refining the grid from 50 to 400 particles moves GIMP's ratio "
                                 "from 0.116 to 0.116 (fitted exponent against the particle "
                                 "count 0.000)"),
            std::string::npos)
      << report.markdown;
  EXPECT_TRUE(holds(report, "eq108-independent-of-grid"));
  for (std::size_t k = 2; k < rows.size(); ++k) {
    const double particles = rows[k]["particles"].get<double>();
    rows[k] = eq108_row("gimp", 1, rows[k]["cells"].get<int>(),
                        0.0874 / 0.7564 * std::sqrt(100 / particles));
  }
  report = test_support::study_report("spectral", rows);
  EXPECT_FALSE(holds(report, "eq108-independent-of-grid"));
  EXPECT_NE(report.markdown.find("| gimp | 200 | 400 | 0.058 | 1.155 |"), std::string::npos)
      << report.markdown;
}

// Every claim's template types no number: thresholds and counts are values.
TEST(SpectralStudy, ClaimTemplatesHoldNoHandTypedDigit) {
  const std::vector<ojson> rows = {spectral_row("gimp", 0.95, 0.5), spectral_row("gimp", 1.05, 40),
                                   eq108_row("gimp", 64, 50, 0.3)};
  const auto report = test_support::study_report("spectral", rows);
  EXPECT_EQ(report.claims.size(), 6u);
  for (const auto& c : report.claims) {
    EXPECT_EQ(hand_typed_digits(c.statement), "") << c.id;
    EXPECT_EQ(hand_typed_digits(c.evidence), "") << c.id;
    EXPECT_NO_THROW(render(c, c.evidence)) << c.id;
  }
}

// An edge row: dt_edge and dt_spectral in units of h / c = 0.02.
ojson edge_row(const char* method, double A, double edge, double limit) {
  ojson r = study_row(method, 1);
  r["A"] = A;
  r["cells"] = 50;
  r["dt_cfl"] = 0.02;
  r["dt_edge"] = edge * 0.02;
  r["dt_fail"] = edge * 1.005 * 0.02;
  r["dt_spectral"] = limit * 0.02;
  r["courant_spectral"] = limit;
  r["spectral_analysis"] = "bloch";
  return r;
}

TEST(SpectralEdgeStudy, AgreementHoldsWithinFivePercentAndTheAmplitudeTableShowsTheFall) {
  std::vector<ojson> rows = {edge_row("mpm", 1e-6, 0.7607, 0.7559),
                             edge_row("gimp", 1e-6, 0.70, 0.7559),  // 7.4% below: disagrees
                             edge_row("mpm", 0.015, 0.70, 0.7559),
                             edge_row("mpm", 0.05, 0.70, 0.7559)};
  test_support::meaningless_row(rows[2]);
  rows[3]["dt_edge"] = nullptr;  // no edge in the scan at A = 0.05
  const std::string md = test_support::study_report("spectral_edge", rows).markdown;
  EXPECT_NE(md.find("1 of 2 measured edges lie within 5% of the spectral limit"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| mpm | 0.7607 | 0.7645 | 0.7559 | bloch | 1.0064 | yes |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| gimp | 0.7000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.9260 | **no** |"), std::string::npos) << md;
  // mpm has two amplitudes: its row in the amplitude table, the meaningless edge marked.
  EXPECT_NE(md.find("| mpm | 1.006 | 0.926 * |"), std::string::npos) << md;
  // The lowest edge measured, and the amplitude at which none was found (lower still).
  EXPECT_NE(md.find("mpm: lowest measured 0.926 of the limit, at A = 0.015; no edge in the scan "
                    "at A = 0.05."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("## The measured edge against the spectral limit (A = 1e-6; c T = 1; 50 "
                    "cells; bar)"),
            std::string::npos)
      << md;
}

}  // namespace
}  // namespace mpmstab
