#!/usr/bin/python3
"""Runs SUMO (reference) and LPSim (candidate) on the same SUMO scenarios and compares trips, edge speeds,
counts and CPU time. Standard library only: run with /usr/bin/python3.

  tools/validate.py SCENARIO.sumocfg... [--lpsim build/lpsim] [--out DIR] [--end T] [--threads 2]
                    [--markdown FILE] [--seed S] [--model IDM|Krauss]
                    [--candidate sumo --candidate-model Krauss]

Each simulator runs in its own mirror of the cfg's folder (copies, never links, through which an output named
like a shipped file would overwrite it; cwd = the mirrored cfg folder), so outputs the cfg or its add-files
name relatively land under --out and the scenario folder stays untouched.
Prints a markdown table (one row per scenario) and writes DIR/results.json with all numbers. A candidate
that is missing or fails is reported in its row; the other scenarios still run.
"""
import argparse
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from validation import metrics, parsers, report, runner  # noqa: E402


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("configs", nargs="+", metavar="SCENARIO_CFG", help=".sumocfg files")
    parser.add_argument("--lpsim", default="build/lpsim", help="LPSim executable (default build/lpsim)")
    parser.add_argument("--sumo", default="sumo", help="SUMO executable (default sumo)")
    parser.add_argument("--sumo-home", default=None, help="SUMO_HOME (default $SUMO_HOME or /usr/share/sumo)")
    parser.add_argument("--out", default="build/validation", help="output folder (default build/validation)")
    parser.add_argument("--end", type=float, default=None, help="simulation end for all runs (default: the cfg's)")
    parser.add_argument("--step-length", type=float, default=None, help="step length (default: the cfg's, else 1)")
    parser.add_argument("--seed", type=int, default=23423, help="random seed for both (default 23423, SUMO's)")
    parser.add_argument("--threads", type=int, default=2, help="LPSim threads (default 2)")
    parser.add_argument("--model", default="IDM",
                        help="default car-following model of SUMO and LPSim (--default.carfollowmodel): IDM "
                             "(default) or Krauss")
    parser.add_argument("--markdown", default=None, help="also write the markdown table here")
    parser.add_argument("--timeout", type=float, default=3600, help="seconds per simulator run (default 3600)")
    parser.add_argument("--weighted-speed", action="store_true",
                        help="weight the edge-speed correlation by time sampled on each edge")
    parser.add_argument("--candidate", choices=("lpsim", "sumo"), default="lpsim",
                        help="what to compare against SUMO; 'sumo' checks the metrics with a second SUMO run")
    parser.add_argument("--candidate-model", default=None, help="with --candidate sumo: its car-following model")
    parser.add_argument("--candidate-seed", type=int, default=None, help="with --candidate sumo: its seed")
    return parser.parse_args(argv)


def resolve_executable(path):
    """Absolute path for a path with a folder part (runs use other working folders); PATH lookup otherwise."""
    if os.sep in path:
        return os.path.abspath(path)
    return shutil.which(path) or path


def scenario_names(configs):
    """Scenario name = the cfg's folder name; cfgs sharing a folder name get their file stem appended."""
    folders = [os.path.basename(os.path.dirname(os.path.abspath(c))) for c in configs]
    names = []
    for cfg, folder in zip(configs, folders):
        stem = os.path.basename(cfg).rsplit(".sumocfg", 1)[0]
        names.append(folder if folders.count(folder) == 1 else "%s-%s" % (folder, stem))
    return names


def _summary_of(outputs):
    """The per-run figures reported even without a comparison."""
    trips = outputs["trips"]
    return {
        "loaded": outputs["stats"].get("loaded"),
        "inserted": outputs["stats"].get("inserted"),
        "arrived": trips.arrived,
        "teleports": outputs["stats"].get("teleports"),
        "duration": metrics.duration_summary(trips.durations),
        "mean_route_length": metrics.mean(trips.route_lengths),
        "mean_time_loss": metrics.mean(trips.time_losses),
        "edges_in_edgedata": len(outputs["edges"]),
    }


def _prepare(scenario_dir, role, cfg):
    """Run folder for one simulator and the path of the cfg inside its mirror of the scenario folder."""
    run_dir = os.path.join(scenario_dir, role)
    work_dir = os.path.join(run_dir, "work")
    os.makedirs(run_dir, exist_ok=True)
    runner.mirror_folder(os.path.dirname(os.path.abspath(cfg)), work_dir)
    return run_dir, work_dir, os.path.join(work_dir, os.path.basename(cfg))


