// The partitioners of `lpsim partition` on a bundled scenario: the junction graph and its weights, each
// method's parts (in range, none empty, the same for the same seed), the partition file read back, and
// every bad partition file refused with file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

#include "app/partition_resolution.hpp"
#include "app/scenario.hpp"
#include "converters/cli_options.hpp"
#include "converters/partition_file.hpp"
#include "core/error.hpp"
#include "lpsim_cli.hpp"
#include "partition/junction_graph.hpp"
#include "partition/kmeans.hpp"
#include "partition/part_cells.hpp"
#include "partition/part_plan.hpp"
#include "partition/partition_layout.hpp"
#include "partition/partition_method.hpp"
#include "partition/partition_summary.hpp"
#include "temp_dir.hpp"

namespace lpsim {
namespace {

using test::TempDir;

const std::string kConfig = std::string(LPSIM_SCENARIOS_DIR) + "/grid_tls/grid_tls.sumocfg";

const Scenario& grid() {
  static const Scenario sc = load_scenario(parse_cli_options({"-c", kConfig}));
  return sc;
}

// The lane parts of the grid's METIS partition into k parts.
std::vector<int32_t> metis_lane_parts(int32_t k, uint64_t seed) {
  const Scenario& sc = grid();
  const JunctionGraph g = build_junction_graph(sc.network, sc.demand, 1.0);
  return lane_parts(sc.network, edge_parts_from_junctions(
                                    sc.network, partition_junctions(g, k, PartitionMethod::Metis, seed)));
}

TEST(PartitionTest, JunctionGraphIsSymmetricAndWeighsTheDemand) {
  const Scenario& sc = grid();
  const JunctionGraph g = build_junction_graph(sc.network, sc.demand, 1.0);
  // One vertex per junction but SUMO's internal ones.
  uint32_t real = 0;
  for (const JunctionType t : sc.network.junction_type) real += t != JunctionType::Internal ? 1 : 0;
  ASSERT_EQ(g.num_vertices(), real);
  ASSERT_EQ(g.junction.size(), real);
  std::set<std::pair<int32_t, int32_t>> pairs;
  for (uint32_t u = 0; u < g.num_vertices(); ++u)
    for (int32_t a = g.adj_begin[u]; a < g.adj_begin[u + 1]; ++a) {
      EXPECT_NE(g.adj[static_cast<size_t>(a)], static_cast<int32_t>(u));
      EXPECT_GE(g.adj_weight[static_cast<size_t>(a)], 1);
      pairs.insert({static_cast<int32_t>(u), g.adj[static_cast<size_t>(a)]});
    }
  for (const auto& [u, v] : pairs) EXPECT_TRUE(pairs.count({v, u})) << u << " " << v;
  // Every route's every edge adds its free-flow steps to the junction it leads to.
  int64_t expected = g.num_vertices(), total = 0;
  for (uint32_t v = 0; v < sc.demand.size(); ++v)
    for (uint32_t i = 0; i < sc.demand.route_length[v]; ++i)
      expected += free_flow_steps(sc.network, sc.demand.route_edges[sc.demand.route_begin[v] + i], 1.0);
  for (int64_t w : g.vertex_weight) total += w;
  EXPECT_EQ(total, expected);
}

// A run's measured load in place of the routes: each junction weighs the vehicle-steps measured on the roads
// leading to it, each link between two junctions the vehicles that entered its roads (both directions).
TEST(PartitionTest, JunctionGraphWeighsAMeasuredLoad) {
  const Network& net = grid().network;
  MeasuredLoad m{std::vector<double>(net.num_edges(), 0), std::vector<int64_t>(net.num_edges(), 0)};
  std::map<uint32_t, int64_t> steps;                    // by junction
  std::map<std::pair<uint32_t, uint32_t>, int64_t> in;  // by pair of junctions, the smaller first
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    if (net.edge_is_internal[e]) continue;
    m.vehicle_seconds[e] =
        7.0 * (e % 5) + 0.3;  // at a 0.5 s step: 14 (e % 5) + 1 vehicle-steps (0.6 rounds up)
    m.entered[e] = e % 3;
    const auto from = static_cast<uint32_t>(net.edge_from_junction[e]),
               to = static_cast<uint32_t>(net.edge_to_junction[e]);
    steps[to] += 14 * (e % 5) + 1;
    in[std::pair{std::min(from, to), std::max(from, to)}] += e % 3;
  }
  const JunctionGraph g = build_junction_graph(net, m, 0.5);
  ASSERT_EQ(g.num_vertices(), build_junction_graph(net, grid().demand, 1.0).num_vertices());
  for (uint32_t u = 0; u < g.num_vertices(); ++u) {
    const uint32_t j = g.junction[u];
    EXPECT_EQ(g.vertex_weight[u], 1 + steps[j]) << net.junction_id[j];
    for (int32_t a = g.adj_begin[u]; a < g.adj_begin[u + 1]; ++a) {
      const uint32_t other = g.junction[static_cast<uint32_t>(g.adj[static_cast<size_t>(a)])];
      const std::pair<uint32_t, uint32_t> key{std::min(j, other), std::max(j, other)};
      EXPECT_EQ(g.adj_weight[static_cast<size_t>(a)], 1 + in[key])
          << net.junction_id[j] << " " << net.junction_id[other];
    }
  }
}

TEST(PartitionTest, EveryMethodGivesKNonEmptyPartsDeterministically) {
  const Scenario& sc = grid();
  const JunctionGraph g = build_junction_graph(sc.network, sc.demand, 1.0);
  for (PartitionMethod m : {PartitionMethod::Metis, PartitionMethod::Leiden, PartitionMethod::Random}) {
    for (int32_t k : {1, 2, 4}) {
      const std::vector<int32_t> a = partition_junctions(g, k, m, 7), b = partition_junctions(g, k, m, 7);
      EXPECT_EQ(a, b) << partition_method_name(m) << " K=" << k;
      std::vector<int> count(static_cast<size_t>(k), 0);
      for (int32_t p : a) {
        ASSERT_GE(p, 0);
        ASSERT_LT(p, k);
        ++count[static_cast<size_t>(p)];
      }
      for (int32_t p = 0; p < k; ++p) EXPECT_GT(count[static_cast<size_t>(p)], 0) << partition_method_name(m);
    }
  }
  // The parts are counted in real junctions (grid_tls: 25 of its 145; the others are SUMO's internal ones,
  // which no road leads to): K may be 25, not 26, and the summary counts 25 junctions.
  const auto most = static_cast<int32_t>(g.num_vertices());
  EXPECT_EQ(most, 25);
  const PartitionSummary s = summarize_partition(
      sc.network, sc.demand, partition_junctions(g, most, PartitionMethod::Random, 1), most, 1.0);
  uint32_t junctions = 0;
  for (const auto& p : s.parts) junctions += p.junctions;
  EXPECT_EQ(junctions, 25u);
  try {
    partition_junctions(g, most + 1, PartitionMethod::Metis, 1);
    ADD_FAILURE() << "26 parts of 25 junctions accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the network has 25"), std::string::npos) << e.what();
  }
  EXPECT_THROW(partition_junctions(g, 0, PartitionMethod::Metis, 1), InputError);
  EXPECT_THROW(partition_junctions(g, static_cast<int32_t>(g.num_vertices()) + 1, PartitionMethod::Metis, 1),
               InputError);
}

