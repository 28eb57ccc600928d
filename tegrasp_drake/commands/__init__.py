"""Sub-commands of the tegrasp command line (cli.py), one module each, with their helpers.

- demo.py, trial.py: one closed-loop trial (the demo: the default scenario, a figure).
- record_events.py: memorize the events of the ideal grasp.
- sweep.py, transfer.py, sensitivity.py: the grasping experiment; the transfer study; the
  guessed parameters over their ranges.
- emulate.py, hardware.py, replay.py: emulated devices; the run on them; its log replayed.
- plot.py: the paper's figures from a log or a results folder.
- command_line_parser.py: the parser of every command, which refuses a command line that
  does not parse in one line.
- scenario_args.py, viewer_args.py, verbosity.py, events_option.py: options shared by the
  commands.
- run_folder.py, progress.py: where a run's files go; the progress bar.
- output_streams.py: the command line's stdout and stderr when the system refuses them (a
  closed pipe, a full disk).
- process_environment.py: the process set up before a command runs (UTF-8 mode, matplotlib's
  folder).
- script_output.py: the reports the analysis scripts write, and their one-line error.
- error_boundary.py: the one line, and the traceback file, an unforeseen exception ends a
  program with (the command line and the analysis scripts)."""
