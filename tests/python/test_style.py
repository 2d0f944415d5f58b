"""Styles from Python: a dict of the `style` section's keys (or a style file's text) given to
Scenario.set_style or load(style=...) draws the frame `particles render --style FILE --at T` writes,
byte for byte, trails and a followed camera included; a wrong key or value is the file's
ScenarioError, with its message; None or an empty dict is no style."""

import pytest

import particles
from conftest import SOURCE_DIR

# The scene and its style file, shared with the C++ tests (tests/test_api_style.cpp).
SCENE = (SOURCE_DIR / "tests" / "fixtures" / "styled_api.yaml").read_text(encoding="utf-8")
LOOK_YAML = (SOURCE_DIR / "tests" / "fixtures" / "styled_api_look.yaml").read_text(encoding="utf-8")

# The style file's keys as a dict.
LOOK = {
    "particles": {"color_by": "speed", "colormap": "magma_r", "range": {"min": 0, "max": 2.0}},
    "springs": {"color_by": "tension", "colormap": "coolwarm", "width": "2px"},
    "bodies": {"color_by": "angular_speed", "range": "auto", "outline": "#ffffff"},
    "colorbar": {"for": "particles", "label": "speed (m/s)", "position": "left"},
    "title": 'Cloth: "styled"',
    "scale_bar": True,
    "select": [
        {"particles": "cloth[0][*]", "color": "orange", "radius": "5px"},
        {"particles": ("cloth[4][2]", "cloth[4][3]"), "trail": {"seconds": 0.5, "width": "2px"},
         "arrow": {"of": "velocity", "scale": 0.2, "max": "40px"}, "label": "corner"},
        {"bodies": "box", "trail": {"seconds": "all", "color": "#ff000080"}, "arrow": "force"},
    ],
}


@pytest.fixture
def scene(tmp_path):
    path = tmp_path / "scene.yaml"
    path.write_text(SCENE, encoding="utf-8")
    return path


def program_png(run_particles, tmp_path, scene, at, style=None, *options):
    """The PNG's bytes `particles render SCENE [--style STYLE] --at AT` writes."""
    style_options = ["--style", style] if style else []
    run_particles("render", scene, *style_options, "--at", at, "-o", "cli.png", "--quiet", *options)
    return (tmp_path / "cli.png").read_bytes()


def test_a_style_dict_draws_the_frames_of_render_style_at(run_particles, tmp_path, scene):
    (tmp_path / "look.yaml").write_text(LOOK_YAML, encoding="utf-8")
    by_dict = particles.Simulation(particles.Scenario.load(scene, style=LOOK), threads=1)
    by_text = particles.Simulation(particles.Scenario.from_text(SCENE, "scene.yaml").set_style(LOOK_YAML), threads=2)
    renderer = particles.Renderer()
    for at in ("0", "0.3", "0.75"):
        expected = program_png(run_particles, tmp_path, scene, at, "look.yaml")
        by_dict.advance_to(float(at))
        by_text.advance_to(float(at))
        assert renderer.render(by_dict).encode_png() == expected, at
        assert by_text.render().encode_png() == expected, at


def test_a_style_dict_takes_the_other_settings_and_set_values(run_particles, tmp_path, scene):
    (tmp_path / "speed.yaml").write_text("particles: {color_by: speed}\ncolorbar: true\n", encoding="utf-8")
    scenario = particles.Scenario.load(scene, set={"style.title": "set"},
                                       style={"particles": {"color_by": "speed"}, "colorbar": True})
    sim = particles.Simulation(scenario)
    sim.advance_to(0.4)
    expected = program_png(run_particles, tmp_path, scene, "0.4", "speed.yaml", "--size", "200x100", "--theme",
                           "light", "--msaa", "2", "--set", "style.title=set")
    assert sim.render(size=(200, 100), theme="light", msaa=2).encode_png() == expected


