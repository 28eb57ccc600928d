"""What `tegrasp demo` writes for a grasp with a hit in Hold (the paper's Fig. 10 scenario):
the trial log, the figures (Fig. 5a-b, 9, 10) and the standalone HTML replay, opened in a
real headless Chromium (tests/headless_chromium.py) and checked from the page itself."""

import contextlib
import io
import json

import numpy as np
import pytest
from matplotlib.image import imread

from tests.headless_chromium import headless_chromium, missing_browser, wait_until
from tegrasp_drake.cli import main

pytestmark = pytest.mark.slow

# Model instances of the station (simulation/station.py) under Meshcat's illustration.
MODELS = ("jaco2", "robotiq_2f85", "object", "table")
READABLE_FRACTION = 0.2  # the gripper spans at least a fifth of the view's width or height

# Functions run in the page. They read the viewer's scene tree without creating nodes
# (SceneNode.find would), seek the animation, and measure in three.js's world.
PAGE_FUNCTIONS = """
window.tegrasp = {
  node(path) {
    let node = viewer.scene_tree;
    for (const name of path) {
      if (!(name in node.children)) return null;
      node = node.children[name];
    }
    return node;
  },
  meshCount(path) {
    const node = this.node(path);
    let count = 0;
    if (node) node.object.traverse(o => { if (o.isMesh) count += 1; });
    return count;
  },
  seek(t) {
    viewer.animator.pause();
    viewer.animator.seek(t);
    viewer.scene.updateMatrixWorld(true);
    viewer.set_dirty();
    viewer.render();
  },
  center(path) {  // in Drake's world frame (three.js's scene turns it to y up)
    const box = new MeshCat.THREE.Box3().setFromObject(this.node(path).object);
    return viewer.scene.worldToLocal(box.getCenter(new MeshCat.THREE.Vector3())).toArray();
  },
  screenBox(path) {  // the node's bounding box on screen, as fractions of the view
    const THREE = MeshCat.THREE;
    const box = new THREE.Box3().setFromObject(this.node(path).object);
    viewer.camera.updateMatrixWorld(true);
    const xs = [], ys = [];
    for (const x of [box.min.x, box.max.x]) for (const y of [box.min.y, box.max.y])
      for (const z of [box.min.z, box.max.z]) {
        const p = new THREE.Vector3(x, y, z).project(viewer.camera);
        xs.push((p.x + 1) / 2); ys.push((1 - p.y) / 2);
      }
    return {x0: Math.min(...xs), x1: Math.max(...xs), y0: Math.min(...ys), y1: Math.max(...ys)};
  },
  taxels(finger) {  // each bar's length [m] (its z scale) and colour
    const pad = this.node(['taxel_forces', finger]);
    return Object.keys(pad.children).sort().map(name => {
      const taxel = pad.children[name];
      const mesh = taxel.children['bar'].children['<object>'].object;
      return {length: taxel.object.scale.z, color: mesh.material.color.toArray()};
    });
  },
  visibleContacts() {
    const node = this.node(['drake', 'contact_forces']);
    let count = 0;
    if (node) node.object.traverse(o => { if (o.isMesh && o.visible) {
      let shown = true;
      for (let p = o; p; p = p.parent) shown = shown && p.visible;
      count += shown; } });
    return count;
  },
};
"""


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """`tegrasp demo --scenario-name box_hit_in_hold --html ... --json`, run once: its
    output folder and its JSON result."""
    out = tmp_path_factory.mktemp("demo_hit")
    stdout = io.StringIO()
    with contextlib.redirect_stdout(stdout):
        code = main(["demo", "--scenario-name", "box_hit_in_hold", "--out", str(out),
                     "--html", str(out / "replay.html"), "--json"])
    assert code == 0
    return out, json.loads(stdout.getvalue())


@pytest.fixture(scope="module")
def page(run):
    """The replay open in headless Chromium, with PAGE_FUNCTIONS loaded."""
    problem = missing_browser()
    if problem:
        pytest.fail(problem)
    out, _ = run
    with headless_chromium() as driver:
        driver.get((out / "replay.html").as_uri())
        wait_until(driver, "return typeof viewer !== 'undefined' && "
                           "viewer.animator.actions.length > 0")
        driver.execute_script(PAGE_FUNCTIONS)
        yield driver


def _span(result, state):
    """(start, end) [s] of the first visit of `state`."""
    transitions = result["transitions"]
    start = next(e["t"] for e in transitions if e["to"] == state)
    end = next(e["t"] for e in transitions if e["from"] == state and e["t"] > start)
    return start, end


def test_demo_writes_the_log_the_figures_and_the_replay(run):
    out, result = run
    assert ("Hold", "Avoid") in [(e["from"], e["to"]) for e in result["transitions"]]
    for key, name in (("log", "trial.npz"), ("figure", "states.png"),
                      ("signals_figure", "signals.png"), ("avoid_figure", "avoid.png"),
                      ("replay_html", "replay.html")):
        assert result[key] == str(out / name)
        assert (out / name).is_file()
    for name in ("states.png", "signals.png", "avoid.png"):
        image = imread(out / name)
        assert min(image.shape[:2]) > 1000  # 150 dpi: at least 7 in on each side
        assert np.ptp(image[..., :3]) > 0.5  # not a blank canvas


