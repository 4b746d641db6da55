"""Tests of the validation tool: metrics, parsers, runner plumbing, and an end-to-end run with stand-in
simulators (plus one with real SUMO when it is installed). Run: /usr/bin/python3 -m unittest
tools/validation/test_metrics.py (from the repository root) or run this file directly."""
import json
import os
import shutil
import stat
import subprocess
import sys
import tempfile
import textwrap
import unittest

TOOLS_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
if TOOLS_DIR not in sys.path:
    sys.path.insert(0, TOOLS_DIR)

from validation import cache, metrics, parsers, report, runner, scenarios  # noqa: E402
import validate  # noqa: E402


def sample(speed, entered, seconds):
    edge = parsers.EdgeSample()
    edge.sampled_seconds = seconds
    edge.speed_time = (speed or 0.0) * seconds
    edge.entered = entered
    return edge


def trips_with(durations, ids=None):
    trips = parsers.TripInfo()
    trips.durations = list(durations)
    trips.ids = set(ids if ids is not None else ("v%d" % i for i in range(len(durations))))
    return trips


class TempDirTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="validate_test_")

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def write(self, name, text):
        path = os.path.join(self.tmp, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as handle:
            handle.write(textwrap.dedent(text).lstrip())
        return path


class StatisticsTest(unittest.TestCase):
    def test_percentiles_interpolate_between_ranks(self):
        values = [float(v) for v in range(10, 0, -1)]  # unsorted on purpose
        self.assertAlmostEqual(metrics.percentile(values, 0.1), 1.9)
        self.assertAlmostEqual(metrics.percentile(values, 0.5), 5.5)
        self.assertAlmostEqual(metrics.percentile(values, 0.9), 9.1)
        self.assertEqual(metrics.percentile([7.0], 0.9), 7.0)
        self.assertIsNone(metrics.percentile([], 0.5))

    def test_duration_summary(self):
        summary = metrics.duration_summary([10.0, 20.0, 30.0, 100.0])
        self.assertEqual(summary["count"], 4)
        self.assertAlmostEqual(summary["mean"], 40.0)
        self.assertAlmostEqual(summary["median"], 25.0)
        self.assertAlmostEqual(summary["p10"], 13.0)
        self.assertAlmostEqual(summary["p90"], 79.0)
        self.assertIsNone(metrics.duration_summary([])["mean"])

    def test_relative_difference(self):
        self.assertAlmostEqual(metrics.relative_difference(110, 100), 0.10)
        self.assertAlmostEqual(metrics.relative_difference(85.0, 100.0), -0.15)
        self.assertIsNone(metrics.relative_difference(5, 0))
        self.assertIsNone(metrics.relative_difference(None, 3))

    def test_pearson_known_values(self):
        self.assertAlmostEqual(metrics.pearson([1, 2, 3, 4], [2, 4, 6, 8]), 1.0)
        self.assertAlmostEqual(metrics.pearson([1, 2, 3, 4], [8, 6, 4, 2]), -1.0)
        # Hand-computed: x mean 2, y mean 3; sxy = 2, sxx = 2, syy = 8 -> 2 / 4
        self.assertAlmostEqual(metrics.pearson([1, 2, 3], [1, 5, 3]), 0.5)

    def test_pearson_undefined_cases(self):
        self.assertIsNone(metrics.pearson([1.0], [2.0]))
        self.assertIsNone(metrics.pearson([1, 2, 3], [5, 5, 5]))
        with self.assertRaises(ValueError):
            metrics.pearson([1, 2], [1, 2, 3])

    def test_weighted_pearson_ignores_zero_weight_outlier(self):
        xs, ys = [1, 2, 3, 4], [1, 2, 3, -50]
        self.assertLess(metrics.pearson(xs, ys), 0)
        self.assertAlmostEqual(metrics.pearson(xs, ys, [1, 1, 1, 0]), 1.0)


class EdgeCorrelationTest(unittest.TestCase):
    def test_speed_r_uses_only_edges_both_sampled(self):
        reference = {"a": sample(10, 5, 100), "b": sample(5, 5, 100), "c": sample(1, 5, 100),
                     "only_ref": sample(30, 1, 10), "unused": sample(None, 0, 0)}
        candidate = {"a": sample(11, 5, 50), "b": sample(6, 4, 50), "c": sample(2, 6, 50),
                     "unused": sample(7, 1, 5)}
        result = metrics.edge_speed_correlation(reference, candidate)
        self.assertEqual(result["edges"], 3)
        self.assertAlmostEqual(result["r"], 1.0)  # candidate = reference + 1 on the common edges
        self.assertFalse(result["weighted"])

    def test_weighted_speed_r_follows_busy_edges(self):
        reference = {"a": sample(10, 1, 1000), "b": sample(5, 1, 1000), "c": sample(1, 1, 1000),
                     "d": sample(20, 1, 0.001)}
        candidate = {"a": sample(10, 1, 1000), "b": sample(5, 1, 1000), "c": sample(1, 1, 1000),
                     "d": sample(0.5, 1, 0.001)}
        unweighted = metrics.edge_speed_correlation(reference, candidate)["r"]
        weighted = metrics.edge_speed_correlation(reference, candidate, weighted=True)["r"]
        self.assertLess(unweighted, 0.5)
        self.assertGreater(weighted, 0.999)

    def test_entered_r_counts_missing_edges_as_zero(self):
        reference = {"a": sample(1, 10, 1), "b": sample(1, 20, 1), "c": sample(1, 30, 1)}
        candidate = {"a": sample(1, 10, 1), "b": sample(1, 20, 1), "d": sample(1, 30, 1)}
        result = metrics.edge_entered_correlation(reference, candidate)
        self.assertEqual(result["edges"], 4)
        # x = [10, 20, 30, 0], y = [10, 20, 0, 30]: mean 15 each; sxy = 25+25-225-225, sxx = syy = 500
        self.assertAlmostEqual(result["r"], -0.8)


class CompareRunsTest(unittest.TestCase):
    def run_pair(self, ref_arrived, cand_arrived, ref_duration, cand_duration, cand_speed_noise,
                 ref_stats=None, cand_stats=None):
        edges_ref = {"e%d" % i: sample(2.0 + i, 10 + i, 50) for i in range(5)}
        edges_cand = {"e%d" % i: sample(2.0 + i + cand_speed_noise[i], 10 + i, 50) for i in range(5)}
        reference = {"trips": trips_with([ref_duration] * ref_arrived), "edges": edges_ref,
                     "stats": ref_stats or {"loaded": 120, "inserted": ref_arrived + 3, "teleports": 2}, "cpu_s": 4.0}
        candidate = {"trips": trips_with([cand_duration] * cand_arrived), "edges": edges_cand,
                     "stats": cand_stats or {"loaded": 121, "inserted": cand_arrived + 1, "teleports": 5},
                     "cpu_s": 1.0}
        return metrics.compare_runs(reference, candidate)

    def test_all_targets_pass_at_their_limits(self):
        result = self.run_pair(100, 103, 100.0, 110.0, [0, 0, 0, 0, 0])
        self.assertEqual(result["targets"], dict.fromkeys(metrics.TARGETS, "PASS"))
        self.assertAlmostEqual(result["arrived"]["relative_difference"], 0.03)
        self.assertAlmostEqual(result["duration"]["relative_difference_of_mean"], 0.10)
        self.assertEqual(result["inserted"]["reference"], 103)
        self.assertEqual(result["inserted"]["candidate"], 104)
        self.assertAlmostEqual(result["inserted"]["relative_difference"], 1 / 103.0)
        self.assertEqual(result["loaded"], {"reference": 120, "candidate": 121})
        self.assertEqual(result["teleports"], {"reference": 2, "candidate": 5})
        self.assertAlmostEqual(result["cpu_s"]["ratio"], 0.25)
        self.assertEqual(result["arrived"]["arrived_by_both"], 100)

    def test_targets_miss_just_past_their_limits(self):
        # Speeds 2..6 against 2, 8, 4, 0, 6: deviations -2..2 against -2, 4, 0, -4, 2 cancel, r = 0.
        result = self.run_pair(100, 96, 100.0, 89.0, [0, 5, 0, -5, 0],
                               cand_stats={"inserted": 101, "teleports": 6})
        self.assertEqual(result["targets"], dict.fromkeys(metrics.TARGETS, "MISS"))
        self.assertAlmostEqual(result["arrived"]["relative_difference"], -0.04)
        self.assertAlmostEqual(result["edge_speed"]["r"], 0.0)

    def test_no_arrivals_leaves_the_duration_undecided(self):
        result = self.run_pair(0, 0, 1.0, 1.0, [0] * 5)
        self.assertEqual(result["targets"]["arrived"], "PASS")  # 0 against 0
        self.assertIsNone(result["targets"]["duration"])
        self.assertIsNone(result["arrived"]["relative_difference"])


class TargetTest(unittest.TestCase):
    def verdicts(self, inserted=(1000, 1000), arrived=(900, 900), duration=(300.0, 300.0), speed_r=0.9,
                 teleports=(0, 0)):
        return metrics.evaluate_targets(inserted, arrived, duration, speed_r, teleports)

    def test_each_target_at_and_past_its_limit(self):
        cases = [  # (target, keyword, value at the limit, value just past it)
            ("inserted", "inserted", (1000, 1010), (1000, 989)),
            ("arrived", "arrived", (900, 927), (900, 872)),
            ("duration", "duration", (300.0, 330.0), (300.0, 269.9)),
            ("speed_r", "speed_r", 0.85, 0.8499),
            ("teleports", "teleports", (3, 6), (3, 7)),
        ]
        for target, keyword, at_limit, past_limit in cases:
            self.assertEqual(self.verdicts(**{keyword: at_limit})[target], "PASS", target)
            missed = self.verdicts(**{keyword: past_limit})
            self.assertEqual(missed[target], "MISS", target)
            self.assertEqual([t for t in metrics.TARGETS if missed[t] != "PASS"], [target])

    def test_teleports_floor_of_five(self):
        self.assertEqual(self.verdicts(teleports=(0, 5))["teleports"], "PASS")
        self.assertEqual(self.verdicts(teleports=(0, 6))["teleports"], "MISS")
        self.assertEqual(self.verdicts(teleports=(10, 20))["teleports"], "PASS")
        self.assertEqual(self.verdicts(teleports=(10, 21))["teleports"], "MISS")

    def test_missing_figures_and_zero_references(self):
        verdicts = self.verdicts(inserted=(None, 5), duration=(None, None), speed_r=None, teleports=(2, None))
        self.assertEqual(verdicts, {"inserted": None, "arrived": "PASS", "duration": None, "speed_r": None,
                                    "teleports": None})
        self.assertTrue(metrics.within(0, 0, 0.01))
        self.assertFalse(metrics.within(1, 0, 0.01))
        self.assertIsNone(metrics.within(None, 3, 0.01))

    def test_tally_counts_pairs_meeting_all_and_misses_per_target(self):
        passing = dict.fromkeys(metrics.TARGETS, "PASS")
        slow = dict(passing, duration="MISS", speed_r="MISS")
        undecided = dict(passing, duration=None)
        totals = metrics.tally([passing, slow, undecided, None, passing])
        self.assertEqual(totals["pairs"], 5)
        self.assertEqual(totals["all_met"], 2)
        self.assertEqual(totals["missed"], {"inserted": 1, "arrived": 1, "duration": 3, "speed_r": 2,
                                            "teleports": 1})

    def test_summary_line_and_refused_row(self):
        passing = {"scenario": "a", "model": "IDM", "comparison": None}
        refused = {"scenario": "b", "model": "Krauss", "comparison": None, "refused": "lpsim: error: no lanes",
                   "candidate_error": "lpsim: exit status 2: lpsim: error: no lanes"}
        line = report.summary_line([passing, refused])
        self.assertIn("0 of 2 (scenario, model) pairs (0 %)", line)
        self.assertIn("inserted ±1% 2", line)
        self.assertIn("teleports ≤max(2×S,5) 2", line)
        row = report.scenario_row(refused)
        self.assertTrue(row.startswith("| b | Krauss | – / – |"), row)
        self.assertTrue(row.endswith("| refused: lpsim: error: no lanes |"), row)


class ParserTest(TempDirTest):
    def test_tripinfo_counts_arrivals_and_skips_unfinished_and_persons(self):
        path = self.write("trips.xml", """
            <?xml version="1.0" encoding="UTF-8"?>
            <!-- a comment -->
            <tripinfos xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance">
                <tripinfo id="a" depart="0.00" arrival="50.00" duration="50.00" routeLength="400.0" timeLoss="10.5"/>
                <tripinfo id="b" depart="5.00" arrival="95.00" duration="90.00" routeLength="800.0" timeLoss="20.5">
                    <emissions CO_abs="1"/>
                </tripinfo>
                <personinfo id="p" depart="0.00"><walk duration="70.00"/></personinfo>
                <tripinfo id="c" depart="9.00" arrival="-1" duration="-1" routeLength="0"/>
            </tripinfos>
            """)
        trips = parsers.parse_tripinfo(path)
        self.assertEqual(trips.arrived, 2)
        self.assertEqual(trips.durations, [50.0, 90.0])
        self.assertEqual(trips.route_lengths, [400.0, 800.0])
        self.assertEqual(trips.time_losses, [10.5, 20.5])
        self.assertEqual(trips.ids, {"a", "b"})
        self.assertEqual(trips.unfinished, 1)

    def test_tripinfo_without_duration_is_an_error(self):
        path = self.write("bad.xml", '<tripinfos><tripinfo id="x" arrival="3"/></tripinfos>')
        with self.assertRaisesRegex(ValueError, "'x' has no duration"):
            parsers.parse_tripinfo(path)

    def test_edgedata_sums_intervals_weighting_speed_by_time(self):
        path = self.write("edges.xml", """
            <meandata>
                <interval begin="0.00" end="100.00" id="d">
                    <edge id="e1" sampledSeconds="10.00" speed="10.00" entered="2" departed="1" left="3"/>
                    <edge id=":j_0" sampledSeconds="5.00" speed="3.00" entered="9"/>
                    <edge id="empty" sampledSeconds="0.00" entered="0" left="0"/>
                </interval>
                <interval begin="100.00" end="200.00" id="d">
                    <edge id="e1" sampledSeconds="30.00" speed="2.00" entered="4" arrived="2"/>
                </interval>
            </meandata>
            """)
        edges = parsers.parse_edgedata(path)
        self.assertEqual(sorted(edges), ["e1", "empty"])
        self.assertAlmostEqual(edges["e1"].speed, (10 * 10 + 2 * 30) / 40.0)
        self.assertEqual(edges["e1"].entered, 6)
        self.assertEqual(edges["e1"].sampled_seconds, 40)
        self.assertEqual(edges["e1"].arrived, 2)
        self.assertIsNone(edges["empty"].speed)

    def test_lanedata_is_summed_per_edge(self):
        path = self.write("lanes.xml", """
            <meandata><interval begin="0" end="10" id="l">
                <edge id="e"><lane id="e_0" sampledSeconds="4" speed="5" entered="1"/>
                             <lane id="e_1" sampledSeconds="12" speed="9" entered="3"/></edge>
            </interval></meandata>
            """)
        edges = parsers.parse_edgedata(path)
        self.assertAlmostEqual(edges["e"].speed, (4 * 5 + 12 * 9) / 16.0)
        self.assertEqual(edges["e"].entered, 4)

    def test_statistic_output(self):
        path = self.write("stats.xml", """
            <statistics>
                <vehicles loaded="2171" inserted="1910" running="78" waiting="261"/>
                <teleports total="3" jam="2" yield="1" wrongLane="0"/>
                <safety collisions="1" emergencyStops="3"/>
                <vehicleTripStatistics count="1832" routeLength="436.69" duration="250.38"/>
            </statistics>
            """)
        self.assertEqual(parsers.parse_statistic_output(path), {
            "loaded": 2171, "inserted": 1910, "running": 78, "waiting": 261, "teleports": 3, "collisions": 1,
            "mean_duration": 250.38})

    def test_statistics_text_with_and_without_loaded_and_teleports(self):
        text = ("Performance: \n Duration: 10.74s\nVehicles: \n Inserted: 1910 (Loaded: 2171)\n Running: 78\n"
                " Waiting: 261\nTeleports: 4 (Jam: 4)\nStatistics (avg of 1832):\n Duration: 250.38\n")
        self.assertEqual(parsers.parse_statistics_text(text), {
            "inserted": 1910, "loaded": 2171, "running": 78, "waiting": 261, "teleports": 4})
        plain = parsers.parse_statistics_text("Vehicles: \n Inserted: 15\n Running: 0\n Waiting: 0\n")
        self.assertEqual(plain["loaded"], 15)
        self.assertEqual(plain["teleports"], 0)
        self.assertEqual(parsers.parse_statistics_text("no statistics printed"), {})

    def test_summary_last_step_holds_the_totals(self):
        path = self.write("summary.xml", """
            <summary>
                <step time="0.00" loaded="5" inserted="1" running="1" waiting="4" arrived="0" teleports="0"/>
                <step time="1.00" loaded="9" inserted="7" running="2" waiting="2" arrived="5" teleports="1"/>
            </summary>
            """)
        self.assertEqual(parsers.parse_summary_last(path), {
            "loaded": 9, "inserted": 7, "running": 2, "waiting": 2, "arrived": 5, "teleports": 1})

    def test_trains_are_counted_apart(self):
        self.write("r.rou.xml", """
            <routes><vType id="train" vClass="rail"/><vType id="car"/><vType id="boat" vClass="ship"/></routes>
            """)
        cfg = self.write("t.sumocfg", """
            <configuration><input><route-files value="r.rou.xml, missing.rou.xml"/></input></configuration>
            """)
        off_road = parsers.off_road_vtypes(cfg, parsers.read_sumocfg(cfg))
        self.assertEqual(off_road, {"train", "boat"})
        path = self.write("ti.xml", """
            <tripinfos>
                <tripinfo id="t" depart="0" arrival="50" duration="50" routeLength="900" timeLoss="0" vType="train"/>
                <tripinfo id="c" depart="0" arrival="20" duration="20" routeLength="300" timeLoss="1" vType="car"/>
            </tripinfos>
            """)
        trips = parsers.parse_tripinfo(path, off_road)
        self.assertEqual((trips.arrived, trips.off_road, trips.durations), (1, 1, [20.0]))
        self.assertEqual(parsers.parse_tripinfo(path).arrived, 2)

    def test_read_sumocfg_times_and_outputs(self):
        path = self.write("a.sumocfg", """
            <configuration>
                <input><net-file value="n.net.xml"/><additional-files value="x.add.xml, sub/y.add.xml"/></input>
                <output><tripinfo-output value="trips.xml"/></output>
                <time><begin value="7:00:00"/><end value="-1"/><step-length value="0.5"/></time>
                <report><log value="log.txt"/><no-step-log value="true"/></report>
            </configuration>
            """)
        config = parsers.read_sumocfg(path)
        self.assertEqual(config["begin"], 25200.0)
        self.assertIsNone(config["end"])
        self.assertEqual(config["step_length"], 0.5)
        self.assertEqual(config["outputs"]["tripinfo-output"], "trips.xml")
        self.assertEqual(config["outputs"]["log"], "log.txt")
        self.assertEqual(runner.cfg_additional_files(config, "/m/a.sumocfg"), ["/m/x.add.xml", "/m/sub/y.add.xml"])
        self.assertEqual(parsers._sumo_time("1:02:00:30"), 93630.0)


class RunnerTest(TempDirTest):
    def test_mirror_copies_every_file_and_keeps_outputs_out_of_the_source(self):
        self.write("scenario/a.sumocfg", "<configuration/>")
        self.write("scenario/sub/b.xml", "<b/>")
        self.write("scenario/det.xml", "<shipped/>")
        mirror = runner.mirror_folder(os.path.join(self.tmp, "scenario"), os.path.join(self.tmp, "mirror"))
        self.assertFalse(os.path.islink(os.path.join(mirror, "a.sumocfg")))
        with open(os.path.join(mirror, "sub", "b.xml")) as handle:
            self.assertEqual(handle.read().strip(), "<b/>")
        with open(os.path.join(mirror, "out.xml"), "w") as handle:
            handle.write("x")
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "scenario", "out.xml")))
        # An output named like a file the scenario ships is written over the mirror's copy, not the original.
        with open(os.path.join(mirror, "det.xml"), "w") as handle:
            handle.write("<written/>")
        with open(os.path.join(self.tmp, "scenario", "det.xml")) as handle:
            self.assertEqual(handle.read(), "<shipped/>")
        os.remove(os.path.join(mirror, "a.sumocfg"))
        os.symlink(os.path.join(self.tmp, "scenario", "a.sumocfg"), os.path.join(mirror, "a.sumocfg"))
        runner.mirror_folder(os.path.join(self.tmp, "scenario"), mirror)  # again: an old link is replaced
        self.assertFalse(os.path.islink(os.path.join(mirror, "a.sumocfg")))

    def test_failed_and_missing_executables_are_reported(self):
        failing = self.write("fail.py", "import sys\nprint('Error: net file broken')\nsys.exit(3)\n")
        files = runner.output_files(self.tmp, with_statistics=False)
        result = runner.run_timed(runner.RunResult("x", [sys.executable, failing], self.tmp, files))
        self.assertEqual(result.returncode, 3)
        self.assertEqual(result.error, "exit status 3: Error: net file broken")
        self.assertGreaterEqual(result.cpu_s, 0.0)
        missing = runner.run_timed(runner.RunResult("y", [os.path.join(self.tmp, "nope")], self.tmp, files))
        self.assertTrue(missing.error.startswith("cannot start"))
        self.assertIsNone(missing.cpu_s)

    def test_commands_carry_step_length_seed_and_end(self):
        files = runner.output_files("/o", with_statistics=True)
        sumo = runner.sumo_command("sumo", "/m/c.sumocfg", files, "IDM", 3600.0, 0.5, 7, ["/m/a.add.xml"])
        self.assertIn("--additional-files", sumo)
        self.assertEqual(sumo[sumo.index("--additional-files") + 1], "/m/a.add.xml,/o/edgedata.add.xml")
        self.assertEqual(sumo[sumo.index("--step-length") + 1], "0.5")
        self.assertEqual(sumo[sumo.index("--end") + 1], "3600")
        self.assertEqual(sumo[sumo.index("--default.carfollowmodel") + 1], "IDM")
        lpsim = runner.lpsim_command("/b/lpsim", "/m/c.sumocfg", files, None, 1.0, 7, 2, "Krauss")
        self.assertEqual(lpsim[:4], ["/b/lpsim", "run", "-c", "/m/c.sumocfg"])
        self.assertEqual(lpsim[lpsim.index("--default.carfollowmodel") + 1], "Krauss")
        self.assertNotIn("--default.carfollowmodel", runner.lpsim_command("/b/lpsim", "/m/c.sumocfg", files,
                                                                          None, 1.0, 7, 2))
        self.assertNotIn("--end", lpsim)
        self.assertEqual(lpsim[lpsim.index("--threads") + 1], "2")
        self.assertEqual(lpsim[lpsim.index("--edgedata-output") + 1], "/o/edgedata.xml")


