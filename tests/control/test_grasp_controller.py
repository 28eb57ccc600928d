"""AddGraspController's wiring: the memorized controller reads as the paper's Fig. 3."""

from tegrasp_drake.scenario.grasp_diagram import MakeGraspDiagram
from tegrasp_drake.scenario.scenario import LoadScenario
from tegrasp_drake.tactile.window_normalizer import WindowNormalizer


def connections(diagram) -> set[tuple[str, str, str, str]]:
    """(source system, output port, destination system, input port) of every connection."""
    return {(source.get_name(), source.get_output_port(output).get_name(),
             destination.get_name(), destination.get_input_port(input).get_name())
            for (destination, input), (source, output) in diagram.connection_map().items()}


def test_memorized_controller_scores_the_window_normalizer_windows():
    diagram = MakeGraspDiagram(LoadScenario(name="box"), log=False).diagram
    assert isinstance(diagram.GetSubsystemByName("event_matcher"), WindowNormalizer)
    wiring = connections(diagram)
    assert {("mechanoreceptor_channels", "channels", "event_matcher", "channels"),
            ("grasp_state_machine", "expected_event", "event_matcher", "expected_event"),
            ("event_matcher", "match", "grasp_state_machine", "match"),
            ("event_matcher", "scores", "grasp_state_machine", "scores")} <= wiring


def test_heuristic_controller_reads_the_channels_directly():
    wiring = connections(MakeGraspDiagram(LoadScenario(name="box", controller="heuristic"),
                                          log=False).diagram)
    assert ("mechanoreceptor_channels", "channels", "heuristic_detector", "channels") in wiring
    assert ("heuristic_detector", "match", "grasp_state_machine", "match") in wiring
    assert not any("event_matcher" in (c[0], c[2]) for c in wiring)
