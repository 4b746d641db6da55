// Emissions outputs do not depend on how the run is split: grid_tls (signals, two-lane roads with lane
// changes, internal lanes) with emissions edgeData and laneData (internal lanes too) writes the same bytes
// with 1 and 2 threads and with its network in 3 parts. Asking for them changes nothing else: the FCD and
// tripinfo of the run are those of the run without them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

constexpr const char* kEmissionsAdd =
    "<additional>\n"
    "    <edgeData id=\"edges\" type=\"emissions\" file=\"edges.xml\" period=\"300\" "
    "withInternal=\"true\"/>\n"
    "    <laneData id=\"lanes\" type=\"emissions\" file=\"lanes.xml\" period=\"600\" "
    "excludeEmpty=\"true\"/>\n"
    "</additional>\n";

struct Outputs {
  std::string edges, lanes, fcd, tripinfo;
};

class EmissionIdentityTest : public ::testing::Test {
 protected:
  // grid_tls up to 900 s in its own folder `tag`, with `args`; with the emissions add-file unless `plain`.
  Outputs run(const std::string& tag, const std::vector<std::string>& args, bool plain = false) {
    const fs::path dir = tmp_.path() / tag;
    fs::create_directories(dir);
    std::vector<std::string> words{"run",
                                   std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg",
                                   "--end",
                                   "900",
                                   "--fcd-output",
                                   "fcd.xml",
                                   "--tripinfo-output",
                                   "tripinfo.xml"};
    if (!plain) {
      std::ofstream(dir / "emissions.add.xml") << kEmissionsAdd;
      words.insert(words.end(), {"-a", "emissions.add.xml"});
    }
    words.insert(words.end(), args.begin(), args.end());
    const test::CliResult r = test::run_lpsim(dir, words);
    EXPECT_EQ(r.exit_code, 0) << tag << ":\n" << r.err;
    return Outputs{test::read_file(dir / "edges.xml"), test::read_file(dir / "lanes.xml"),
                   test::read_file(dir / "fcd.xml"), test::read_file(dir / "tripinfo.xml")};
  }

  test::TempDir tmp_{"lpsim_emission_identity"};
};

TEST_F(EmissionIdentityTest, SameBytesWithAnyThreadsAndParts) {
  const Outputs one = run("threads1", {"--threads", "1"});
  EXPECT_GT(one.edges.size(), 10000u);
  EXPECT_NE(one.edges.find("CO2_perVeh"), std::string::npos);
  EXPECT_NE(one.lanes.find("<lane id="), std::string::npos);
  const Outputs two = run("threads2", {"--threads", "2"});
  EXPECT_TRUE(one.edges == two.edges) << "edgeData differs with 2 threads";
  EXPECT_TRUE(one.lanes == two.lanes) << "laneData differs with 2 threads";
  const Outputs parts = run("parts3", {"--parts", "3", "--parts.min-vehicles", "0"});
  EXPECT_TRUE(one.edges == parts.edges) << "edgeData differs in 3 parts";
  EXPECT_TRUE(one.lanes == parts.lanes) << "laneData differs in 3 parts";
}

TEST_F(EmissionIdentityTest, AskingForEmissionsChangesNoTrip) {
  const Outputs with = run("with", {});
  const Outputs without = run("without", {}, true);
  EXPECT_TRUE(with.fcd == without.fcd);
  EXPECT_TRUE(with.tripinfo == without.tripinfo);
}

}  // namespace
}  // namespace lpsim