# A stand-in simulator: writes tripinfo/edgeData/statistics like SUMO would; run with the Krauss model its
# durations are multiplied and its speeds divided by FAKE_SCALE, so the comparison has something to measure.
# The edgeData file comes from --edgedata-output or, as the runner does for SUMO, from the edgeData element of
# the last additional file. It answers --version as SUMO does, appends a line per run to FAKE_LOG when set
# (to count runs) and, with FAKE_REFUSE, refuses the scenario as LPSim does (exit status 2).
FAKE_SIMULATOR = r"""
import os, re, sys
args = sys.argv[1:]
def opt(name):
    return args[args.index(name) + 1] if name in args else None
if args == ["--version"]:
    print("Fake SUMO Version 1.15.0\n Build features: none"); sys.exit(0)
if os.environ.get("FAKE_LOG"):
    with open(os.environ["FAKE_LOG"], "a") as log:
        log.write(os.path.basename(sys.argv[0]) + " " + str(opt("--default.carfollowmodel")) + "\n")
scale = float(os.environ.get("FAKE_SCALE", "1")) if "Krauss" in args else 1.0
if os.environ.get("FAKE_FAIL"):
    print("Error: cannot simulate"); sys.exit(1)
if os.environ.get("FAKE_REFUSE") and "run" in args:
    print("Loading ...")
    sys.stderr.write("warning: something\nlpsim: error: vClass 'ship' has no lane\n"); sys.exit(2)
edgedata = opt("--edgedata-output")
if edgedata is None:
    last_add = opt("--additional-files").split(",")[-1]
    edgedata = re.search(r'file="([^"]+)"', open(last_add).read()).group(1)
with open(opt("--tripinfo-output"), "w") as f:
    f.write("<tripinfos>\n")
    for i in range(10):
        f.write('<tripinfo id="v%d" arrival="1" duration="%.2f"/>\n' % (i, (60 + 10 * i) * scale))
    f.write("</tripinfos>\n")
with open(edgedata, "w") as f:
    f.write('<meandata><interval begin="0" end="100" id="x">\n')
    for i in range(4):
        f.write('<edge id="e%d" sampledSeconds="50" speed="%.2f" entered="%d"/>\n' % (i, (5 + i) / scale, 10 + i))
    f.write("</interval></meandata>\n")
if opt("--statistic-output"):
    with open(opt("--statistic-output"), "w") as f:
        f.write('<statistics><vehicles loaded="12" inserted="11" running="1" waiting="1"/>'
                '<teleports total="2"/></statistics>')
print("Vehicles:\n Inserted: 11 (Loaded: 12)\n Running: 1\n Waiting: 1")
"""


