// The spectral studies' reports (experiments/studies/spectral.cpp, spectral_edge.cpp), from
// synthetic rows: a scheme is confirmed only when its run below the limit stays bounded and its
// run above it grows; a measured edge agrees only within 5% of the limit.
#include <gtest/gtest.h>

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
  EXPECT_NE(md.find("for 1 of 2 schemes; not for `gimp`"), std::string::npos) << md;
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
  EXPECT_NE(md.find("Eq. (108) at the same state lies at 0.116 to 0.116 times the limit at this "
                    "E and grid only"),
            std::string::npos)
      << md;
}

bool holds(const StudyReport& r, const std::string& id) {
  for (const auto& c : r.claims)
    if (c.id == id) return c.holds;
  ADD_FAILURE() << "no claim " << id;
  return false;
}

// Eq. (108) against the limit at other E: the rows at another E are not schemes of the table,
// they measure how the ratio moves; the claims read them and flip with them.
TEST(SpectralStudy, Eq108RatioPerEIsReadFromTheRowsAndItsClaimsFlipWithThem) {
  std::vector<ojson> rows = {spectral_row("gimp", 0.95, 0.5), spectral_row("gimp", 1.05, 40)};
  ojson stiff = spectral_row("gimp", 0.95, 0.5);  // E = 64: eq. (108) at 0.3 of the limit
  stiff["E"] = 64.0;
  stiff["T"] = 2.5;
  stiff["dt_cfl"] = 0.02 / 8;
  stiff["dt_stable_min"] = 0.3 * 0.7564 * stiff["dt_cfl"].get<double>();
  rows.push_back(stiff);
  const auto report = test_support::study_report("spectral", rows);
  EXPECT_NE(report.markdown.find("for 1 of 1 schemes"), std::string::npos) << report.markdown;
  EXPECT_NE(report.markdown.find("| gimp | 64 | 3.00e-1 |"), std::string::npos) << report.markdown;
  EXPECT_TRUE(holds(report, "eq108-below-limit-every-E"));
  EXPECT_TRUE(holds(report, "eq108-not-homogeneous"));  // 0.116 against 0.3
  stiff["dt_stable_min"] = 1.2 * 0.7564 * stiff["dt_cfl"].get<double>();
  rows.back() = stiff;
  EXPECT_FALSE(holds(test_support::study_report("spectral", rows), "eq108-below-limit-every-E"));
  stiff["dt_stable_min"] = 0.0874 * stiff["dt_cfl"].get<double>();  // the same ratio as E = 1
  rows.back() = stiff;
  EXPECT_FALSE(holds(test_support::study_report("spectral", rows), "eq108-not-homogeneous"));
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
                             edge_row("mpm", 0.015, 0.70, 0.7559)};
  test_support::meaningless_row(rows[2]);
  const std::string md = test_support::study_report("spectral_edge", rows).markdown;
  EXPECT_NE(md.find("1 of 2 measured edges lie within 5% of the spectral limit"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| mpm | 0.7607 | 0.7645 | 0.7559 | bloch | 1.0064 | yes |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| gimp | 0.7000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.9260 | **no** |"), std::string::npos) << md;
  // mpm has two amplitudes: its row in the amplitude table, the meaningless edge marked.
  EXPECT_NE(md.find("| mpm | 1.006 | 0.926 * |"), std::string::npos) << md;
  EXPECT_NE(md.find("mpm: lowest 0.926 of the limit, at A = 0.015."), std::string::npos) << md;
}

}  // namespace
}  // namespace mpmstab