def test_none_or_an_empty_style_is_no_style_and_none_in_a_dict_takes_a_key_away(run_particles, tmp_path, scene):
    own = program_png(run_particles, tmp_path, scene, "0.2")
    for style in (None, {}, ""):
        sim = particles.Simulation(particles.Scenario.load(scene, style=style))
        sim.advance_to(0.2)
        assert sim.render().encode_png() == own, style
    scenario = particles.Scenario.load(scene, style={"particles": {"color_by": "speed"}})
    scenario.set_style(None)  # takes the style before away
    sim = particles.Simulation(scenario)
    sim.advance_to(0.2)
    assert sim.render().encode_png() == own
    (tmp_path / "red.yaml").write_text("particles: {color_by: ~, color: red}\n", encoding="utf-8")
    red = particles.Simulation(scenario.copy().set_style({"particles": {"color_by": None, "color": "red"}}))
    red.advance_to(0.2)
    assert red.render().encode_png() == program_png(run_particles, tmp_path, scene, "0.2", "red.yaml")


@pytest.mark.parametrize("style,yaml,key_path,words", [
    ({"particles": {"color_by": "sped"}}, "particles: {color_by: sped}", "style.particles.color_by",
     "unknown particle quantity 'sped'; did you mean 'speed'?"),
    ({"particles": {"colr_by": "speed"}}, "particles: {colr_by: speed}", "style.particles.colr_by",
     "did you mean 'color_by'?"),
    ({"springs": {"width": "-2px"}}, "springs: {width: -2px}", "style.springs.width", "expected a length > 0"),
    ({"bodies": {"color": "steelblu"}}, "bodies: {color: steelblu}", "style.bodies.color", "'steelblue'"),
    ({"particles": {"range": [2, 1]}}, "particles: {range: [2, 1]}", "style.particles.range", "lo < hi"),
    ({"select": [{"particles": "clth"}]}, "select: [{particles: clth}]", "style.select[0].particles", "clth"),
    ({"colorbar": {"for": "bodies"}}, "colorbar: {for: bodies}", "style.colorbar.for", "not coloured by a quantity"),
    ({"particles": {"color": "red"}}, "particles: {color: red}", "style.particles.color", "color: ~"),
])
def test_a_bad_style_is_the_style_files_scenario_error(tmp_path, scene, style, yaml, key_path, words):
    (tmp_path / "bad.yaml").write_text(yaml + "\n", encoding="utf-8")
    scenario = particles.Scenario.load(scene)
    with pytest.raises(particles.ScenarioError) as from_file:
        particles.Scenario.load(scene).set_style((tmp_path / "bad.yaml").read_text(encoding="utf-8"))
    with pytest.raises(particles.ScenarioError) as from_dict:
        scenario.set_style(style)
    e = from_dict.value
    assert (e.file, e.line, e.column, e.key_path) == ("style", 0, 0, key_path)
    assert e.message == from_file.value.message and words in e.message
    assert str(e) == f"style: error: {key_path}: {e.message}"
    assert from_file.value.line == 1 and str(from_file.value).startswith("style:1:")
    with pytest.raises(particles.ScenarioError, match="sped"):
        particles.Scenario.load(scene, style={"particles": {"color_by": "sped"}})
    # The scenario stays as it was: its own style, with no error.
    assert particles.Scenario.load(scene).summary() == scenario.summary()


def test_what_a_style_is_not_is_an_argument_error(scene):
    scenario = particles.Scenario.load(scene)
    with pytest.raises(particles.ArgumentError, match="Scenario.set_style: style takes a dict"):
        scenario.set_style(3)
    with pytest.raises(particles.ArgumentError, match="Scenario.load: style takes a dict"):
        particles.Scenario.load(scene, style=[("particles", {})])
    with pytest.raises(particles.ArgumentError, match="must be finite"):
        scenario.set_style({"particles": {"range": [0, float("nan")]}})
    with pytest.raises(particles.ArgumentError, match="keys of a dict"):
        scenario.set_style({1: "x"})
    with pytest.raises(particles.ScenarioError, match="unknown key 'colour'"):
        scenario.set_style({"colour": "red"})
