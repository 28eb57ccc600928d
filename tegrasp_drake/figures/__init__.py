"""The paper's figures: one trial's (Fig. 5a-b, 9, 10, the RA at first contact), the
memorized events (Fig. 5c) and a sweep's (Table I against the paper, success maps,
detection latencies), each written by `save_figure` as PNG, PDF or SVG."""