class EndToEndTest(TempDirTest):
    def make_simulator(self, name):
        path = self.write(name, "#!%s\n%s" % (sys.executable, FAKE_SIMULATOR))
        os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)
        return path

    def setUp(self):
        super().setUp()
        self.cfg = self.write("scn/run.sumocfg", """
            <configuration><input><net-file value="n.net.xml"/><additional-files value="own.add.xml"/></input>
            <time><begin value="0"/><end value="100"/></time></configuration>
            """)
        self.write("scn/own.add.xml", "<additional/>")
        self.log = os.path.join(self.tmp, "runs.log")

    def runs(self):
        """Simulator runs so far, as 'name model' lines."""
        if not os.path.exists(self.log):
            return []
        with open(self.log) as handle:
            return handle.read().split()[::2]

    def run_validate(self, extra_env, *options, configs=None):
        out = os.path.join(self.tmp, "out")
        saved = dict(os.environ)
        os.environ.update(dict(extra_env, FAKE_LOG=self.log))
        try:
            markdown = os.path.join(self.tmp, "table.md")
            with open(os.devnull, "w") as sink:
                stdout, stderr = sys.stdout, sys.stderr
                sys.stdout = sys.stderr = sink
                try:
                    code = validate.main((configs if configs is not None else [self.cfg])
                                         + ["--sumo", self.make_simulator("sumo"), "--out", out,
                                            "--markdown", markdown] + list(options))
                finally:
                    sys.stdout, sys.stderr = stdout, stderr
        finally:
            os.environ.clear()
            os.environ.update(saved)
        self.assertEqual(code, 0)
        with open(os.path.join(out, "results.json")) as handle:
            document = json.load(handle)
        with open(markdown) as handle:
            return document, handle.read()

    def test_identical_simulators_pass_every_target(self):
        document, table = self.run_validate({}, "--lpsim", self.make_simulator("lpsim"))
        entry = document["scenarios"][0]
        comparison = entry["comparison"]
        self.assertEqual((entry["scenario"], entry["model"]), ("scn", "IDM"))
        self.assertEqual(comparison["arrived"]["reference"], 10)
        self.assertEqual(comparison["inserted"]["reference"], 11)
        self.assertEqual(comparison["inserted"]["candidate"], 11)
        self.assertEqual(comparison["teleports"], {"reference": 2, "candidate": 0})
        self.assertAlmostEqual(comparison["edge_speed"]["r"], 1.0)
        self.assertEqual(comparison["targets"], dict.fromkeys(metrics.TARGETS, "PASS"))
        self.assertIn("| scn | IDM | 12 / 12 | 11 / 11 | 10 / 10 | 105.0 / 105.0 | +0.0 % | 1.000 (4) | 2 / 0 |",
                      table)
        self.assertIn("| PASS +0.0 % | PASS +0.0 % | PASS | PASS | PASS |", table)
        self.assertIn("All five targets met: 1 of 1 (scenario, model) pairs (100 %)", table)
        self.assertEqual(document["totals"]["all_met"], 1)
        command = entry["reference"]["run"]["command"]
        self.assertEqual(command[-2:], ["--end", "100"])
        self.assertIn(os.path.join(self.tmp, "out", "scn", "IDM", "sumo", "work", "own.add.xml"),
                      command[command.index("--additional-files") + 1])

    def test_slower_candidate_misses_duration_only(self):
        # The Krauss candidate: durations x 1.5, speeds / 1.5 (so speed r stays 1), same arrivals.
        document, table = self.run_validate({"FAKE_SCALE": "1.5"}, "--candidate", "sumo",
                                            "--candidate-model", "Krauss")
        comparison = document["scenarios"][0]["comparison"]
        self.assertAlmostEqual(comparison["duration"]["relative_difference_of_mean"], 0.5)
        self.assertAlmostEqual(comparison["duration"]["candidate"]["p90"], 1.5 * 141.0)
        self.assertEqual(comparison["targets"], dict(dict.fromkeys(metrics.TARGETS, "PASS"), duration="MISS"))
        self.assertIn("Krauss", document["scenarios"][0]["candidate"]["run"]["command"])
        self.assertIn("| +50.0 % |", table)

    def test_failing_candidate_is_reported_in_its_row(self):
        document, table = self.run_validate({}, "--lpsim", os.path.join(self.tmp, "missing-lpsim"))
        entry = document["scenarios"][0]
        self.assertIsNone(entry["comparison"])
        self.assertIn("cannot start", entry["candidate_error"])
        self.assertEqual(entry["reference"]["summary"]["arrived"], 10)
        self.assertIn("lpsim: cannot start", table)
        self.assertIn("| scn | IDM | 12 / – | 11 / – | 10 / – |", table)
        self.assertIsNone(entry["candidate"]["run"]["cpu_s"])
        self.assertIn("All five targets met: 0 of 1", table)

    def test_refused_scenario_is_a_row_of_its_own_and_a_miss(self):
        document, table = self.run_validate({"FAKE_REFUSE": "1"}, "--lpsim", self.make_simulator("lpsim"))
        self.assertEqual(document["scenarios"][0]["refused"], "lpsim: error: vClass 'ship' has no lane")
        self.assertIn("| refused: lpsim: error: vClass 'ship' has no lane |", table)
        self.assertEqual(document["totals"]["missed"], dict.fromkeys(metrics.TARGETS, 1))

    def test_both_models_and_the_sumo_cache(self):
        lpsim = self.make_simulator("lpsim")
        document, table = self.run_validate({"FAKE_SCALE": "1.5"}, "--lpsim", lpsim, "--model", "both")
        self.assertEqual([(e["scenario"], e["model"]) for e in document["scenarios"]],
                         [("scn", "Krauss"), ("scn", "IDM")])
        self.assertEqual(self.runs(), ["sumo", "lpsim", "sumo", "lpsim"])
        self.assertEqual(document["totals"]["all_met"], 2)  # both scale Krauss alike
        self.assertIn("cache: 0 of 2", table)
        # Again: SUMO's runs come from the cache, with the same figures.
        again, table = self.run_validate({"FAKE_SCALE": "1.5"}, "--lpsim", lpsim, "--model", "both")
        self.assertEqual(self.runs()[4:], ["lpsim", "lpsim"])
        self.assertIn("cache: 2 of 2", table)
        for before, after in zip(document["scenarios"], again["scenarios"]):
            self.assertEqual(before["comparison"]["arrived"], after["comparison"]["arrived"])
            self.assertEqual(before["reference"]["summary"], after["reference"]["summary"])
            self.assertTrue(after["reference"]["run"]["cached"].startswith(os.path.join(self.tmp, "out", "sumo_cache")))
        # A scenario file changed in place (same size) is a new key; --refresh-sumo reruns a matching one.
        self.write("scn/own.add.xml", "<additionaL/>")
        self.run_validate({}, "--lpsim", lpsim, "--model", "Krauss")
        self.assertEqual(self.runs()[6:], ["sumo", "lpsim"])
        self.run_validate({}, "--lpsim", lpsim, "--model", "Krauss")
        self.assertEqual(self.runs()[8:], ["lpsim"])
        self.run_validate({}, "--lpsim", lpsim, "--model", "Krauss", "--refresh-sumo")
        self.assertEqual(self.runs()[9:], ["sumo", "lpsim"])

    def test_all_and_extra_pick_the_run_cfgs(self):
        shared = os.path.join(self.tmp, "shared")
        self.write("shared/a/run.sumocfg", "<configuration/>")
        self.write("shared/a/present.sumocfg", "<configuration/>")
        self.write("shared/b/only.sumocfg", "<configuration/>")
        self.write("shared/c/readme.md", "no cfg")
        self.write("wiz/w1/osm.sumocfg", "<configuration/>")
        self.write("wiz/w1/other.sumocfg", "<configuration/>")
        args = validate.parse_args(["--all", "--shared", shared, "--extra", os.path.join(self.tmp, "wiz"),
                                    os.path.join(shared, "a", "run.sumocfg")])
        self.assertEqual([os.path.relpath(c, self.tmp) for c in validate.collect_configs(args)],
                         ["shared/a/run.sumocfg", "shared/b/only.sumocfg", "wiz/w1/osm.sumocfg"])
        self.assertEqual(scenarios.model_list("both"), ["Krauss", "IDM"])
        self.assertEqual(scenarios.model_list("Krauss"), ["Krauss"])


