// The subcommands of build/mpmstab. Each returns the process exit status and throws
// cli::UsageError for bad input (status 2, printed by main).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "args.hpp"
#include "spec.hpp"

namespace mpmstab::cli {

int cmd_run(const std::vector<std::string_view>& args);
int cmd_edge(const std::vector<std::string_view>& args);
int cmd_advise(const std::vector<std::string_view>& args);
int cmd_documents(const std::vector<std::string_view>& args);
int cmd_spectral(const std::vector<std::string_view>& args);
int cmd_sweep(const std::vector<std::string_view>& args);
int cmd_reproduce(const std::vector<std::string_view>& args);
int cmd_index(const std::vector<std::string_view>& args);
int cmd_plot(const std::vector<std::string_view>& args);
int cmd_performance(const std::vector<std::string_view>& args);
int cmd_compare(const std::vector<std::string_view>& args);
int cmd_check(const std::vector<std::string_view>& args);
int cmd_bless(const std::vector<std::string_view>& args);
int cmd_merge(const std::vector<std::string_view>& args);
int cmd_slurm(const std::vector<std::string_view>& args);
int cmd_list(const std::vector<std::string_view>& args);
int cmd_build_time(const std::vector<std::string_view>& args);
int cmd_cluster_time(const std::vector<std::string_view>& args);

// Shared by the commands that read specs and write reports.
int default_jobs();                                                        // the machine's cores
std::vector<Spec> load_specs(const std::vector<std::string_view>& paths);  // UsageError if bad
// --out (default results): checked (a folder, or absent under a writable one), not made: the
// first file written makes it, so a refused command leaves no folder behind.
std::filesystem::path output_folder(const Args& args);
// Makes the --out folder, once every argument and input was checked (UsageError if it cannot).
void make_output_folder(const std::filesystem::path& out);
bool omit_timing(const Args& args);  // --timing keep|omit (default keep)
// The specs of tier `tier` ("paper" or "studies") in DIR, in the order `mpmstab list --tier`
// prints them (UsageError for another tier or a bad spec).
std::vector<std::string> tier_spec_paths(const std::filesystem::path& dir, std::string_view tier);
// Positional arguments <spec>... <folder>... (merge, reproduce --follow-ups): the specs are the
// arguments before the first folder, the folders the rest; UsageError unless there is at least
// one of each and every argument after the first folder is one.
struct SpecsAndFolders {
  std::vector<std::string_view> specs;
  std::vector<std::filesystem::path> folders;
};
SpecsAndFolders specs_and_folders(const std::vector<std::string_view>& positional);

}  // namespace mpmstab::cli
