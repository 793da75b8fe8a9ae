// Readers never crash: plot and index on a results file that is not what a sweep writes answer
// with a message naming the file and exit 2, and write nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;
using test_support::run_mpmstab;

TEST(Readers, PlotAndIndexRefuseAResultsFileThatIsNotASweepsAndWriteNothing) {
  const fs::path dir =
      fs::temp_directory_path() / ("mpmstab_readers_" + std::to_string(::getpid()));
  fs::create_directories(dir / "experiments");
  fs::create_directories(dir / "out");
  std::ofstream(dir / "experiments/f.json")
      << R"({"name": "f", "report": "figure", "record": ["history"], "cases": [{"method":
      "gimp", "E": 1e4, "A": 0.06, "dt": 1e-3, "T": 0.01, "cells": 20}]})";
  fs::copy_file(fs::path(MPMSTAB_SOURCE_DIR) / "experiments/fig3.gp", dir / "experiments/f.gp");
  std::ofstream(dir / "out/f_data.csv") << "step,time,error,dt_stable,crossings\n1,1,1,1,1\n";
  const std::string spec = (dir / "experiments/f.json").string();
  const std::string out = (dir / "out").string();
  const std::vector<std::string> docs = {R"({"cases": []})",
                                         R"({"cases": [{}]})",
                                         R"({})",
                                         R"([])",
                                         "garbage",
                                         R"({"cases": [{"method": 1}]})",
                                         R"({"cases": "x"})",
                                         R"({"cases": [], "study": 3})"};
  for (const auto& doc : docs) {
    std::ofstream(dir / "out/f.json") << doc;
    for (const char* command : {"plot", "index"}) {
      const auto o = run_mpmstab(std::string(command) + " " + spec + " --out " + out);
      EXPECT_EQ(o.status, 2) << command << " on " << doc << "\n" << o.output;
      EXPECT_NE(o.output.find("f.json"), std::string::npos) << o.output;
      EXPECT_EQ(o.output.find("internal error"), std::string::npos) << o.output;
    }
    EXPECT_FALSE(fs::exists(dir / "out/f.png")) << doc;
    EXPECT_FALSE(fs::exists(dir / "out/README.md")) << doc;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mpmstab