class CacheTest(TempDirTest):
    def test_folder_digest_follows_contents_not_sizes_or_times(self):
        path = self.write("scn/a.xml", "<a>1</a>")
        folder = os.path.dirname(path)
        first = cache.folder_digest(folder)
        stamp = os.stat(path)
        self.write("scn/a.xml", "<a>2</a>")
        os.utime(path, ns=(stamp.st_atime_ns, stamp.st_mtime_ns))
        self.assertNotEqual(cache.folder_digest(folder), first)
        self.write("scn/a.xml", "<a>1</a>")
        self.assertEqual(cache.folder_digest(folder), first)
        self.write("scn/.git/ignored", "x")  # hidden folders are not mirrored, so not hashed
        self.assertEqual(cache.folder_digest(folder), first)
        self.write("scn/sub/b.xml", "")
        self.assertNotEqual(cache.folder_digest(folder), first)

    def test_key_changes_with_every_field(self):
        fields = ["f" * 40, "run.sumocfg", "Krauss", 23423, 3600.0, 1.0, "Eclipse SUMO sumo Version 1.15.0"]
        key = cache.cache_key(*fields)
        self.assertEqual(key, cache.cache_key(*fields))
        self.assertEqual(key, cache.cache_key(*fields[:4] + [3600, 1] + fields[6:]))  # 3600 == 3600.0
        changed = ["e" * 40, "osm.sumocfg", "IDM", 1, None, 0.5, "Eclipse SUMO sumo Version 1.16.0"]
        for index, value in enumerate(changed):
            other = list(fields)
            other[index] = value
            self.assertNotEqual(cache.cache_key(*other), key, "field %d" % index)

    def test_store_and_load_round_trip(self):
        run_dir = os.path.join(self.tmp, "run")
        files = runner.output_files(run_dir, with_statistics=True)
        for role in ("tripinfo", "edgedata", "statistics", "stdout", "stderr", "log"):
            self.write(os.path.relpath(files[role], self.tmp), role)
        run = {"command": ["sumo"], "files": files, "cpu_s": 1.5, "wall_s": 2.0, "returncode": 0}
        store = os.path.join(self.tmp, "cache")
        self.assertIsNone(cache.load(store, "k"))
        cache.store(store, "k", run, {"scenario": "s"})
        record = cache.load(store, "k")
        self.assertEqual(record["cpu_s"], 1.5)
        self.assertEqual(record["about"], {"scenario": "s"})
        self.assertNotIn("summary", record["files"])
        with open(record["files"]["tripinfo"]) as handle:
            self.assertEqual(handle.read(), "tripinfo")
        os.remove(record["files"]["edgedata"])  # an entry missing a file is no entry
        self.assertIsNone(cache.load(store, "k"))


