"""GIF and MP4 export of the animations (app.animation_export, python -m app.animate):
files with the requested number of frames and size, read back; clear errors, exit 2."""
import imageio_ffmpeg
import numpy as np
import pytest
from PIL import Image

from app import animate
from app.animation_export import animation_bytes, export_animation
from model import REGIMES

SIZE = (320, 240)


def _frames_gif(path):
    with Image.open(path) as im:
        first = np.asarray(im.convert("RGB"))
        im.seek(im.n_frames - 1)
        last = np.asarray(im.convert("RGB"))
        return im.n_frames, im.size, first, last


def _frames_mp4(path):
    reader = imageio_ffmpeg.read_frames(str(path))
    meta = next(reader)
    frames = [np.frombuffer(f, np.uint8) for f in reader]
    return len(frames), tuple(meta["size"]), frames[0], frames[-1]


@pytest.mark.parametrize("what", ["support", "array"])
@pytest.mark.parametrize("fmt", ["gif", "mp4"])
def test_file_has_the_requested_frames_and_size(tmp_path, what, fmt):
    out = tmp_path / f"anim.{fmt}"
    result = export_animation(what, fmt, out, REGIMES["pendulum"], frames=7, size=SIZE, fps=10)
    assert result.success, result.message
    n, size, first, last = (_frames_gif if fmt == "gif" else _frames_mp4)(out)
    assert (n, size) == (7, SIZE)
    assert not np.array_equal(first, last)  # it moves


def test_bytes_for_a_download_button():
    data, mime, result = animation_bytes("support", "gif", REGIMES["slider"], frames=3, size=SIZE)
    assert result.success and mime == "image/gif" and data[:6] == b"GIF89a"
    data, mime, _ = animation_bytes("array", "mp4", REGIMES["stiff"], frames=3, size=SIZE)
    assert mime == "video/mp4" and data[4:8] == b"ftyp"


@pytest.mark.parametrize("kwargs, word", [
    (dict(what="forces"), "what"), (dict(fmt="avi"), "format"), (dict(frames=1), "frames"),
    (dict(frames=2.0), "frames"), (dict(size=(100, 100)), "size"),
    (dict(fmt="mp4", size=(321, 240)), "even"), (dict(fps=0), "fps"),
    (dict(orientation="random"), "orientation")])
def test_bad_requests_are_named(tmp_path, kwargs, word):
    args = dict(what="support", fmt="gif", frames=3, size=SIZE)
    args.update(kwargs)
    with pytest.raises(ValueError, match=word):
        export_animation(args.pop("what"), args.pop("fmt"), tmp_path / "x", REGIMES["stiff"], **args)


def test_missing_folder_is_named(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        export_animation("support", "gif", tmp_path / "no" / "x.gif", REGIMES["stiff"], frames=2)


def test_cli_writes_the_file(tmp_path, capsys):
    out = tmp_path / "s.mp4"
    code = animate.main(["--what", "support", "--frames", "4", "--size", "320x240",
                         "--out", str(out), "--regime", "slider", "--theta0-deg", "60",
                         "--F-N", "2"])
    assert code == 0
    n, size, _, _ = _frames_mp4(out)
    assert (n, size) == (4, SIZE)
    assert "4 frames, 320x240 px" in capsys.readouterr().out


@pytest.mark.parametrize("argv, word", [
    (["--what", "support", "--size", "big"], "WIDTHxHEIGHT"),
    (["--what", "pillar"], "invalid choice"),
    (["--what", "support", "--frames", "0"], "frames"),
    (["--what", "support", "--frames", "ten"], "not a whole number"),
    (["--what", "support", "--k-r", "-1"], "k_r"),
    (["--what", "support", "--theta0-deg", "400"], "theta0"),
    (["--what", "support", "--format", "gif", "--out-ext", "mp4"], "unrecognized"),
    (["--what", "array", "--supports", "0"], "supports")])
def test_cli_bad_input_exits_2(tmp_path, capsys, argv, word):
    if "--out-ext" in argv:
        argv = ["--what", "support", "--format", "gif", "--out", str(tmp_path / "x.mp4")]
        word = "ends in .mp4"
    elif "--out" not in argv:
        argv = [*argv, "--out", str(tmp_path / "x.gif")]
    with pytest.raises(SystemExit) as exit_info:
        animate.main(argv)
    assert exit_info.value.code == 2
    assert word in capsys.readouterr().err
    assert not (tmp_path / "x.gif").exists()


# --------------------------------------------------------------------- what a slide shows

@pytest.mark.parametrize("what", ["support", "array"])
@pytest.mark.parametrize("size", [(640, 360), (960, 540)])
def test_every_text_of_the_frame_is_inside_it(what, size):
    """Title, panel titles, axis labels, legends and tick labels lie within the picture
    (at 640 x 360 the title, the energy panel's title and the legend were cut off)."""
    from app.animation_export import frame_figure
    from app.frame_fit import outside

    _, fig = frame_figure(what, REGIMES["slider"], 4, size)
    assert outside(fig) == []
    title = fig.get_suptitle()
    assert "k_r = 0.01" in title and "F_N = 1" in title
    legends = fig.legends + [ax.get_legend() for ax in fig.axes if ax.get_legend()]
    assert legends and all(t.get_fontsize() >= 6 for lg in legends for t in lg.get_texts())
    assert all(ax.title.get_fontsize() >= 6 for ax in fig.axes)


def test_the_frame_draws_each_quantity_in_the_page_s_colour():
    """v_R, the friction force and the slab as on the page's top view
    (``app.figures.scene``); the energy terms as the page's bars (``app.figures.histories``)."""
    from matplotlib.colors import to_hex

    from app.animation_export import frame_figure
    from app.figures.histories import ENERGY_COLORS, ENERGY_TERMS
    from app.figures.scene import FORCE_COLOR, SLAB_COLOR, VREL_COLOR

    drawer, fig = frame_figure("support", REGIMES["pendulum"], 4, (640, 360))
    assert to_hex(drawer.relvel.arrow_patch.get_edgecolor()) == VREL_COLOR.lower()
    assert to_hex(drawer.friction.arrow_patch.get_edgecolor()) == FORCE_COLOR.lower()
    keys = {t.get_text(): to_hex(h.get_color())
            for lg in fig.legends for t, h in zip(lg.get_texts(), lg.legend_handles)}
    assert keys["relative velocity v_R"] == VREL_COLOR.lower()
    assert keys["friction on the mass"] == FORCE_COLOR.lower()
    assert keys["slab velocity V₀ (slab shaded)"] == SLAB_COLOR.lower()
    bars = [to_hex(bar.get_facecolor()) for bar in drawer.parts]
    assert bars == [c.lower() for c in ENERGY_COLORS] and len(bars) == len(ENERGY_TERMS)
