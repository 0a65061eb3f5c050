"""The sensor on its own: camsim.Sensor, expose(), develop(), display().

- expose(): mean and temporal variance of 64 frames of a uniform electrons image match
  EMVA 1288's linear model (mean K(mu_e + mu_d) + black, variance K^2(sigma_r^2 + mu_e +
  mu_d) + 1/12 DN^2 quantisation) within 2 %, at two signal levels and two ISOs;
- the same seed gives the same bytes, another seed other ones; frame f of a stack is the
  frame expose(first_frame=f) draws alone; a thread count does not change the bytes;
- another frame index or seed changes only the temporal noise: the fixed pattern (mean of
  64 frames) correlates above 0.8 between seeds, single frames' residuals do not (|r| < 0.1);
- with a capture's seed, frame, exposure and ISO, expose() gives the capture's raw bytes,
  develop() its ACEScg and display() its display values and PNG bytes, bit for bit;
- bad input raises camsim.InputError naming the argument;
- expose_file() (`camsim expose` in Python) writes the CLI's bytes, and its frames are
  expose() with exposure_scale on the file's electrons.
"""
import subprocess

import numpy as np
import pytest

import camsim
from conftest import BOX

SENSOR = "smartphone-1.4um"


@pytest.fixture(scope="module")
def sensor():
    return camsim.Sensor(SENSOR)


@pytest.mark.parametrize("electrons,iso", [(300.0, 50), (3000.0, 50), (300.0, 400)])
def test_mean_and_variance_follow_the_emva_linear_model(sensor, electrons, iso):
    t = 0.01
    e = np.full((64, 64), electrons, np.float32)
    frames = camsim.expose(e, sensor, seed=11, frames=64, exposure_time=t, iso=iso).astype(float)
    assert frames.max() < sensor.white_level_dn  # below saturation: the linear model holds
    k = sensor.system_gain(iso)
    mu = electrons + sensor.dark_current_e_per_s * t
    mean_model = k * mu + sensor.black_level_dn
    var_model = k * k * (sensor.read_noise_e ** 2 + mu) + 1.0 / 12.0
    assert frames.mean() == pytest.approx(mean_model, rel=0.02)
    temporal = frames.var(axis=0, ddof=1).mean()  # per photosite over frames: no fixed pattern
    assert temporal == pytest.approx(var_model, rel=0.02)


def test_same_seed_same_frames_and_frame_f_is_first_frame_f(sensor):
    e = np.random.default_rng(0).uniform(0, 2000, (24, 32)).astype(np.float32)
    a = camsim.expose(e, sensor, seed=5, frames=8)
    assert a.shape == (8, 24, 32) and a.dtype == np.uint16
    np.testing.assert_array_equal(a, camsim.expose(e, sensor, seed=5, frames=8, threads=1))
    np.testing.assert_array_equal(a[5], camsim.expose(e, sensor, seed=5, first_frame=5))
    assert camsim.expose(e, sensor, seed=5).shape == (24, 32)
    assert not np.array_equal(a[0], a[1])
    assert not np.array_equal(a, camsim.expose(e, sensor, seed=6, frames=8))


def test_only_temporal_noise_changes_with_seed_and_frame(sensor):
    # At 5000 e- (below saturation at base ISO, 6000 e-) the PRNU pattern (0.7 %: 35 e- rms)
    # is well above the 64-frame mean's shot noise (71 e- / 8): the two means correlate at
    # about 35^2 / (35^2 + 8.8^2) = 0.94 when the pattern is the same, near 0 if it is not.
    e = np.full((64, 64), 5000.0, np.float32)
    a = camsim.expose(e, sensor, seed=1, frames=64).astype(float)
    b = camsim.expose(e, sensor, seed=2, frames=64, first_frame=64).astype(float)
    pa, pb = a.mean(axis=0), b.mean(axis=0)
    assert a.max() < sensor.white_level_dn
    assert np.corrcoef(pa.ravel(), pb.ravel())[0, 1] > 0.8
    ra, rb = a[0] - pa, b[0] - pb
    assert abs(np.corrcoef(ra.ravel(), rb.ravel())[0, 1]) < 0.1


@pytest.fixture(scope="module")
def box():
    scene = camsim.load(BOX, overrides={"seed": 3})
    return scene, scene.render(threads=2)


def test_expose_develop_display_give_the_capture_bytes(box):
    scene, r = box
    s = camsim.Sensor.of(scene)
    meta = r["meta"]["sensor"]
    for b in r["brackets"]:
        raw = camsim.expose(b["electrons"], s, seed=meta["noise_seed"], first_frame=b["frame_index"],
                            exposure_time=b["exposure_time_s"], iso=meta["iso"], noise=meta["noise"])
        np.testing.assert_array_equal(raw, b["raw"])
    isp = r["meta"]["isp"]
    acescg = camsim.develop(r["raw"], s, white_balance=isp["white_balance"],
                            illuminant=isp["illuminant"], demosaic=isp["demosaic"])
    np.testing.assert_array_equal(acescg, r["acescg"])
    np.testing.assert_array_equal(camsim.display(acescg), r["display"])
    np.testing.assert_array_equal(camsim.display(acescg, dtype="uint8"), r["display8"])