@unittest.skipUnless(shutil.which("sumo") and shutil.which("netgenerate"), "SUMO not installed")
class RealSumoTest(TempDirTest):
    def test_krauss_against_idm_on_a_small_grid_beginning_after_zero(self):
        folder = os.path.join(self.tmp, "grid")
        os.makedirs(folder)
        subprocess.run(["netgenerate", "--grid", "--grid.number", "3", "--grid.length", "200",
                        "--no-turnarounds", "-o", os.path.join(folder, "g.net.xml")],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        vehicles = "".join('<vehicle id="v%d" depart="%d" route="r%d"/>' % (i, 100 + 4 * i, i % 2)
                           for i in range(30))
        self.write("grid/g.rou.xml", '<routes><route id="r0" edges="A0A1 A1A2 A2B2"/>'
                   '<route id="r1" edges="C0B0 B0B1 B1C1"/>%s</routes>' % vehicles)
        cfg = self.write("grid/g.sumocfg", '<configuration><input><net-file value="g.net.xml"/>'
                         '<route-files value="g.rou.xml"/></input><time><begin value="100"/>'
                         '<end value="600"/></time></configuration>')
        out = os.path.join(self.tmp, "out")
        with open(os.devnull, "w") as sink:
            stdout, stderr = sys.stdout, sys.stderr
            sys.stdout = sys.stderr = sink
            try:
                validate.main([cfg, "--out", out, "--candidate", "sumo", "--candidate-model", "Krauss"])
            finally:
                sys.stdout, sys.stderr = stdout, stderr
        with open(os.path.join(out, "results.json")) as handle:
            entry = json.load(handle)["scenarios"][0]
        comparison = entry["comparison"]
        self.assertIsNotNone(comparison, entry.get("reference_error") or entry.get("candidate_error"))
        self.assertEqual(comparison["arrived"]["reference"], 30)
        self.assertEqual(comparison["inserted"]["reference"], 30)
        self.assertEqual(comparison["teleports"]["reference"], 0)
        self.assertEqual(comparison["edge_speed"]["edges"], 6)  # the six route edges, begin 100 notwithstanding
        self.assertGreater(comparison["edge_entered"]["r"], 0.99)
        self.assertGreater(comparison["cpu_s"]["reference"], 0.0)


if __name__ == "__main__":
    unittest.main()
