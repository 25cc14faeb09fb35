"""import statmc: the numpy round trip, denoise equal to the command line bit for bit, the
command line's parameter checks and messages, errors that write nothing, and the GIL
released while an operator runs. Run by ctest (python.pytest) with PYTHONPATH on the
built package and STATMC_CLI naming the statmc executable."""

import os
import subprocess
import threading
import time

import numpy as np
import pytest

import statmc

CLI = os.environ.get("STATMC_CLI")


def statistics_image(width=40, height=24, seed=3):
    """A variance-AOV statistics image: a dark and a bright half, noisy means, per-sample
    variances and counts that differ from pixel to pixel."""
    rng = np.random.default_rng(seed)
    level = np.where(np.arange(width) < width // 2, 0.2, 0.9).astype(np.float32)
    count = (8 + (np.add.outer(np.arange(height), np.arange(width)) % 3)).astype(np.float32)
    variance = np.full((height, width, 3), 0.05, np.float32)
    noise = rng.normal(0, 1, (height, width, 3)).astype(np.float32)
    beauty = level[None, :, None] + noise * np.sqrt(variance / count[:, :, None])
    image = statmc.Image({"beauty": beauty.astype(np.float32),
                          "sampleCount": count[:, :, None],
                          "variance": variance},
                         attributes={"statmc:spp": 8, "note": "synthetic", "gain": 1.5})
    return image


def test_numpy_round_trip_is_exact(tmp_path):
    image = statistics_image()
    image["normal"] = np.linspace(-1, 1, 40 * 24 * 3, dtype=np.float32).reshape(24, 40, 3)
    path = tmp_path / "round.exr"
    statmc.write_statistics(path, image)
    back = statmc.read_statistics(path)
    assert set(back) == set(image)
    for layer in image:
        assert back[layer].dtype == np.float32
        assert np.array_equal(back[layer], image[layer]), layer
    assert back.channels["normal"] == ["X", "Y", "Z"]
    assert back.channels["beauty"] == ["R", "G", "B"]
    assert back.attributes["statmc:spp"] == 8
    assert back.attributes["note"] == "synthetic"
    assert back.attributes["gain"] == pytest.approx(1.5)


def test_denoise_equals_the_command_line_bitwise(tmp_path):
    assert CLI, "STATMC_CLI must name the statmc executable"
    source = tmp_path / "stats.exr"
    statmc.write_statistics(source, statistics_image())
    cli_out = tmp_path / "cli.exr"
    subprocess.run([CLI, str(source), "--denoise:radius=5:alpha=0.01", "-o", str(cli_out)],
                   check=True)
    expected = statmc.read_statistics(cli_out)
    got = statmc.denoise(source, radius=5, alpha=0.01)
    assert np.array_equal(got["beauty"], expected["beauty"])
    # It denoised: the means moved.
    assert not np.array_equal(got["beauty"], statmc.read_statistics(source)["beauty"])
    # From arrays as from the file, and with the same defaults.
    assert np.array_equal(statmc.denoise(statmc.read_statistics(source), radius=5,
                                         alpha=0.01)["beauty"], expected["beauty"])
    assert got.attributes["statmc:denoised"] == 1
    # from= is spelled from_= in Python.
    assert np.array_equal(statmc.denoise(source, radius=5, alpha=0.01, from_="statmc")["beauty"],
                          expected["beauty"])


def test_an_operators_notes_are_python_warnings_with_the_command_lines_text(tmp_path):
    source = tmp_path / "stats.exr"
    statmc.write_statistics(source, statistics_image())
    # Diagnostics describe one radius per pixel, so the default leaves its ladder out and
    # says so: on stderr from the command line, as a warning here.
    cli = subprocess.run([CLI, str(source), "--denoise:diagnostics=1", "-o",
                          str(tmp_path / "cli.exr")], capture_output=True, text=True, check=True)
    assert "left out ici" in cli.stderr
    with pytest.warns(UserWarning) as caught:
        statmc.denoise(source, diagnostics=True)
    assert [str(w.message) for w in caught] == [line.replace(str(source), str(source))
                                                for line in cli.stderr.splitlines()]
    # Warnings turned into errors stop the call.
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning):
            statmc.denoise(source, diagnostics=True)


