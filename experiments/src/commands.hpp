// The subcommands of build/mpmstab. Each returns the process exit status and throws
// cli::UsageError for bad input (status 2, printed by main).
#pragma once

#include <string_view>
#include <vector>

namespace mpmstab::cli {

int cmd_run(const std::vector<std::string_view>& args);
int cmd_edge(const std::vector<std::string_view>& args);
int cmd_sweep(const std::vector<std::string_view>& args);
int cmd_index(const std::vector<std::string_view>& args);
int cmd_plot(const std::vector<std::string_view>& args);
int cmd_performance(const std::vector<std::string_view>& args);
int cmd_compare(const std::vector<std::string_view>& args);
int cmd_check(const std::vector<std::string_view>& args);
int cmd_bless(const std::vector<std::string_view>& args);

}  // namespace mpmstab::cli