TEST(PartitionTest, MetisBalancesAndCutsLessThanRandom) {
  const Scenario& sc = grid();
  const JunctionGraph g = build_junction_graph(sc.network, sc.demand, 1.0);
  const PartitionSummary metis = summarize_partition(
      sc.network, sc.demand, partition_junctions(g, 4, PartitionMethod::Metis, 1), 4, 1.0);
  const PartitionSummary random = summarize_partition(
      sc.network, sc.demand, partition_junctions(g, 4, PartitionMethod::Random, 1), 4, 1.0);
  EXPECT_LT(metis.imbalance, 1.15);
  EXPECT_LT(metis.cut_roads, random.cut_roads);
  EXPECT_LT(metis.migrations, random.migrations);
  // Every lane of the network is in exactly one part.
  uint32_t lanes = 0;
  for (const auto& p : metis.parts) lanes += p.lanes;
  EXPECT_EQ(lanes, sc.network.num_lanes());
}

// Ghosts: the lanes of other parts just past each of a part's lanes are among its ghosts, its own never are,
// and more look-ahead never sees fewer.
TEST(PartitionTest, LayoutOwnsEveryLaneOnceAndSeesAcrossTheCuts) {
  const Scenario& sc = grid();
  const Network& net = sc.network;
  const std::vector<int32_t> lane_part = metis_lane_parts(3, 2);
  const std::vector<PartLayout> near = partition_layout(net, lane_part, 3, 1.0, 0.0);
  const std::vector<PartLayout> far = partition_layout(net, lane_part, 3, 400.0, 7.5);
  std::vector<int> owners(net.num_lanes(), 0);
  for (int32_t p = 0; p < 3; ++p) {
    const std::set<uint32_t> ghosts(near[static_cast<size_t>(p)].ghosts.begin(),
                                    near[static_cast<size_t>(p)].ghosts.end());
    const std::set<uint32_t> more(far[static_cast<size_t>(p)].ghosts.begin(),
                                  far[static_cast<size_t>(p)].ghosts.end());
    EXPECT_TRUE(std::includes(more.begin(), more.end(), ghosts.begin(), ghosts.end()));
    EXPECT_GT(more.size(), ghosts.size());
    for (uint32_t l : near[static_cast<size_t>(p)].owned) {
      ++owners[l];
      EXPECT_EQ(lane_part[l], p);
      EXPECT_FALSE(more.count(l));
      for (uint32_t c = net.lane_conn_begin[l]; c < net.lane_conn_begin[l + 1]; ++c) {
        const uint32_t next =
            net.conn_via_lane[c] >= 0 ? static_cast<uint32_t>(net.conn_via_lane[c]) : net.conn_to_lane[c];
        if (lane_part[next] == p) continue;
        EXPECT_TRUE(ghosts.count(next)) << net.lane_id[next] << " after " << net.lane_id[l];
      }
    }
  }
  for (int n : owners) EXPECT_EQ(n, 1);
  // A ghost edge comes whole.
  for (const PartLayout& part : far)
    for (uint32_t l : part.ghosts) {
      const uint32_t e = net.lane_edge[l];
      for (uint32_t m = net.edge_first_lane[e]; m < net.edge_first_lane[e] + net.edge_num_lanes[e]; ++m)
        EXPECT_TRUE(std::binary_search(part.ghosts.begin(), part.ghosts.end(), m)) << net.lane_id[m];
    }
}

