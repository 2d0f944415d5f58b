"""particles.golden.check: the checks of `particles golden check`, from Python."""

import json

import pytest

import particles
from conftest import SOURCE_DIR, scenario_path


def test_the_projects_golden_frame_and_state_pass_with_the_commands_report(tmp_path):
    report = particles.golden.check(SOURCE_DIR / "golden" / "golden.yaml", tmp_path / "report",
                                    only=["cloth_t0.5", "rigid_chain"], jobs=1)
    assert report and report.all_passed and (report.passed, report.failed) == (2, 0)
    assert [f.name for f in report.frames] == ["cloth_t0.5"] and report.frames[0].outcome == "passed"
    assert [s.name for s in report.states] == ["rigid_chain"] and report.states[0].values > 0
    assert report.html == str(tmp_path / "report" / "report.html")
    results = json.loads((tmp_path / "report" / "results.json").read_text())
    assert [f["name"] for f in results["frames"]] == ["cloth_t0.5"]
    assert "2 passed" in report.summary


def test_a_missing_reference_and_a_changed_frame_are_results_not_exceptions(tmp_path):
    manifest = tmp_path / "golden.yaml"
    manifest.write_text(f"references: refs\ndefaults:\n  render: {{size: 64x48}}\n"
                        f"frames:\n  - scenario: {scenario_path('cloth')}\n    times: [0.5]\n")
    first = particles.golden.check(manifest, tmp_path / "report")
    assert not first and first.missing == 1 and first.frames[0].outcome == "missing"
    (tmp_path / "refs").mkdir()
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")))
    sim.render(size=(64, 48)).save_png(tmp_path / "refs" / "cloth_t0.5.png")  # t = 0, not 0.5
    second = particles.golden.check(manifest, tmp_path / "report")  # replaces the earlier report
    frame = second.frames[0]
    assert frame.outcome == "failed" and frame.differing > 0 and frame.pixels == 64 * 48
    assert frame.actual and (tmp_path / "report" / frame.actual).is_file()
    assert any("particles" in command for command in frame.reproduce)


def test_bad_options_and_a_folder_that_is_not_a_report_are_refused(tmp_path):
    manifest = SOURCE_DIR / "golden" / "golden.yaml"
    for kwargs, message in [({"shard": "3"}, "K/N"), ({"shard": "3/2"}, "shard"), ({"only": "nope"}, "nope"),
                            ({"gl": "vulkan"}, "gl"), ({"raster": "dots"}, "raster"), ({"threshold": 300}, "threshold"),
                            ({"max_share": 2.0}, "maxShare"), ({"jobs": -1}, "jobs")]:
        with pytest.raises(particles.ArgumentError, match=message):
            particles.golden.check(manifest, tmp_path / "report", **kwargs)
    foreign = tmp_path / "mine"
    foreign.mkdir()
    (foreign / "thesis.tex").write_text("keep me")
    with pytest.raises(particles.ArgumentError, match="output"):
        particles.golden.check(manifest, foreign, only="cloth_t0.5")
    assert (foreign / "thesis.tex").read_text() == "keep me"
    with pytest.raises(particles.ScenarioError):
        particles.golden.check(tmp_path / "nowhere.yaml", tmp_path / "report")


def test_gpu_draws_on_a_gpu_or_says_there_is_none(tmp_path):
    # golden check --gpu from Python: on a GPU server the frame is drawn there (and compared); where
    # EGL lists no hardware device each frame is an error that says so, not an exception.
    report = particles.golden.check(SOURCE_DIR / "golden" / "golden.yaml", tmp_path / "report", only="cloth_t0.5",
                                    gl="egl", gpu=True, jobs=1)
    frame = report.frames[0]
    if frame.outcome == "error":
        assert "a GPU was asked for" in frame.message and report.errors == 1
    else:
        assert frame.outcome in ("passed", "failed") and frame.pixels == 320 * 240
    assert frame.reproduce[-1].endswith("--only cloth_t0.5 --gl egl --gpu")