def test_stacked_sensor_round_trip():
    s = camsim.Sensor("ideal-xyz")
    assert s.stacked and s.channels == ["X", "Y", "Z"]
    e = np.full((8, 8, 3), 500.0, np.float32)
    raw = camsim.expose(e, s, seed=1, frames=2)
    assert raw.shape == (2, 8, 8, 3)
    img = camsim.develop(raw[0], s)
    assert img.shape == (8, 8, 3) and np.isfinite(img).all()
    planes = {c: np.ascontiguousarray(raw[0][..., i]) for i, c in enumerate(s.channels)}
    np.testing.assert_array_equal(camsim.develop(planes, s), img)


@pytest.mark.parametrize("call,key", [
    (lambda s: camsim.expose(np.full((4, 4), -1.0), s, seed=1), "electrons"),
    (lambda s: camsim.expose(np.full((4, 4), np.nan), s, seed=1), "electrons"),
    (lambda s: camsim.expose(np.zeros((4, 4, 3)), s, seed=1), "electrons"),
    (lambda s: camsim.expose(np.zeros((4, 4)), s, seed=1, frames=0), "frames"),
    (lambda s: camsim.expose(np.zeros((4, 4)), s, seed=1, noise="loud"), "noise"),
    (lambda s: camsim.expose(np.zeros((4, 4)), s, seed=1, iso=-100), "iso"),
    (lambda s: camsim.develop(np.zeros((4, 4), np.uint16), s, demosaic="fast"), "demosaic"),
    (lambda s: camsim.develop(np.full((4, 4), 4095, np.uint16), s), "raw"),
    (lambda s: camsim.develop(np.zeros((4, 4), np.uint16), s, white_balance="region"), "region"),
    (lambda s: camsim.display(np.zeros((4, 4)), ), "image"),
    (lambda s: camsim.display(np.zeros((4, 4, 3)), view="No such view"), "view"),
    # Found by probing: an unknown illuminant named "<input>" and no key; NaN and inf went
    # through display() to NaN output.
    (lambda s: camsim.develop(np.full((4, 4), 100, np.uint16), s, illuminant="Z99"), "illuminant"),
    (lambda s: camsim.display(np.full((2, 2, 3), np.nan, np.float32)), "image"),
    (lambda s: camsim.display(np.full((2, 2, 3), np.inf, np.float32)), "image"),
])
def test_bad_input_raises_input_error_naming_the_argument(sensor, call, key):
    with pytest.raises(camsim.InputError) as e:
        call(sensor)
    assert key in str(e.value)
    assert e.value.key == key


def test_unknown_sensor_preset_is_an_input_error():
    with pytest.raises(camsim.InputError, match="no-such-sensor"):
        camsim.Sensor("no-such-sensor")


def test_expose_file_gives_the_cli_bytes_and_expose_with_exposure_scale(cli_box, camsim_binary,
                                                                          tmp_path):
    """expose_file() writes `camsim expose`'s bytes; its frames are expose() on the file's
    electrons with the same seed, ISO, exposure_scale and the recorded exposure time."""
    raw_exr = next(cli_box.glob("*_raw.exr"))
    cli = tmp_path / "cli"
    subprocess.run([camsim_binary, "expose", str(raw_exr), "--frames", "3", "--seed", "4",
                    "--iso", "400", "--exposure-scale", "0.5", "-o", str(cli)], check=True,
                   capture_output=True)
    r = camsim.expose_file(str(raw_exr), seed=4, frames=3, iso=400, exposure_scale=0.5,
                           output_dir=str(tmp_path / "py"))
    assert r["raw"].shape[0] == 3 and r["raw"].dtype == np.uint16
    assert len(r["files"]) == 6
    for f in r["files"]:
        name = f.rsplit("/", 1)[1]
        assert (cli / name).read_bytes() == (tmp_path / "py" / name).read_bytes(), name
    exr = camsim.read_exr(str(raw_exr))
    electrons = next(v for k, v in exr["channels"].items() if k.startswith("electrons."))
    t = float(exr["metadata"]["camsim:exposure_time_s"])
    assert r["exposure_time_s"] == pytest.approx(0.5 * t, rel=1e-12)
    direct = camsim.expose(electrons, r["sensor"], seed=4, frames=3, exposure_time=t, iso=400,
                           exposure_scale=0.5)
    np.testing.assert_array_equal(r["raw"], direct)
    written = camsim.read_exr(str(tmp_path / "py" / r["files"][-1].rsplit("/", 1)[1]))
    np.testing.assert_array_equal(written["channels"]["raw.DN"], r["raw"][2])


def test_expose_file_bad_input_names_the_key(cli_box, tmp_path):
    raw_exr = str(next(cli_box.glob("*_raw.exr")))
    for kwargs, key in [({"frames": 0}, "frames"), ({"exposure_scale": 0.0}, "exposure_scale"),
                        ({"iso": -1.0}, "iso"), ({"noise": "loud"}, "noise"),
                        ({"sensor": "fullframe-d850"}, "sensor")]:
        with pytest.raises(camsim.InputError) as e:
            camsim.expose_file(raw_exr, output_dir=str(tmp_path / "out"), **kwargs)
        assert key in str(e.value) and "_raw.exr" in str(e.value)
    with pytest.raises(camsim.InputError, match="no such file"):
        camsim.expose_file(str(tmp_path / "missing_raw.exr"))
    assert not (tmp_path / "out").exists()
