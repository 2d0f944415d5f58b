"""Frames and videos from Python: the pixels of `particles render --at`, PNGs, VideoWriter's
whole-or-nothing files and its checks on frames, through the Python module."""

import threading

import numpy as np
import pytest

import particles
from conftest import scenario_path

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize("name,at", [("cloth", "0.5"), ("rigid_chain", "0.3"), ("cloth_stiff", "2.5")])
def test_render_gives_the_bytes_of_particles_render_at(run_particles, tmp_path, name, at):
    # The golden frames' look (golden/golden.yaml: 320x240, the dark theme, 4 samples).
    run_particles("render", scenario_path(name), "--at", at, "--size", "320x240", "-o", "cli.png", "--quiet")
    sim = particles.Simulation(particles.Scenario.load(scenario_path(name)), threads=2)
    sim.advance(float(at))
    frame = sim.render(size=(320, 240))
    assert isinstance(frame, particles.Frame) and frame.shape == (240, 320, 4) and frame.dtype == np.uint8
    assert frame.encode_png() == (tmp_path / "cli.png").read_bytes()
    frame.save_png(tmp_path / "api.png")
    assert (tmp_path / "api.png").read_bytes() == (tmp_path / "cli.png").read_bytes()


@pytest.mark.parametrize("raster", ["triangles", "tiles", "resident", "cpu"])
def test_each_raster_path_gives_the_bytes_of_particles_render(run_particles, tmp_path, raster):
    # The resident path (springs and particles kept in GL's buffers) included: the library draws
    # the command's springs by index too.
    run_particles("render", scenario_path("cloth"), "--at", "1.5", "--size", "320x240", "--raster", raster,
                  "-o", "cli.png", "--quiet")
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=2)
    sim.advance(1.5)
    assert sim.render(size=(320, 240), raster=raster).encode_png() == (tmp_path / "cli.png").read_bytes()


def test_frames_show_in_a_notebook_and_a_renderer_draws_several_simulations(tmp_path):
    cloth = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=1)
    chain = particles.Simulation(particles.Scenario.load(scenario_path("rigid_chain")), threads=1)
    frame = cloth.render(size=(64, 48), theme="light", msaa=1)
    png = frame._repr_png_()
    assert png.startswith(PNG_SIGNATURE) and png == frame.encode_png()
    assert frame.encode_png(alpha=True) != png
    assert frame[:, :, 0]._repr_png_() is None  # a slice is no longer a picture
    renderer = particles.Renderer(size=(64, 48), theme="light", msaa=1)
    assert renderer.gl_description == ""
    assert np.array_equal(renderer.render(cloth), frame)
    assert renderer.render(chain).shape == (48, 64, 4)
    assert renderer.gl_description == "none (the cpu raster)"  # auto without a GPU: no GL context
    by_scene = particles.Renderer().render(cloth)  # the scenario's render.size
    assert by_scene.shape[2] == 4 and by_scene.shape[:2] != (48, 64)
    transparent = cloth.render(size=(64, 48), background="transparent")
    assert transparent[0, 0, 3] == 0


def test_a_renderer_draws_from_any_thread():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=1)
    first = sim.render(size=(64, 48))
    frames = []
    worker = threading.Thread(target=lambda: frames.append(sim.render(size=(64, 48))))
    worker.start()
    worker.join()
    assert len(frames) == 1 and np.array_equal(frames[0], first)
    assert np.array_equal(sim.render(size=(64, 48)), first)


def test_bad_render_settings_are_argument_errors():
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=1)
    for kwargs, message in [({"theme": "pink"}, "theme"), ({"msaa": 3}, "msaa"), ({"size": (0, 10)}, "size"),
                            ({"size": "big"}, "size"), ({"gl": "vulkan"}, "gl"), ({"raster": "dots"}, "raster"),
                            ({"background": "blue"}, "background")]:
        with pytest.raises(particles.ArgumentError, match=message):
            sim.render(**kwargs)
    with pytest.raises(particles.OutputError):
        sim.render(size=(8, 8)).save_png("/nonexistent-folder/frame.png")


@pytest.mark.parametrize("extension", ["mp4", "webm", "gif"])
def test_a_video_is_written_whole_by_the_context_manager(tmp_path, extension):
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=1)
    path = tmp_path / f"cloth.{extension}"
    with particles.VideoWriter(path, fps=10) as video:
        for _ in range(5):
            sim.advance(0.1)
            video.write(sim.render(size=(64, 48)))
        assert not path.exists()  # written under a temporary name until finished
    assert video.frames == 5 and path.stat().st_size > 0
    assert "5 frames" in repr(video)


def test_an_exception_or_ctrl_c_in_the_block_leaves_no_video_and_an_old_file_as_it_was(tmp_path):
    sim = particles.Simulation(particles.Scenario.load(scenario_path("cloth")), threads=1)
    path = tmp_path / "clip.mp4"
    for raised in (RuntimeError("stop"), KeyboardInterrupt()):
        with pytest.raises(type(raised)):
            with particles.VideoWriter(path, fps=10) as video:
                video.write(sim.render(size=(64, 48)))
                raise raised
        assert list(tmp_path.iterdir()) == []
    path.write_bytes(b"old")
    with pytest.raises(KeyboardInterrupt):
        with particles.VideoWriter(path) as video:
            video.write(sim.render(size=(64, 48)))
            raise KeyboardInterrupt
    assert path.read_bytes() == b"old" and list(tmp_path.iterdir()) == [path]
    video = particles.VideoWriter(tmp_path / "dropped.webm")
    video.write(sim.render(size=(64, 48)))
    del video  # never finished: nothing is left
    assert sorted(p.name for p in tmp_path.iterdir()) == ["clip.mp4"]


def test_frames_of_the_wrong_shape_or_dtype_are_refused(tmp_path):
    video = particles.VideoWriter(tmp_path / "v.mp4", fps=10)
    good = np.zeros((48, 64, 4), np.uint8)
    for bad, message in [(good.astype(np.float64), "dtype"), (good.astype(np.int16), "dtype"),
                         (np.zeros((48, 64), np.uint8), "shape"), (np.zeros((48, 64, 2), np.uint8), "shape"),
                         (np.zeros((0, 64, 4), np.uint8), "shape"), ("frame", "dtype|array"),
                         (np.zeros((47, 64, 4), np.uint8), "even")]:
        with pytest.raises(particles.ArgumentError, match=message):
            video.write(bad)
    video.write(good[:, :, :3])  # RGB is taken, alpha 255
    video.write(np.asfortranarray(good))  # any memory order
    with pytest.raises(particles.ArgumentError, match="like the first"):
        video.write(np.zeros((50, 64, 4), np.uint8))
    video.finish()
    assert video.frames == 2
    with pytest.raises(particles.ArgumentError, match="finished"):
        video.write(good)
    for kwargs in ({"fps": 0}, {"preset": "warp"}, {"crf": 99}, {"keyint_seconds": -1.0}, {"alpha": True}):
        with pytest.raises(particles.ArgumentError):
            particles.VideoWriter(tmp_path / "w.mp4", **kwargs)
    with pytest.raises(particles.ArgumentError, match="not a video"):
        particles.VideoWriter(tmp_path / "w.png")