// Each part's map holds its owned lanes' cells, then its ghosts', each lane's cells together and no two
// lanes' overlapping; the owned cells of all parts are the whole network's.
TEST(PartitionTest, PartCellsHoldOwnedLanesFirstThenGhosts) {
  const Scenario& sc = grid();
  const Network& net = sc.network;
  const std::vector<int32_t> lane_part = metis_lane_parts(3, 2);
  const std::vector<PartLayout> layout = partition_layout(net, lane_part, 3, 300.0, 7.5);
  uint64_t owned_total = 0;
  for (const PartLayout& part : layout) {
    const PartCells cells = part_cells(net, part);
    EXPECT_EQ(cells.owned_cells, part.owned_cells);
    EXPECT_EQ(cells.cells, part.owned_cells + part.ghost_cells);
    owned_total += cells.owned_cells;
    std::vector<uint8_t> used(cells.cells, 0);
    auto check = [&](uint32_t l, uint64_t from, uint64_t to) {
      ASSERT_NE(cells.cell_begin[l], kNoCells) << net.lane_id[l];
      EXPECT_GE(cells.cell_begin[l], from) << net.lane_id[l];
      const uint64_t n = net.lane_cell_begin[l + 1] - net.lane_cell_begin[l];
      EXPECT_LE(cells.cell_begin[l] + n, to) << net.lane_id[l];
      for (uint64_t i = 0; i < n; ++i) EXPECT_EQ(used[cells.cell_begin[l] + i]++, 0) << net.lane_id[l];
    };
    for (uint32_t l : part.owned) check(l, 0, cells.owned_cells);
    for (uint32_t l : part.ghosts) check(l, cells.owned_cells, cells.cells);
    EXPECT_EQ(std::count(used.begin(), used.end(), 1), static_cast<int64_t>(cells.cells));
    uint32_t held = 0;
    for (uint32_t l = 0; l < net.num_lanes(); ++l) held += cells.cell_begin[l] != kNoCells ? 1u : 0u;
    EXPECT_EQ(held, part.owned.size() + part.ghosts.size());
  }
  EXPECT_EQ(owned_total, net.num_cells());
}

