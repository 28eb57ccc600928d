"""The paper's figures, each written by `save_figure` as PNG, PDF or SVG.

trial_figures.py: the figures of one trial, as `tegrasp trial`/`demo` write them.
states.py: Fig. 9, SA and RA over the run with states, transitions and scores.
signals.py: Fig. 5a-b, raw and processed signals per finger.
contact_ra.py: the RA at first contact, zoomed.
avoid.py: Fig. 10, a hit on the held object and the Avoid reaction.
trial_annotations.py: what those figures draw over the signals (states, events, labels).
events.py: Fig. 5c, the memorized events.
table1.py: Table I against the paper, from a sweep.
sweep.py: per-position success maps of a sweep.
latency.py: detection latency distributions of a sweep.
ra_transients.py: the first-contact RA transient of the accelerometer chain and of the film.
figure_files.py: new_figure and save_figure."""