def test_read_layers_are_views_and_edits_reach_the_operator(tmp_path):
    # A read image's layers are views into one array, which goes back to the operator
    # whole; an edit in place is in that array, and a replaced layer makes a new one.
    source = tmp_path / "stats.exr"
    statmc.write_statistics(source, statistics_image())
    image = statmc.read_statistics(source)
    assert image["beauty"].base is not None
    brighter = statmc.read_statistics(source)
    brighter["beauty"] = brighter["beauty"] + np.float32(0.5)  # replaced: a copy goes
    expected = statmc.denoise(brighter, radius=5)["beauty"]
    image["beauty"] += np.float32(0.5)  # edited in place: the shared array goes
    assert np.array_equal(statmc.denoise(image, radius=5)["beauty"], expected)
    assert not np.array_equal(expected, statmc.denoise(source, radius=5)["beauty"])
    # A result's layers are views too, and denoising one again reads what it holds.
    once = statmc.denoise(source, radius=5)
    assert np.array_equal(statmc.denoise(once, radius=5)["beauty"],
                          statmc.denoise(statmc.Image(dict(once), once.channels, once.attributes),
                                         radius=5)["beauty"])


def test_an_edit_of_a_layer_read_as_a_copy_is_passed_on():
    # Channels in an order (another tool's) where a layer's channels are not side by side:
    # that layer is a copy, not a view, so the image must be joined anew, edit included.
    names = ["aov.X", "R", "G", "B", "aov.R", "aov.G", "aov.B"]
    pixels = np.arange(2 * 3 * 7, dtype=np.float32).reshape(2, 3, 7)
    image = statmc._from_native((names, pixels, {}, (0, 0)))
    assert image.channels["aov"] == ["R", "G", "B", "X"]
    image["aov"] += np.float32(100)
    native_names, native_pixels = image._native()[:2]
    x = native_names.index("aov.X")
    assert np.array_equal(native_pixels[:, :, x], pixels[:, :, 0] + 100)
    # While a read of side-by-side channels passes its own array on untouched.
    image = statmc._from_native((names[1:4], pixels[:, :, 1:4].copy(), {}, (0, 0)))
    assert image._native()[1] is image._source[1]


@pytest.mark.parametrize("options, modifier", [
    ({"radius": -1}, "radius=-1"),
    ({"method": "fancy"}, "method=fancy"),
    ({"guides": ["albedo", "depth"]}, "guides=albedo,depth"),
    ({"sigma_albedo": "wide"}, "sigma_albedo=wide"),
    ({"no_such": 1}, "no_such=1"),
    ({"device": "gpu"}, "device=gpu"),
    ({"joint": "maybe"}, "joint=maybe"),
    ({"nonfinite": "skip"}, "nonfinite=skip"),
    ({"ici": 0.01}, "ici=0.01"),
])
def test_options_are_checked_with_the_command_lines_messages(tmp_path, options, modifier):
    source = tmp_path / "stats.exr"
    statmc.write_statistics(source, statistics_image())
    with pytest.raises(ValueError) as raised:
        statmc.denoise(source, **options)
    cli = subprocess.run([CLI, str(source), "--denoise:" + modifier, "-o",
                          str(tmp_path / "x.exr")], capture_output=True, text=True)
    assert cli.returncode == 1
    assert cli.stderr.strip() == "statmc: error: " + str(raised.value)


def test_device_cuda_runs_or_fails_as_the_command_line_does(tmp_path):
    """Where a GPU is present both run on it and agree bit for bit (the GPU's sums have a
    fixed order); elsewhere both fail with the same message, which names the reason."""
    source = tmp_path / "stats.exr"
    statmc.write_statistics(source, statistics_image())
    out = tmp_path / "cli.exr"
    cli = subprocess.run([CLI, str(source), "--denoise:device=cuda", "-o", str(out)],
                         capture_output=True, text=True)
    if cli.returncode == 0:
        got = statmc.denoise(source, device="cuda")
        assert np.array_equal(got["beauty"], statmc.read_statistics(out)["beauty"])
        return
    with pytest.raises(ValueError) as raised:
        statmc.denoise(source, device="cuda")
    # The command line names the file it read; the reason is the same words.
    reason = str(raised.value).split("device=cuda: ", 1)[1]
    assert reason
    assert cli.stderr.strip() == ("statmc: error: --denoise: " + str(source) +
                                  ": device=cuda: " + reason)
    assert not out.exists()


