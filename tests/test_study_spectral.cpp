// The spectral study's report (experiments/studies/spectral.cpp), from synthetic rows: a scheme
// is confirmed only when its run below the limit stays bounded and its run above it grows.
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
  r["policy"] = "spectral";
  r["safety"] = safety;
  r["courant_spectral"] = 0.7564;
  r["max_error_over_time"] = error_over_A * 1e-6;
  return r;
}

TEST(SpectralStudy, ConfirmsALimitOnlyWhenBelowStaysBoundedAndAboveGrows) {
  std::vector<ojson> rows = {spectral_row("mpm", 0.95, 0.5), spectral_row("mpm", 1.05, 40),
                             spectral_row("gimp", 0.95, 0.5), spectral_row("gimp", 1.05, 2.0)};
  const std::string md = test_support::study_report("spectral", rows).markdown;
  EXPECT_NE(md.find("for 1 of 2 schemes; not for `gimp`"), std::string::npos) << md;
  EXPECT_NE(md.find("| mpm | 2 | 0.7564 | bounded (error 5.0e-1 A) | grew (error 4.0e1 A) | yes |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| gimp | 2 | 0.7564 | bounded (error 5.0e-1 A) | bounded (error 2.0 A) | "
                    "**no** |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("usl 0.756 to 0.756."), std::string::npos) << md;
}

}  // namespace
}  // namespace mpmstab
