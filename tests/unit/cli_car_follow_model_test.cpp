// --default.carfollowmodel as SUMO takes it: on the command line or in the .sumocfg, it decides the model of
// the vTypes that name none (Krauss without it), the snapshot keeps the model `lpsim convert` gave each
// vType, and beside a snapshot the option is refused (it acts while loading). The bundled grid_tls scenario
// (its vTypes name no model).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lpsim_cli.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::CliResult;
using test::read_file;

const std::string kGrid = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/";

class CliCarFollowModelTest : public ::testing::Test {
 protected:
  CliResult run(const std::vector<std::string>& args) const { return test::run_lpsim(tmp_.path(), args); }

  // The tripinfo of grid_tls run with `extra` options (net and routes from the bundled folder).
  std::string tripinfo(const std::vector<std::string>& input, const std::vector<std::string>& extra) {
    std::vector<std::string> args{"run"};
    args.insert(args.end(), input.begin(), input.end());
    args.insert(args.end(), {"--no-step-log", "--tripinfo-output", "t.xml"});
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = run(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_file(tmp_.path() / "t.xml");
  }

  const std::vector<std::string> files_{"-n", kGrid + "grid_tls.net.xml", "-r", kGrid + "grid_tls.rou.xml"};
  test::TempDir tmp_{"lpsim_cf_model"};
};

TEST_F(CliCarFollowModelTest, OptionOrSumocfgChoosesTheModel) {
  const std::string krauss = tripinfo(files_, {});
  const std::string idm = tripinfo(files_, {"--default.carfollowmodel", "IDM"});
  EXPECT_FALSE(krauss.empty());
  EXPECT_NE(krauss, idm);
  EXPECT_EQ(tripinfo(files_, {"--default.carfollowmodel", "Krauss"}), krauss);
  // An unimplemented model runs the IDM (and warns, cli_model_warnings_test).
  EXPECT_EQ(tripinfo(files_, {"--default.carfollowmodel", "EIDM"}), idm);
  // The same option in a .sumocfg's processing section.
  tmp_.write("idm.sumocfg", "<configuration>\n<input>\n<net-file value=\"" + kGrid +
                                "grid_tls.net.xml\"/>\n<route-files value=\"" + kGrid +
                                "grid_tls.rou.xml\"/>\n</input>\n<processing>\n"
                                "<default.carfollowmodel value=\"IDM\"/>\n</processing>\n</configuration>\n");
  EXPECT_EQ(tripinfo({"-c", "idm.sumocfg"}, {}), idm);
  // The command line overrides the .sumocfg.
  EXPECT_EQ(tripinfo({"-c", "idm.sumocfg"}, {"--default.carfollowmodel", "Krauss"}), krauss);
}

TEST_F(CliCarFollowModelTest, SnapshotKeepsTheModelAndRefusesTheOptionBesideIt) {
  const std::string idm = tripinfo(files_, {"--default.carfollowmodel", "IDM"});
  std::vector<std::string> convert{"convert", "-o", "idm.lpsim", "--default.carfollowmodel", "IDM"};
  convert.insert(convert.begin() + 1, files_.begin(), files_.end());
  ASSERT_EQ(run(convert).exit_code, 0);
  EXPECT_EQ(tripinfo({"idm.lpsim"}, {}), idm);
  const CliResult beside = run({"run", "idm.lpsim", "--default.carfollowmodel", "IDM"});
  EXPECT_EQ(beside.exit_code, 2);
  EXPECT_NE(beside.err.find("--default.carfollowmodel given beside the snapshot"), std::string::npos)
      << beside.err;
}

TEST_F(CliCarFollowModelTest, AnEmptyModelNameIsRefused) {
  std::vector<std::string> args{"info", "--default.carfollowmodel", ""};
  args.insert(args.end(), files_.begin(), files_.end());
  const CliResult r = run(args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--default.carfollowmodel: expected a model name"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace lpsim
