// Outputs of `lpsim run` on bundled scenarios: valid against SUMO's XSDs (when xmllint and the XSDs are
// installed), gzip outputs equal to the plain ones, and consistent with each other and with the run's
// printed summary (one tripinfo per arrival, edgeData totals, summary counts).
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "app/scenario.hpp"
#include "converters/cli_options.hpp"
#include "sumo_schema.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

namespace fs = std::filesystem;

const char* const kXsdDir = test::kSumoXsdDir;

// Reads a plain or gzip file (gzread passes plain files through unchanged).
std::string read_all(const fs::path& file) {
  gzFile gz = gzopen(file.c_str(), "rb");
  if (gz == nullptr) return {};
  std::string content;
  char chunk[1 << 16];
  int n;
  while ((n = gzread(gz, chunk, sizeof chunk)) > 0) content.append(chunk, static_cast<size_t>(n));
  gzclose(gz);
  return content;
}

bool is_gzip(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char magic[2] = {0, 0};
  in.read(reinterpret_cast<char*>(magic), 2);
  return magic[0] == 0x1f && magic[1] == 0x8b;
}

std::string mask_duration(const std::string& summary) {
  static const std::regex duration(" duration=\"[^\"]*\"");
  return std::regex_replace(summary, duration, " duration=\"masked\"");
}

std::vector<std::string> lines_starting(const std::string& content, const std::string& prefix) {
  std::vector<std::string> out;
  std::istringstream in(content);
  std::string line;
  while (std::getline(in, line)) {
    const size_t first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.compare(first, prefix.size(), prefix) == 0) out.push_back(line);
  }
  return out;
}

// The value of attribute `name` in one element line ("" when absent).
std::string attr(const std::string& line, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const size_t at = line.find(key);
  if (at == std::string::npos) return {};
  const size_t begin = at + key.size();
  return line.substr(begin, line.find('"', begin) - begin);
}

double num(const std::string& line, const std::string& name) { return std::stod(attr(line, name)); }

// A number printed by `lpsim run` on stdout after `label` (e.g. " Arrived: ").
long long printed_count(const std::string& log, const std::string& label) {
  const size_t at = log.find(label);
  if (at == std::string::npos) return -1;
  return std::stoll(log.substr(at + label.size()));
}

struct OutputSet {
  fs::path fcd, tripinfo, edgedata, lanedata, summary;
};

// Both runs of one scenario (plain and gzip outputs), made once for all tests of the suite.
struct ScenarioRun {
  fs::path dir;
  OutputSet plain, gz;
  std::string log;
  bool ok = false;
};

class EngineOutputsTest : public ::testing::TestWithParam<std::string> {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new test::TempDir("lpsim_outputs");
    runs_ = new std::map<std::string, ScenarioRun>();
  }
  static void TearDownTestSuite() {
    delete tmp_;
    delete runs_;
    tmp_ = nullptr;
    runs_ = nullptr;
  }

  static OutputSet outputs_in(const fs::path& d, const std::string& ext) {
    return OutputSet{d / ("fcd.xml" + ext), d / ("tripinfo.xml" + ext), d / ("edgedata.xml" + ext),
                     d / ("lanedata.xml" + ext), d / ("summary.xml" + ext)};
  }

  // Edge speeds are never sampled (adaptation interval 0): trips keep the routes they were loaded with,
  // which the counters are checked against (flows_from_routes).
  static int run_binary(const std::string& scenario, const OutputSet& o, const fs::path& log) {
    const std::string cfg = std::string(LPSIM_SCENARIOS_DIR) + "/" + scenario + "/" + scenario + ".sumocfg";
    const std::string cmd = std::string(LPSIM_BINARY) + " run " + cfg +
                            " --threads 1 --device.rerouting.adaptation-interval 0 --fcd-output " +
                            o.fcd.string() + " --tripinfo-output " + o.tripinfo.string() +
                            " --edgedata-output " + o.edgedata.string() + " --lanedata-output " +
                            o.lanedata.string() + " --summary-output " + o.summary.string() + " > " +
                            log.string() + " 2>&1";
    return std::system(cmd.c_str());
  }

  // The runs of the test's scenario (made on first use).
  const ScenarioRun& run() {
    ScenarioRun& r = (*runs_)[GetParam()];
    if (!r.dir.empty()) return r;
    r.dir = tmp_->path() / GetParam();
    fs::create_directories(r.dir / "plain");
    fs::create_directories(r.dir / "gz");
    r.plain = outputs_in(r.dir / "plain", "");
    r.gz = outputs_in(r.dir / "gz", ".gz");
    const int rc_plain = run_binary(GetParam(), r.plain, r.dir / "plain.log");
    const int rc_gz = run_binary(GetParam(), r.gz, r.dir / "gz.log");
    r.log = read_all(r.dir / "plain.log");
    EXPECT_EQ(rc_plain, 0) << r.log;
    EXPECT_EQ(rc_gz, 0) << read_all(r.dir / "gz.log");
    r.ok = rc_plain == 0 && rc_gz == 0;
    return r;
  }

  static inline test::TempDir* tmp_ = nullptr;
  static inline std::map<std::string, ScenarioRun>* runs_ = nullptr;
};