// One rank's plan (part_plan: what an MPI rank works out for itself) is that part's of all the plans, and
// every lane a part holds lists it among the lane's holders.
TEST(PartitionTest, OneRanksPlanIsItsPartOfEveryPlan) {
  const Scenario& sc = grid();
  const Network& net = sc.network;
  const std::vector<int32_t> edge_part = edge_parts_from_junctions(
      net, partition_junctions(build_junction_graph(net, sc.demand, 1.0), 3, PartitionMethod::Metis, 2));
  const std::vector<PartPlan> all = part_plans(net, edge_part, 3, 7.5);
  ASSERT_EQ(all.size(), 3u);
  for (int32_t p = 0; p < 3; ++p) {
    const PartPlan one = part_plan(net, edge_part, 3, 7.5, p);
    const PartPlan& of_all = all[static_cast<size_t>(p)];
    EXPECT_EQ(one.part, p);
    EXPECT_EQ(one.parts, 3);
    EXPECT_EQ(one.lane_owner, of_all.lane_owner);
    EXPECT_EQ(one.edge_owner, of_all.edge_owner);
    EXPECT_EQ(one.held, of_all.held);
    EXPECT_EQ(one.cells.cell_begin, of_all.cells.cell_begin);
    EXPECT_EQ(one.cells.owned_cells, of_all.cells.owned_cells);
    EXPECT_EQ(one.holder_begin, of_all.holder_begin);
    EXPECT_EQ(one.holders, of_all.holders);
    EXPECT_EQ(one.shared_lanes, of_all.shared_lanes);
    EXPECT_EQ(one.signal_owner, of_all.signal_owner);
    EXPECT_FALSE(one.shared_lanes.empty());
    for (uint32_t l = 0; l < net.num_lanes(); ++l) {
      const auto* b = one.holders.data() + one.holder_begin[l];
      const auto* e = one.holders.data() + one.holder_begin[l + 1];
      EXPECT_EQ(std::find(b, e, p) != e, one.held[l] != 0) << net.lane_id[l];
    }
  }
}

TEST(PartitionTest, KmeansGivesEveryClusterAPoint) {
  const std::vector<double> x{0, 0, 0, 0, 10, 10, 50}, y{0, 1, 0, 1, 0, 0, 50};
  const std::vector<int32_t> c = kmeans(x, y, 3, 5);
  EXPECT_EQ(c, kmeans(x, y, 3, 5));
  EXPECT_EQ(std::set<int32_t>(c.begin(), c.end()).size(), 3u);
  EXPECT_EQ(c[0], c[1]);
  EXPECT_NE(c[0], c[6]);
}