def test_bad_input_raises_and_writes_nothing(tmp_path):
    plain = statmc.Image({"beauty": np.ones((8, 8, 3), np.float32)})
    with pytest.raises(ValueError, match="missing layer sampleCount"):
        statmc.denoise(plain)
    uneven = statistics_image()
    uneven["albedo"] = np.ones((5, 5, 3), np.float32)
    target = tmp_path / "out.exr"
    with pytest.raises(ValueError, match="differ in size"):
        statmc.write_statistics(target, uneven)
    with pytest.raises(OSError):
        statmc.write_statistics(tmp_path / "missing" / "out.exr", statistics_image())
    with pytest.raises(OSError, match="no such file"):
        statmc.read_statistics(tmp_path / "absent.exr")
    assert os.listdir(tmp_path) == []


def test_the_gil_is_released_while_denoising():
    big = statistics_image(width=1024, height=768, seed=11)
    options = {"radius": 20, "method": "classic"}
    began = time.perf_counter()
    serial = [statmc.denoise(big, **options)["beauty"] for _ in range(2)]
    one_denoise = (time.perf_counter() - began) / 2
    results = [None, None]

    def work(k):
        results[k] = statmc.denoise(big, **options)["beauty"]

    # Two Python threads denoising at once give what each gives alone.
    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    stamps = [time.perf_counter()]
    for t in threads:
        t.start()
    # Python code keeps running beside them. With the GIL held through the filter, this
    # loop would stall for a whole filter run; released, it stalls only while the
    # threads convert arrays in Python (a few ms).
    while any(t.is_alive() for t in threads):
        time.sleep(0.001)
        stamps.append(time.perf_counter())
    for t in threads:
        t.join()
    for k in range(2):
        assert np.array_equal(results[k], serial[k])
    longest_stall = max(b - a for a, b in zip(stamps, stamps[1:]))
    assert longest_stall < one_denoise / 2, (longest_stall, one_denoise)


def test_passes_compare_and_merge_take_lists(tmp_path):
    rng = np.random.default_rng(5)
    renders = [statmc.Image({"beauty": rng.random((6, 9, 3), dtype=np.float32)})
               for _ in range(3)]
    stats = statmc.passes(renders)
    stacked = np.stack([r["beauty"] for r in renders])
    assert np.allclose(stats["beauty"], stacked.mean(axis=0), rtol=1e-6)
    assert np.allclose(stats["variance"], stacked.var(axis=0, ddof=1), rtol=1e-4, atol=1e-7)
    assert np.all(stats["sampleCount"] == 3)
    report = statmc.compare(renders[0], renders[0]).report
    assert "relMSE" in report or "RMSE" in report, report
    with pytest.raises(ValueError, match="^--passes: needs at least 2 renders, got 1$"):
        statmc.passes(renders[:1])


def test_compare_returns_its_metrics_as_numbers():
    reference = statmc.Image({"beauty": np.full((6, 9, 3), 0.5, np.float32)})
    offset = statmc.Image({"beauty": np.full((6, 9, 3), 0.625, np.float32)})
    metrics = statmc.compare(offset, reference).metrics
    assert set(metrics) == {"RMSE", "MAE", "relMSE", "SSIM", "DSSIM"}
    assert metrics["RMSE"] == pytest.approx(0.125, abs=1e-7)
    assert metrics["MAE"] == pytest.approx(0.125, abs=1e-7)
    # relMSE = mean of (x - r)^2 / (r^2 + 0.01)
    assert metrics["relMSE"] == pytest.approx(0.125 ** 2 / (0.25 + 0.01), rel=1e-6)
    assert statmc.compare(reference, reference).metrics["DSSIM"] == pytest.approx(0, abs=1e-12)


