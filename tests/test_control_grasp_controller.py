"""AddGraspController's wiring: the memorized controller reads as the paper's Fig. 3."""

from tegrasp_drake.experiments.grasp_diagram import MakeGraspDiagram
from tegrasp_drake.experiments.scenario import LoadScenario


def connections(diagram) -> set[tuple[str, str, str, str]]:
    """(source system, output port, destination system, input port) of every connection."""
    return {(source.get_name(), source.get_output_port(output).get_name(),
             destination.get_name(), destination.get_input_port(input).get_name())
            for (destination, input), (source, output) in diagram.connection_map().items()}


def test_memorized_controller_scores_the_window_normalizer_windows():
    wiring = connections(MakeGraspDiagram(LoadScenario(name="box"), log=False).diagram)
    assert {("mechanoreceptor_channels", "channels", "window_normalizer", "channels"),
            ("window_normalizer", "sa_window_position", "event_scorer", "sa_window_position"),
            ("window_normalizer", "sa_window_buffer", "event_scorer", "sa_window_buffer"),
            ("window_normalizer", "ra_window_position", "event_scorer", "ra_window_position"),
            ("window_normalizer", "ra_window_buffer", "event_scorer", "ra_window_buffer"),
            ("mechanoreceptor_channels", "channels", "event_scorer", "channels"),
            ("grasp_state_machine", "expected_event", "event_scorer", "expected_event"),
            ("event_scorer", "match", "grasp_state_machine", "match"),
            ("event_scorer", "scores", "grasp_state_machine", "scores")} <= wiring


def test_heuristic_controller_reads_the_channels_directly():
    wiring = connections(MakeGraspDiagram(LoadScenario(name="box"), log=False,
                                             controller="heuristic").diagram)
    assert ("mechanoreceptor_channels", "channels", "heuristic_detector", "channels") in wiring
    assert ("heuristic_detector", "match", "grasp_state_machine", "match") in wiring
    assert not any("window_normalizer" in (c[0], c[2]) for c in wiring)