TEST_P(EngineOutputsTest, OutputsValidateAgainstSumoSchemas) {
  if (std::system("xmllint --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "xmllint not installed";
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const std::vector<std::pair<fs::path, std::string>> files{{r.plain.fcd, "fcd_file.xsd"},
                                                            {r.plain.tripinfo, "tripinfo_file.xsd"},
                                                            {r.plain.edgedata, "meandata_file.xsd"},
                                                            {r.plain.lanedata, "meandata_file.xsd"},
                                                            {r.plain.summary, "summary_file.xsd"}};
  for (const auto& [file, xsd] : files) {
    const fs::path schema = fs::path(kXsdDir) / xsd;
    if (!fs::exists(schema)) GTEST_SKIP() << schema << " not installed";
    const fs::path log = r.dir / ("xmllint_" + file.filename().string() + ".log");
    const std::string cmd = "xmllint --noout --schema " + test::usable_sumo_schema(schema.string(), *tmp_) +
                            " " + file.string() + " > " + log.string() + " 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << file << " fails " << xsd << ":\n"
                                           << read_all(log).substr(0, 2000);
  }
}

TEST_P(EngineOutputsTest, GzipOutputsEqualPlainOnes) {
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const std::vector<std::pair<fs::path, fs::path>> pairs{{r.plain.fcd, r.gz.fcd},
                                                         {r.plain.tripinfo, r.gz.tripinfo},
                                                         {r.plain.edgedata, r.gz.edgedata},
                                                         {r.plain.lanedata, r.gz.lanedata}};
  for (const auto& [plain, gz] : pairs) {
    EXPECT_FALSE(is_gzip(plain)) << plain;
    EXPECT_TRUE(is_gzip(gz)) << gz;
    const std::string text = read_all(plain);
    EXPECT_GT(text.size(), 200u) << plain;
    EXPECT_TRUE(text == read_all(gz)) << gz << " does not uncompress to " << plain;
  }
  EXPECT_TRUE(is_gzip(r.gz.summary));
  EXPECT_TRUE(mask_duration(read_all(r.plain.summary)) == mask_duration(read_all(r.gz.summary)));
}

TEST_P(EngineOutputsTest, OneTripinfoPerArrivedVehicle) {
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const std::vector<std::string> trips = lines_starting(read_all(r.plain.tripinfo), "<tripinfo ");
  const std::vector<std::string> steps = lines_starting(read_all(r.plain.summary), "<step ");
  ASSERT_FALSE(steps.empty());
  const long long arrived = std::stoll(attr(steps.back(), "arrived"));
  EXPECT_EQ(static_cast<long long>(trips.size()), arrived);
  EXPECT_EQ(printed_count(r.log, " Arrived: "), arrived);
  EXPECT_EQ(std::stoll(attr(steps.back(), "loaded")), arrived) << "every vehicle of the scenario arrives";
  std::set<std::string> ids;
  double previous_arrival = 0;
  for (const std::string& t : trips) {
    EXPECT_TRUE(ids.insert(attr(t, "id")).second) << "second tripinfo for " << attr(t, "id");
    const double depart = num(t, "depart"), arrival = num(t, "arrival");
    EXPECT_GT(arrival, depart) << t;
    EXPECT_NEAR(num(t, "duration"), arrival - depart, 0.011) << t;
    EXPECT_GE(arrival, previous_arrival) << "tripinfos are written in order of arrival: " << t;
    EXPECT_GT(num(t, "routeLength"), 0) << t;
    EXPECT_EQ(attr(t, "vaporized"), "") << t;
    previous_arrival = arrival;
  }
}

TEST_P(EngineOutputsTest, SummaryCountsAddUp) {
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const std::vector<std::string> steps = lines_starting(read_all(r.plain.summary), "<step ");
  ASSERT_GT(steps.size(), 100u);
  long long last_arrived = 0, last_inserted = 0;
  for (size_t k = 0; k < steps.size(); ++k) {
    const std::string& s = steps[k];
    EXPECT_NEAR(num(s, "time"), static_cast<double>(k), 1e-9) << "one row per 1 s step";
    const long long inserted = std::stoll(attr(s, "inserted")), running = std::stoll(attr(s, "running"));
    const long long ended = std::stoll(attr(s, "ended")), arrived = std::stoll(attr(s, "arrived"));
    EXPECT_EQ(std::stoll(attr(s, "teleports")), 0) << s;
    EXPECT_EQ(inserted, running + ended) << s;
    EXPECT_EQ(ended, arrived) << s;
    EXPECT_LE(inserted + std::stoll(attr(s, "waiting")), std::stoll(attr(s, "loaded"))) << s;
    EXPECT_GE(arrived, last_arrived) << s;
    EXPECT_GE(inserted, last_inserted) << s;
    EXPECT_LE(std::stoll(attr(s, "halting")), running) << s;
    last_arrived = arrived;
    last_inserted = inserted;
  }
  EXPECT_EQ(printed_count(r.log, " Inserted: "), last_inserted);
}

// Per edge: the vehicles whose route starts there (departed), ends there (arrived), reaches it from
// upstream (entered) or moves on downstream (left), from the scenario's routes. In a run where every
// vehicle arrives without a teleport, each vehicle drives each edge of its route once.
struct EdgeFlows {
  std::map<std::string, long long> departed, arrived, entered, left;
};

EdgeFlows flows_from_routes(const std::string& scenario) {
  const std::string cfg = std::string(LPSIM_SCENARIOS_DIR) + "/" + scenario + "/" + scenario + ".sumocfg";
  const Scenario sc = load_scenario(parse_cli_options({"-c", cfg}));
  EdgeFlows f;
  for (uint32_t v = 0; v < sc.demand.size(); ++v) {
    const uint32_t n = sc.demand.route_length[v];
    for (uint32_t k = 0; k < n; ++k) {
      const std::string& e = sc.network.edge_id[sc.demand.route_edges[sc.demand.route_begin[v] + k]];
      ++(k == 0 ? f.departed : f.entered)[e];
      ++(k + 1 == n ? f.arrived : f.left)[e];
    }
  }
  return f;
}

// The edges whose edgeData `counter` differs from `expected` (missing edges count 0), as text.
std::string counter_mismatches(const fs::path& edgedata, const std::string& counter,
                               const std::map<std::string, long long>& expected) {
  const std::string text = read_all(edgedata);
  EXPECT_EQ(lines_starting(text, "<interval ").size(), 1u) << edgedata;
  std::map<std::string, long long> got;
  for (const std::string& e : lines_starting(text, "<edge "))
    got[attr(e, "id")] = std::stoll(attr(e, counter));
  std::string out;
  size_t shown = 0, wrong = 0;
  auto check = [&](const std::string& edge) {
    const long long want = expected.count(edge) ? expected.at(edge) : 0,
                    have = got.count(edge) ? got.at(edge) : 0;
    if (want == have) return;
    if (++wrong, shown++ < 5)
      out += " " + edge + ": " + std::to_string(have) + " (expected " + std::to_string(want) + ")";
  };
  std::set<std::string> edges;
  for (const auto& [e, n] : got) edges.insert(e);
  for (const auto& [e, n] : expected) edges.insert(e);
  for (const std::string& e : edges) check(e);
  return wrong == 0 ? "" : counter + " wrong on " + std::to_string(wrong) + " edges:" + out;
}

TEST_P(EngineOutputsTest, EdgeDataArrivalsFollowTheRoutes) {
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const EdgeFlows f = flows_from_routes(GetParam());
  EXPECT_EQ(counter_mismatches(r.plain.edgedata, "arrived", f.arrived), "");
  long long total = 0;
  for (const auto& [e, n] : f.arrived) total += n;
  EXPECT_EQ(printed_count(r.log, " Arrived: "), total);
}

// Departures at the begin time belong to the first interval; leaving an edge is counted on the normal
// lane left (not on the junction-internal lane the front was on); lane changes are neither.
TEST_P(EngineOutputsTest, EdgeDataDeparturesEntriesAndExitsFollowTheRoutes) {
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const EdgeFlows f = flows_from_routes(GetParam());
  EXPECT_EQ(counter_mismatches(r.plain.edgedata, "departed", f.departed), "");
  EXPECT_EQ(counter_mismatches(r.plain.edgedata, "entered", f.entered), "");
  EXPECT_EQ(counter_mismatches(r.plain.edgedata, "left", f.left), "");
}

TEST_P(EngineOutputsTest, LaneDataSumsToEdgeData) {
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const std::vector<std::string> edges = lines_starting(read_all(r.plain.edgedata), "<edge ");
  std::map<std::string, long long> arrived_by_edge;
  std::map<std::string, double> sampled_by_edge;
  std::string edge;
  for (const std::string& line : lines_starting(read_all(r.plain.lanedata), "<")) {
    if (line.find("<edge ") != std::string::npos) edge = attr(line, "id");
    if (line.find("<lane ") == std::string::npos) continue;
    arrived_by_edge[edge] += std::stoll(attr(line, "arrived"));
    sampled_by_edge[edge] += num(line, "sampledSeconds");
  }
  ASSERT_FALSE(edges.empty());
  for (const std::string& e : edges) {
    const std::string id = attr(e, "id");
    EXPECT_EQ(arrived_by_edge[id], std::stoll(attr(e, "arrived"))) << id;
    EXPECT_NEAR(sampled_by_edge[id], num(e, "sampledSeconds"), 0.011 * 4) << id;
  }
}

// Summary means follow SUMO: meanTravelTime over arrived vehicles, meanWaitingTime the mean insertion delay.
TEST_P(EngineOutputsTest, SummaryMeansMatchTripinfo) {
  const ScenarioRun& r = run();
  ASSERT_TRUE(r.ok);
  const std::vector<std::string> trips = lines_starting(read_all(r.plain.tripinfo), "<tripinfo ");
  const std::vector<std::string> steps = lines_starting(read_all(r.plain.summary), "<step ");
  ASSERT_FALSE(trips.empty());
  double duration = 0, delay = 0;
  for (const std::string& t : trips) {
    duration += num(t, "duration");
    delay += num(t, "departDelay");
  }
  const double n = static_cast<double>(trips.size());
  EXPECT_NEAR(num(steps.back(), "meanTravelTime"), duration / n, 0.01);
  EXPECT_NEAR(num(steps.back(), "meanWaitingTime"), delay / n, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Bundled, EngineOutputsTest, ::testing::Values("random_net", "grid_tls"),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace lpsim
