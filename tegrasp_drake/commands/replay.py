"""`tegrasp replay LOG`: what a hardware run's log holds, and the event matcher re-run on
its tactile data offline, two ways: expecting the event of the mode the logged
transitions show (run_log.replay_matcher), and expecting the memorized events one after
another, advanced by each match, as an EventSequencer does
(events/replay.replay_events_in_sequence). The matcher's thresholds are the run's own
(its scenario in TEGRASP_RUN_INFO), or the defaults."""

import json


def register(subparsers) -> None:
    parser = subparsers.add_parser(
        "replay", help="re-run the event matcher offline on the LCM log of `tegrasp hardware`")
    parser.add_argument("log", metavar="LOG")
    parser.add_argument("--events", default=None,
                        help="memorized events folder (default: the one the run used, "
                        "else the package's)")
    parser.add_argument("--object", default=None,
                        help="whose memorized events (default: the run's object)")
    parser.add_argument("--json", action="store_true")
    parser.set_defaults(func=run)


def _fmt(value):
    return "-" if value is None else f"{value:8.3f}"


def matcher_config_of(run_info, events):
    """The run's matcher thresholds (from its scenario), at the events' rates."""
    from tegrasp_drake.events.event_matcher import EventMatcherConfig
    from tegrasp_drake.events.replay import live_matcher_config
    config = EventMatcherConfig()
    if run_info is not None and run_info.scenario_yaml:
        from pydrake.common.yaml import yaml_load_typed

        from tegrasp_drake.experiments.scenario import Scenario
        scenario = yaml_load_typed(schema=Scenario, data=run_info.scenario_yaml,
                                   defaults=Scenario())
        config.sa_threshold = scenario.controller.sa_threshold
        config.ra_threshold = scenario.controller.ra_threshold
    return live_matcher_config(events, config)


def run(args) -> int:
    import pathlib

    from tegrasp_drake.rig import paths
    from tegrasp_drake.events import MemorizedEventError, load_memorized_events
    from tegrasp_drake.events.replay import replay_events_in_sequence
    from tegrasp_drake.experiments.run_log import RunLogError, read_run_log, replay_matcher
    try:
        log = read_run_log(args.log)
        info = log.run_info
        object_name = args.object or (info.object_name if info else None)
        if not object_name:
            raise RunLogError(f"run log '{args.log}' has no TEGRASP_RUN_INFO: give --object")
        events_dir = args.events or (info.events_dir if info and info.events_dir and
                                     pathlib.Path(info.events_dir).is_dir()
                                     else str(paths.events_dir()))
        events = load_memorized_events(events_dir, object_name)
        config = matcher_config_of(info, events)
        trial = log.tactile_trial()
        results = replay_matcher(trial, log.transitions, events, config=config)
        in_sequence = replay_events_in_sequence(trial, events, config=config)
    except (RunLogError, MemorizedEventError, ValueError) as e:
        raise SystemExit(f"tegrasp: error: {e}") from None
    summary = {
        "log": str(log.path), "controller": info.controller if info else None,
        "object": object_name, "events": events_dir, "messages": log.message_counts,
        "tactile_s": float(log.tactile["t"][-1] - log.tactile["t"][0])
        if len(log.tactile["t"]) else 0.0,
        "stale_ticks": int(log.tactile["stale"].sum()),
        "transitions": log.transitions,
        "faults": [{"t": f.utime * 1e-6, "device": f.device, "kind": f.kind, "code": f.code,
                    "description": f.description, "since": f.since_utime * 1e-6}
                   for f in log.faults],
        "replay": [{"transition": r.transition, "mode_entered": r.mode_entered,
                    "logged_time": r.logged_time, "match_time": r.match_time,
                    "scores": r.best_scores} for r in results],
        "sequence_fire_times": in_sequence.fire_times}
    if args.json:
        print(json.dumps(summary, sort_keys=True))
        return 0
    print(f"{summary['log']}: controller {summary['controller']}, object {object_name}, "
          f"{summary['tactile_s']:.2f} s of tactile data ({summary['stale_ticks']} stale ticks)")
    print("messages: " + ", ".join(f"{c} {n}" for c, n in sorted(log.message_counts.items())))
    for t in log.transitions:
        print(f"  [{t['t']:8.3f} s] {t['from']} -> {t['to']}  ({t['trigger']})")
    for f in summary["faults"]:
        print(f"  [{f['t']:8.3f} s] FAULT {f['device']}: {f['kind']}: {f['description']} "
              f"(since {f['since']:.3f} s)")
    print("offline matcher (expected event from the logged transitions):")
    print("  transition      expected from  transition   match    scores at match (or max)")
    for r in results:
        print(f"  {r.transition:14s}  {_fmt(r.mode_entered)}  {_fmt(r.logged_time)}  "
              f"{_fmt(r.match_time)}  " + " ".join(f"{s:5.2f}" for s in r.best_scores))
    print("offline matcher with an EventSequencer (events expected in grasp order):")
    for transition, fired in in_sequence.fire_times.items():
        print(f"  {transition:14s}  fired at {_fmt(fired)}")
    return 0
