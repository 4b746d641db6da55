// `lpsim <command> --help` (or -h) prints that command's usage and every option it takes, one line each,
// generated from the option table: every option listed is accepted by that command and options of other
// commands are not listed. `lpsim --help` keeps listing the commands.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "converters/cli_options.hpp"
#include "core/error.hpp"
#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

struct Case {
  std::string command;
  CliCommand id;
  std::vector<std::string> listed, not_listed;
};

const std::vector<Case> kCases = {
    {"run",
     CliCommand::Run,
     {"-c, --configuration-file",
      "-n, --net-file",
      "-r, --route-files",
      "-a, --additional-files",
      "-b, --begin",
      "-e, --end",
      "--step-length",
      "--seed",
      "--threads",
      "--time-to-teleport",
      "--ignore-route-errors",
      "--fcd-output",
      "--device.fcd.period",
      "--tripinfo-output",
      "--summary-output",
      "--statistic-output",
      "--edgedata-output",
      "--lanedata-output",
      "--device",
      "--max-lane-map-gb",
      "--lpsim-nodes",
      "--lpsim-od",
      "-W, --no-warnings",
      "--weights.minor-penalty"},
     {"--output"}},
    {"info",
     CliCommand::Info,
     {"-c, --configuration-file", "-n, --net-file", "-b, --begin", "--seed", "--lpsim-edges",
      "--ignore-route-errors"},
     {"--fcd-output", "--tripinfo-output", "--output", "--device DEVICE", "--time-to-teleport"}},
    {"convert",
     CliCommand::Convert,
     {"-o, --output", "-c, --configuration-file", "-n, --net-file", "-r, --route-files", "--threads"},
     {"--fcd-output", "--summary-output", "--device DEVICE"}},
};

TEST(CliHelpTest, EachCommandListsItsOwnOptions) {
  test::TempDir tmp("lpsim_help");
  for (const auto& c : kCases) {
    for (const std::string flag : {"--help", "-h"}) {
      SCOPED_TRACE(c.command + " " + flag);
      const auto r = test::run_lpsim(tmp.path(), {c.command, flag});
      EXPECT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(r.err, "");
      EXPECT_EQ(r.out.rfind("usage: lpsim " + c.command, 0), 0u) << r.out;
      for (const auto& o : c.listed)
        EXPECT_NE(r.out.find(o), std::string::npos) << o << " missing:\n" << r.out;
      for (const auto& o : c.not_listed)
        EXPECT_EQ(r.out.find(o), std::string::npos) << o << " listed:\n" << r.out;
    }
  }
  // Help wins wherever it stands among the command's options, even beside ones it would refuse.
  const auto r = test::run_lpsim(tmp.path(), {"run", "-c", "missing.sumocfg", "--help"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.rfind("usage: lpsim run", 0), 0u) << r.out;
}

TEST(CliHelpTest, EveryListedOptionIsAcceptedByItsCommandAndHasADescription) {
  for (const auto& c : kCases) {
    const std::string help = describe_options(c.id);
    size_t start = 0, lines = 0;
    while (start < help.size()) {
      const size_t nl = help.find('\n', start);
      const std::string line = help.substr(start, nl - start);
      start = nl + 1;
      ++lines;
      SCOPED_TRACE(c.command + ": " + line);
      const size_t at = line.find("--");
      ASSERT_NE(at, std::string::npos);
      const std::string name = line.substr(at, line.find(' ', at) - at);
      const std::string meta =
          line.substr(at + name.size() + 1, line.find(' ', at + name.size() + 1) - at - name.size() - 1);
      const std::string value = meta == "FILE" || meta == "FILE[,FILE]" ? "x.xml"
                                : meta == "DEVICE"                      ? "cpu"
                                : meta == "METHOD"                      ? "metis"
                                : meta == "ALGORITHM"                   ? "CH"
                                : meta == "[BOOL]"                      ? "true"
                                                                        : "1";
      if (name == "--configuration-file") continue;  // reads the file
      EXPECT_NO_THROW(parse_cli_options({name, value}, nullptr, c.id));
      EXPECT_GT(line.size(), line.find(meta) + meta.size() + 4) << "no description";
    }
    EXPECT_GE(lines, c.listed.size());
  }
  // An option of another command is refused by this one.
  EXPECT_THROW(parse_cli_options({"--fcd-output", "f.xml"}, nullptr, CliCommand::Info), InputError);
  EXPECT_THROW(parse_cli_options({"-o", "f.lpsim"}, nullptr, CliCommand::Run), InputError);
}

// -h, --help and -? ask for help where an option may stand; as an option's value they are that value (before,
// `--sumo-args --help` printed lpsim's help instead of reaching SUMO).
TEST(CliHelpTest, HelpAsAnOptionsValueIsAValue) {
  EXPECT_TRUE(help_requested({"-c", "a.sumocfg", "--help"}));
  EXPECT_TRUE(help_requested({"--no-step-log", "-h"}));
  EXPECT_TRUE(help_requested({"--end", "-?"}));  // a time cannot be "-?": asked for help, as the parser says
  EXPECT_FALSE(help_requested({"--sumo-args", "--help"}));
  EXPECT_FALSE(help_requested({"--sumo-args", "-h", "--end", "10"}));
  EXPECT_FALSE(help_requested({"--sumo-args=--help"}));
  EXPECT_FALSE(help_requested({"--", "--help"}));
  EXPECT_TRUE(help_requested({"--sumo-args", "--help", "--help"}));
  test::TempDir tmp("lpsim_help_value");
  const auto r = test::run_lpsim(tmp.path(), {"run", "--sumo-args", "--help"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'--sumo-args' is not used by this command"), std::string::npos) << r.err;
}

TEST(CliHelpTest, TopLevelHelpListsTheCommands) {
  test::TempDir tmp("lpsim_help");
  const auto r = test::run_lpsim(tmp.path(), {"--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const std::string c : {"info", "convert", "run", "version", "lpsim <command> --help"})
    EXPECT_NE(r.out.find(c), std::string::npos) << c;
}

}  // namespace
}  // namespace lpsim