def test_replay_opens_offline_with_the_arm_gripper_object_and_an_animation(run, page):
    _, result = run
    for model in MODELS:
        assert page.execute_script(
            f"return tegrasp.meshCount(['drake', 'illustration', '{model}'])") > 0, model
    duration = page.execute_script("return viewer.animator.duration")
    assert duration == pytest.approx(result["sim_time_s"], abs=0.1)
    # Everything came from the file itself: no request left the page (and the proxy on a
    # closed port would have failed any).
    fetched = page.execute_script(
        "return performance.getEntriesByType('resource').map(e => e.name)")
    assert [url for url in fetched if not url.startswith(("data:", "file:"))] == []


def test_replay_lifts_the_object_with_contact_and_taxel_forces_shown(run, page):
    _, result = run
    hold_start, hold_end = _span(result, "Hold")
    page.execute_script("tegrasp.seek(0.0)")
    object_at_start = np.array(page.execute_script(
        "return tegrasp.center(['drake', 'illustration', 'object'])"))
    idle = page.execute_script("return tegrasp.taxels('left')")
    page.execute_script(f"tegrasp.seek({(hold_start + hold_end) / 2})")
    object_held = np.array(page.execute_script(
        "return tegrasp.center(['drake', 'illustration', 'object'])"))
    lift = object_held[2] - object_at_start[2]  # Drake's world: z up, metres
    assert lift > 0.5 * 0.06  # lifted by most of the 6 cm lift
    assert page.execute_script("return tegrasp.visibleContacts()") > 0
    for finger in ("left", "right"):
        held = page.execute_script(f"return tegrasp.taxels('{finger}')")
        assert len(held) == 12
        pressed = [t for t in held if t["length"] > 0.002]
        assert len(pressed) >= 4, finger  # the box's face presses several taxels
    assert all(t["length"] < 0.001 for t in idle)
    assert {tuple(t["color"]) for t in held} != {tuple(t["color"]) for t in idle}


LINKS = ("driver", "coupler", "finger", "spring_link")


def test_replay_shows_the_finger_linkage_moving(run, page):
    out, result = run
    hold_start, hold_end = _span(result, "Hold")
    paths = [["drake", "illustration", "robotiq_2f85", f"{finger}_{link}"]
             for finger in ("left", "right") for link in LINKS]
    for path in paths:
        assert page.execute_script(f"return tegrasp.meshCount({path})") > 0, path
    page.execute_script("tegrasp.seek(0.0)")
    open_pose = [np.array(page.execute_script(f"return tegrasp.center({p})")) for p in paths]
    page.execute_script(f"tegrasp.seek({(hold_start + hold_end) / 2})")
    gripper = np.array(page.execute_script(
        "return tegrasp.center(['drake', 'illustration', 'robotiq_2f85', 'base'])"))
    page.execute_script("tegrasp.seek(0.0)")
    base_open = np.array(page.execute_script(
        "return tegrasp.center(['drake', 'illustration', 'robotiq_2f85', 'base'])"))
    page.execute_script(f"tegrasp.seek({(hold_start + hold_end) / 2})")
    for path, before in zip(paths, open_pose):
        now = np.array(page.execute_script(f"return tegrasp.center({path})"))
        # Each link moved against the gripper body: the linkage closed on the box.
        moved = np.linalg.norm((now - gripper) - (before - base_open))
        assert moved > 0.003, path


def test_replay_screenshot_shows_the_gripper_at_a_readable_size(run, page):
    out, result = run
    hold_start, hold_end = _span(result, "Hold")
    page.execute_script(f"tegrasp.seek({(hold_start + hold_end) / 2})")
    box = page.execute_script("return tegrasp.screenBox(['drake', 'illustration', "
                              "'robotiq_2f85'])")
    assert max(box["x1"] - box["x0"], box["y1"] - box["y0"]) >= READABLE_FRACTION
    assert 0.0 < (box["x0"] + box["x1"]) / 2 < 1.0 and 0.0 < (box["y0"] + box["y1"]) / 2 < 1.0
    screenshot = out / "replay_hold.png"
    assert page.get_screenshot_as_file(str(screenshot))
    image = imread(screenshot)
    assert np.ptp(image[..., :3]) > 0.5  # the scene was rendered, not a blank page


def test_plot_redraws_the_trial_figures_in_every_format(run, tmp_path, capsys):
    out, _ = run
    log = str(out / "trial.npz")
    for what, figure in (("signals", "fig5ab.pdf"), ("trial", "fig9.svg"),
                         ("avoid", "fig10.png")):
        assert main(["plot", what, log, "--out", str(tmp_path / figure)]) == 0
    assert (tmp_path / "fig5ab.pdf").read_bytes().startswith(b"%PDF")
    assert b"<svg" in (tmp_path / "fig9.svg").read_bytes()[:1000]
    assert imread(tmp_path / "fig10.png").shape[1] > 1000
    assert main(["plot", "trial", log, "--format", "pdf", "--out",
                 str(tmp_path / "fig9.pdf")]) == 0
    capsys.readouterr()