def test_errors_are_the_command_lines(tmp_path):
    if not CLI:
        pytest.fail("STATMC_CLI is not set: ctest sets it to the statmc executable")
    render = statmc.Image({"beauty": np.full((6, 9, 3), 0.5, np.float32)})
    statmc.write_statistics(tmp_path / "one.exr", render)
    cli = subprocess.run([CLI, str(tmp_path / "one.exr"), "--passes", "-o",
                          str(tmp_path / "out.exr")], capture_output=True, text=True)
    assert cli.returncode == 1
    with pytest.raises(ValueError) as python:
        statmc.passes([tmp_path / "one.exr"])
    assert cli.stderr == f"statmc: error: {python.value}\n"


def test_version_and_operator_docstrings():
    assert statmc.__version__.count(".") == 2, statmc.__version__
    for function, parameter in ((statmc.denoise, "radius"), (statmc.passes, "from"),
                                (statmc.merge, "allow_partial"), (statmc.compare, "epsilon")):
        assert parameter in function.__doc__, (function.__name__, function.__doc__)


def test_temporal_denoise_equals_the_command_lines_sequence(tmp_path):
    for frame in (1, 2, 3):
        statmc.write_statistics(tmp_path / f"shot.{frame:04d}.exr", statistics_image(seed=frame))
    subprocess.run([CLI, str(tmp_path / "shot.#.exr"), "--frames", "1-3",
                    "--denoise:temporal=1:radius=4", "-o", str(tmp_path / "out.#.exr")],
                   check=True)
    expected = statmc.read_statistics(tmp_path / "out.0002.exr")
    got = statmc.denoise(tmp_path / "shot.0002.exr", previous=[tmp_path / "shot.0001.exr"],
                         next=[statmc.read_statistics(tmp_path / "shot.0003.exr")],
                         temporal=1, radius=4)
    assert np.array_equal(got["beauty"], expected["beauty"])
    # The frames mattered: alone, the frame denoises otherwise.
    alone = statmc.denoise(tmp_path / "shot.0002.exr", radius=4)
    assert not np.array_equal(alone["beauty"], expected["beauty"])
    with pytest.raises(ValueError, match="needs a frame sequence"):
        statmc.denoise(tmp_path / "shot.0002.exr", temporal=1)


def test_verify_takes_the_candidate_as_an_array_and_equals_the_command_line(tmp_path):
    assert CLI, "STATMC_CLI must name the statmc executable"
    source = tmp_path / "stats.exr"
    image = statistics_image()
    statmc.write_statistics(source, image)
    # Right on the right half; on the left 0.5 against a truth of 0.2, four standard errors
    # of a pixel and twelve of its box: rejected there, and on the right at most at the
    # rate alpha (about 4 of its 432 pixels at 0.01; a deterministic seed).
    candidate = np.where(np.arange(40)[None, :, None] < 20, 0.5, 0.9).astype(np.float32)
    candidate = np.broadcast_to(candidate, (24, 40, 3)).copy()
    got = statmc.verify(source, candidate, alpha=0.01)
    rejected = got["diagnostics"][:, :, 0]
    assert rejected[:, :18].all() and rejected[:, 22:].mean() < 0.05
    kept = rejected == 0
    assert np.array_equal(got["beauty"][kept], candidate[kept])
    statmc.write_statistics(tmp_path / "candidate.exr", statmc.Image({"beauty": candidate}))
    subprocess.run([CLI, str(source), str(tmp_path / "candidate.exr"), "--verify:alpha=0.01",
                    "-o", str(tmp_path / "cli.exr")], check=True, stdout=subprocess.DEVNULL)
    assert np.array_equal(got["beauty"], statmc.read_statistics(tmp_path / "cli.exr")["beauty"])
    assert "rejected" in got.report
    with pytest.raises(ValueError, match="the candidate.* differ in resolution: 20x24 vs 40x24"):
        statmc.verify(source, candidate[:, :20])
