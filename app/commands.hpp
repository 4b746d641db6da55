#pragma once
// The sub-commands of the lpsim CLI. Each takes the arguments after its name and returns the exit status;
// bad input is raised as InputError (the caller prints it and exits with 2).
#include <string>
#include <vector>

namespace lpsim {

int command_info(const std::vector<std::string>& args);
int command_convert(const std::vector<std::string>& args);
int command_run(const std::vector<std::string>& args);
int command_partition(const std::vector<std::string>& args);
int command_assign(const std::vector<std::string>& args);

/// `lpsim <command> --help`: the command's usage and every option it takes, one line each (from the
/// option table, so it cannot drift from what is parsed). Empty for a name that is not a command with
/// options.
std::string command_help(const std::string& command);

}  // namespace lpsim