class PartitionFileTest : public ::testing::Test {
 protected:
  TempDir dir{"lpsim_partition_file"};
  // The METIS partition of the grid as a file, and its lines after the header.
  std::string written() {
    const Scenario& sc = grid();
    const JunctionGraph g = build_junction_graph(sc.network, sc.demand, 1.0);
    parts_ = partition_junctions(g, 3, PartitionMethod::Metis, 3);
    const std::vector<int32_t> edge_part = edge_parts_from_junctions(sc.network, parts_);
    std::vector<std::string> ids;
    std::vector<int32_t> part;
    for (uint32_t e = 0; e < sc.network.num_edges(); ++e)
      if (!sc.network.edge_is_internal[e]) ids.push_back(sc.network.edge_id[e]), part.push_back(edge_part[e]);
    const std::string path = (dir.path() / "p.txt").string();
    write_partition_file(path, {"a comment"}, 3, ids, part);
    return test::read_file(path);
  }
  std::string write(const std::string& text, const std::string& name = "q.txt") {
    const std::string path = (dir.path() / name).string();
    std::ofstream(path) << text;
    return path;
  }
  std::string error_of(const std::string& text, int32_t expected_parts = 0) {
    try {
      resolve_partition(read_partition_file(write(text)), grid().network, expected_parts);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  std::vector<int32_t> parts_;
};

TEST_F(PartitionFileTest, ReadsBackWhatWasWritten) {
  const std::string text = written();
  ASSERT_EQ(text.rfind("# a comment\nparts 3\n", 0), 0u) << text.substr(0, 80);
  const PartitionSpec spec = read_partition_file((dir.path() / "p.txt").string());
  EXPECT_EQ(spec.parts, 3);
  const std::vector<int32_t> junction_part = resolve_partition(spec, grid().network, 3);
  // Junctions with a road into them get their part back exactly.
  const Network& net = grid().network;
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    if (net.edge_is_internal[e] || net.edge_to_junction[e] < 0) continue;
    const uint32_t j = static_cast<uint32_t>(net.edge_to_junction[e]);
    EXPECT_EQ(junction_part[j], parts_[j]);
  }
}

TEST_F(PartitionFileTest, RefusesBadFilesWithFileAndLine) {
  const std::string good = written();
  const size_t first_edge = good.find("parts 3\n") + 8;
  const std::string head = good.substr(0, first_edge), body = good.substr(first_edge);
  const std::string first_line = body.substr(0, body.find('\n') + 1);
  const std::string first_id = first_line.substr(0, first_line.find(' '));
  // Line numbers: 1 comment, 2 parts, 3 the first edge.
  EXPECT_NE(error_of(head + "nosuchedge 0\n" + body).find("q.txt:3: edge 'nosuchedge' is not a normal edge"),
            std::string::npos)
      << error_of(head + "nosuchedge 0\n" + body);
  EXPECT_NE(error_of(head + body + first_line).find("listed twice (first at line 3)"), std::string::npos);
  EXPECT_NE(error_of(head + first_id + " 7\n" + body.substr(first_line.size())).find("q.txt:3: part 7"),
            std::string::npos);
  EXPECT_NE(
      error_of(head + body.substr(first_line.size())).find("have no part (the first: '" + first_id + "')"),
      std::string::npos);
  EXPECT_NE(error_of(good, 2).find("has 3 parts, the run asks for 2"), std::string::npos);
  EXPECT_NE(error_of("parts 2\nx y\n").find("q.txt:2: 'y' is not a whole number"), std::string::npos);
  EXPECT_NE(error_of("a 1\n").find("q.txt:1: the file must declare 'parts K'"), std::string::npos);
  EXPECT_NE(error_of("# nothing\n").find("no 'parts K' line"), std::string::npos);
  // Two roads into one junction in different parts: the second road into the first junction with two.
  const Network& net = grid().network;
  std::vector<int> into(net.num_junctions(), 0);
  for (uint32_t e = 0; e < net.num_edges(); ++e)
    if (!net.edge_is_internal[e] && net.edge_to_junction[e] >= 0)
      ++into[static_cast<size_t>(net.edge_to_junction[e])];
  const int32_t busy = static_cast<int32_t>(
      std::find_if(into.begin(), into.end(), [](int n) { return n >= 2; }) - into.begin());
  std::string split = head;
  bool moved = false;
  int seen = 0;
  for (uint32_t e = 0; e < net.num_edges(); ++e) {
    if (net.edge_is_internal[e]) continue;
    int32_t part = parts_[static_cast<uint32_t>(net.edge_to_junction[e])];
    if (net.edge_to_junction[e] == busy && seen++ == 1) {
      part = (part + 1) % 3;
      moved = true;
    }
    split += net.edge_id[e] + " " + std::to_string(part) + "\n";
  }
  ASSERT_TRUE(moved);
  EXPECT_NE(error_of(split).find("the roads into a junction must share its part"), std::string::npos);
}

TEST_F(PartitionFileTest, CliWritesFileAndMapAndRefusesABadFile) {
  const test::CliResult ok =
      test::run_lpsim(dir.path(), {"partition", "-c", kConfig, "--parts", "3", "--partition-method", "leiden",
                                   "-o", "p.txt", "--map", "p.png"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("| part | junctions |"), std::string::npos) << ok.out;
  EXPECT_EQ(test::read_file(dir.path() / "p.png").substr(1, 3), "PNG");
  const test::CliResult again =
      test::run_lpsim(dir.path(), {"partition", "-c", kConfig, "--partition-file", "p.txt", "--parts", "3"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  write("parts 3\nnosuchedge 0\n");
  const test::CliResult bad =
      test::run_lpsim(dir.path(), {"partition", "-c", kConfig, "--partition-file", "q.txt"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("q.txt:2: edge 'nosuchedge' is not a normal edge"), std::string::npos) << bad.err;
  const test::CliResult no_k = test::run_lpsim(dir.path(), {"partition", "-c", kConfig, "-o", "r.txt"});
  EXPECT_EQ(no_k.exit_code, 2);
  const test::CliResult bad_method = test::run_lpsim(
      dir.path(), {"partition", "-c", kConfig, "--parts", "2", "--partition-method", "kahip", "-o", "r.txt"});
  EXPECT_EQ(bad_method.exit_code, 2);
  EXPECT_NE(bad_method.err.find("expected metis, leiden or random"), std::string::npos) << bad_method.err;
}

// `lpsim run --partition-file`: a Leiden partition runs to the same trips as one part; a file of another part
// count than --parts, or naming an unknown edge, or missing one, is one error line and exit 2.
TEST_F(PartitionFileTest, RunTakesAPartitionFileAndRefusesABadOne) {
  const test::CliResult made = test::run_lpsim(dir.path(), {"partition", "-c", kConfig, "--parts", "3",
                                                            "--partition-method", "leiden", "-o", "p.txt"});
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const test::CliResult one =
      test::run_lpsim(dir.path(), {"run", "-c", kConfig, "--end", "600", "--tripinfo-output", "one.xml"});
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const test::CliResult three = test::run_lpsim(
      dir.path(),
      {"run", "-c", kConfig, "--end", "600", "--partition-file", "p.txt", "--tripinfo-output", "three.xml"});
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_NE(three.out.find("Partitions: 3 parts"), std::string::npos) << three.out;
  // Each vehicle update counted once, whichever part made it (a vehicle that drove into another part was
  // counted by both in that step).
  const std::regex updates("Vehicle updates: ([0-9]+) ");
  std::smatch u1, u3;
  ASSERT_TRUE(std::regex_search(one.out, u1, updates)) << one.out;
  ASSERT_TRUE(std::regex_search(three.out, u3, updates)) << three.out;
  EXPECT_EQ(u1[1].str(), u3[1].str());
  const std::string trips = test::read_file(dir.path() / "one.xml");
  EXPECT_GT(trips.size(), 10000u);
  EXPECT_TRUE(trips == test::read_file(dir.path() / "three.xml"));

  const test::CliResult other_count = test::run_lpsim(
      dir.path(), {"run", "-c", kConfig, "--end", "60", "--partition-file", "p.txt", "--parts", "2"});
  EXPECT_EQ(other_count.exit_code, 2);
  EXPECT_EQ(test::lines_of(other_count.err).size(), 1u) << other_count.err;
  EXPECT_NE(other_count.err.find("p.txt"), std::string::npos) << other_count.err;
  write("parts 3\nnosuchedge 0\n");
  const test::CliResult unknown =
      test::run_lpsim(dir.path(), {"run", "-c", kConfig, "--end", "60", "--partition-file", "q.txt"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("q.txt:2: edge 'nosuchedge' is not a normal edge"), std::string::npos)
      << unknown.err;
  const std::string all = written();
  write(all.substr(0, all.rfind('\n', all.size() - 2) + 1));  // the last edge left out
  const test::CliResult missing =
      test::run_lpsim(dir.path(), {"run", "-c", kConfig, "--end", "60", "--partition-file", "q.txt"});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("q.txt"), std::string::npos) << missing.err;
}

// Partition input that used to be taken silently or to grow without bound: a part count beyond the limit or
// beyond the network's real junctions (grid_tls: 25; SUMO's 120 internal ones own no road), a method without
// --parts or beside a partition file, a map that is not a PNG; a map that cannot be written leaves no
// partition file behind. Each is one error line and exit 2.
TEST_F(PartitionFileTest, RefusesUnboundedOrMeaninglessPartitionInput) {
  auto refused = [&](const std::vector<std::string>& args, const std::string& says) {
    const test::CliResult r = test::run_lpsim(dir.path(), args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(test::lines_of(r.err).size(), 1u) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  };
  write("parts 1000000000\nA0B0 0\n");
  refused({"run", "-c", kConfig, "--partition-file", "q.txt"}, "q.txt:1: parts must lie in 1..1000000");
  write("parts 26\nA0B0 0\n");
  refused({"run", "-c", kConfig, "--partition-file", "q.txt"},
          "26 parts need at least as many junctions; the network has 25");
  refused({"partition", "-c", kConfig, "--parts", "26", "-o", "p.txt"}, "the network has 25");
  refused({"run", "-c", kConfig, "--partition-method", "leiden"}, "give --parts K as well");
  refused({"run", "-c", kConfig, "--partition.load-from", "e.xml"}, "give --parts K as well");
  write(
      "<meandata>\n  <interval begin=\"0\" end=\"60\">\n    <edge id=\"nosuchedge\" sampledSeconds=\"3\"/>\n"
      "  </interval>\n</meandata>\n",
      "other.xml");
  refused({"run", "-c", kConfig, "--parts", "2", "--partition.load-from", "other.xml"},
          "other.xml: edge 'nosuchedge' is not in the network");
  refused({"partition", "-c", kConfig, "--parts", "2", "-o", "p.txt", "--partition.load-from", "other.xml"},
          "other.xml: edge 'nosuchedge' is not in the network");
  write("parts 3\n");
  refused({"run", "-c", kConfig, "--partition-method", "leiden", "--partition-file", "q.txt"},
          "--partition-file gives the parts already");
  refused({"run", "-c", kConfig, "--partition.load-from", "other.xml", "--partition-file", "q.txt"},
          "--partition.load-from weighs what --parts splits the network; --partition-file gives the parts");
  refused({"partition", "-c", kConfig, "--parts", "2", "-o", "p.txt", "--map", "p.jpg"}, "ending in .png");
  refused({"partition", "-c", kConfig, "--parts", "2", "-o", "p.txt", "--map", "nodir/p.png"}, "p.png");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "p.txt"));
  const test::CliResult most =
      test::run_lpsim(dir.path(), {"partition", "-c", kConfig, "--parts", "25", "-o", "p.txt"});
  EXPECT_EQ(most.exit_code, 0) << most.err;
}

// The vehicles of a run that cross a cut, counted from its edgeData: on the grid every vehicle completes
// its route, so they are the routes' entries of cut roads (the expected migrations), and a partition without
// cuts has none.
TEST_F(PartitionFileTest, MigrationsMeasuredFromARunAreTheRoutesCrossings) {
  const test::CliResult run =
      test::run_lpsim(dir.path(), {"run", "-c", kConfig, "--edgedata-output", "e.xml"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const test::CliResult three = test::run_lpsim(
      dir.path(), {"partition", "-c", kConfig, "--parts", "3", "-o", "p3.txt", "--migrations-from", "e.xml"});
  ASSERT_EQ(three.exit_code, 0) << three.err;
  const size_t at = three.out.find("expected migrations ");
  ASSERT_NE(at, std::string::npos) << three.out;
  const std::string expected = three.out.substr(at + 20, three.out.find(',', at) - at - 20);
  EXPECT_GT(std::stoll(expected), 0);
  EXPECT_NE(three.out.find("measured migrations " + expected + " "), std::string::npos) << three.out;
  const test::CliResult one = test::run_lpsim(
      dir.path(), {"partition", "-c", kConfig, "--parts", "1", "-o", "p1.txt", "--migrations-from", "e.xml"});
  EXPECT_NE(one.out.find("measured migrations 0 "), std::string::npos) << one.out;
}

// A run split on another run's measured load: its vehicles per step come from that edgeData (the grid's
// hour: its vehicle-seconds over the 3,600 s the intervals cover), and its outputs are the run's in one part.
TEST_F(PartitionFileTest, ARunSplitOnAMeasuredLoadTakesItsVehiclesPerStepFromIt) {
  const test::CliResult measured = test::run_lpsim(
      dir.path(), {"run", "-c", kConfig, "--edgedata-output", "e.xml", "--tripinfo-output", "one.xml"});
  ASSERT_EQ(measured.exit_code, 0) << measured.err;
  double vehicle_seconds = 0;
  const std::string edges = test::read_file(dir.path() / "e.xml");
  static const std::regex sampled(" sampledSeconds=\"([0-9.]+)\"");
  for (auto it = std::sregex_iterator(edges.begin(), edges.end(), sampled); it != std::sregex_iterator();
       ++it)
    vehicle_seconds += std::stod((*it)[1].str());
  const test::CliResult split =
      test::run_lpsim(dir.path(), {"run", "-c", kConfig, "--parts", "2", "--parts.min-vehicles", "100000",
                                   "--partition.load-from", "e.xml", "--tripinfo-output", "two.xml"});
  ASSERT_EQ(split.exit_code, 0) << split.err;
  char says[96];
  std::snprintf(says, sizeof says, "about %.0f vehicles per step measured", vehicle_seconds / 3600);
  EXPECT_NE(split.err.find(says), std::string::npos) << split.err;
  const test::CliResult kept =
      test::run_lpsim(dir.path(), {"run", "-c", kConfig, "--parts", "3", "--parts.min-vehicles", "0",
                                   "--partition.load-from", "e.xml", "--tripinfo-output", "three.xml"});
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_NE(kept.out.find("Part 2: vehicle updates"), std::string::npos) << kept.out;
  EXPECT_TRUE(test::read_file(dir.path() / "three.xml") == test::read_file(dir.path() / "one.xml"));
}

}  // namespace
}  // namespace lpsim
