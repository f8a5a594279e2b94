#pragma once
// The subcommands of `hapscene`. Each returns its exit code (0 success, 1 failure) and
// throws InputError for invalid input (exit code 2).
#include <string>
#include <vector>

namespace hapscene {

int run_command(std::vector<std::string> args);
int probe_command(std::vector<std::string> args);
int bench_command(std::vector<std::string> args);
int validate_command(std::vector<std::string> args);
int plot_command(std::vector<std::string> args);
int test_command(std::vector<std::string> args);
int devices_command(std::vector<std::string> args);
int calibrate_command(std::vector<std::string> args);
int new_command(std::vector<std::string> args);

}  // namespace hapscene