def _execute(name, role, command_for, cfg, scenario_dir, env, timeout, is_sumo):
    run_dir, work_dir, mirrored_cfg = _prepare(scenario_dir, role, cfg)
    files = runner.output_files(run_dir, with_statistics=is_sumo)
    for path in files.values():  # stale outputs of an earlier run must not pass for this one's
        if os.path.lexists(path):
            os.remove(path)
    result = runner.RunResult(role, command_for(mirrored_cfg, files), work_dir, files)
    print("[%s] %s: %s" % (name, role, runner.describe(result.command)), file=sys.stderr, flush=True)
    runner.run_timed(result, env=env, timeout=timeout)
    timing = "" if result.cpu_s is None else ", %.1f CPU s, %.1f wall s" % (result.cpu_s, result.wall_s)
    print("[%s] %s: %s%s" % (name, role, result.error or "ok", timing), file=sys.stderr, flush=True)
    outputs, error = None, result.error
    if error is None:
        try:
            outputs = runner.load_outputs(result, is_sumo)
        except ValueError as bad:
            error = str(bad)
    entry = {"run": result.to_json()}
    if outputs is not None:
        entry["summary"] = _summary_of(outputs)
    return entry, outputs, error


def run_scenario(cfg, name, args, env):
    config = parsers.read_sumocfg(cfg)
    end = args.end if args.end is not None else config["end"]
    step_length = args.step_length or config["step_length"] or 1.0
    scenario_dir = os.path.join(os.path.abspath(args.out), name)
    sumo = resolve_executable(args.sumo)

    def sumo_with(model, seed):
        def command(mirrored_cfg, files):
            runner.write_edgedata_additional(files["edgedata_add"], files["edgedata"])
            return runner.sumo_command(sumo, mirrored_cfg, files, model, end, step_length, seed,
                                       runner.cfg_additional_files(config, mirrored_cfg))
        return command

    if args.candidate == "sumo":
        candidate_label = "sumo-candidate"
        candidate_command = sumo_with(args.candidate_model or args.model,
                                      args.seed if args.candidate_seed is None else args.candidate_seed)
    else:
        candidate_label = "lpsim"
        lpsim = resolve_executable(args.lpsim)
        candidate_command = (lambda mirrored_cfg, files: runner.lpsim_command(
            lpsim, mirrored_cfg, files, end, step_length, args.seed, args.threads, args.model))

    entry = {"scenario": name, "cfg": os.path.abspath(cfg), "end": end, "cfg_end": config["end"],
             "step_length": step_length, "seed": args.seed, "cfg_outputs": config["outputs"]}
    reference, ref_outputs, ref_error = _execute(name, "sumo", sumo_with(args.model, args.seed), cfg,
                                                 scenario_dir, env, args.timeout, True)
    candidate, cand_outputs, cand_error = _execute(name, candidate_label, candidate_command, cfg, scenario_dir,
                                                   env, args.timeout, args.candidate == "sumo")
    entry["reference"], entry["candidate"] = reference, candidate
    entry["reference_error"] = "SUMO: %s" % ref_error if ref_error else None
    entry["candidate_error"] = "%s: %s" % (candidate_label, cand_error) if cand_error else None
    entry["comparison"] = None
    if ref_outputs is not None and cand_outputs is not None:
        entry["comparison"] = metrics.compare_runs(ref_outputs, cand_outputs, args.weighted_speed)
    return entry


def main(argv=None):
    args = parse_args(sys.argv[1:] if argv is None else argv)
    for cfg in args.configs:
        if not os.path.isfile(cfg):
            print("validate: no such scenario config: %s" % cfg, file=sys.stderr)
            return 2
    os.makedirs(args.out, exist_ok=True)
    env = runner.sumo_env(args.sumo_home)
    entries = []
    for cfg, name in zip(args.configs, scenario_names(args.configs)):
        try:
            entries.append(run_scenario(cfg, name, args, env))
        except Exception as failure:  # a broken cfg must not stop the other scenarios
            entries.append({"scenario": name, "cfg": os.path.abspath(cfg), "comparison": None,
                            "reference_error": "validate: %s: %s" % (type(failure).__name__, failure)})
    if args.candidate == "sumo":
        candidate_label = "SUMO %s seed %s" % (args.candidate_model or args.model,
                                               args.seed if args.candidate_seed is None else args.candidate_seed)
    else:
        candidate_label = "LPSim"
    table = report.markdown_table(entries, "SUMO %s seed %d" % (args.model, args.seed), candidate_label)
    sys.stdout.write(table)
    for path in filter(None, (args.markdown, os.path.join(args.out, "report.md"))):
        with open(path, "w") as handle:
            handle.write(table)
    report.write_json(os.path.join(args.out, "results.json"), {
        "targets": {"arrived_tolerance": metrics.ARRIVED_TOLERANCE,
                    "duration_tolerance": metrics.DURATION_TOLERANCE, "speed_r_min": metrics.SPEED_R_MIN},
        "reference": {"simulator": "sumo", "model": args.model, "seed": args.seed},
        "candidate": {"simulator": args.candidate, "label": candidate_label},
        "scenarios": entries,
    })
    return 0


if __name__ == "__main__":
    sys.exit(main())
