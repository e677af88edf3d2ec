"""Safe output: path validation before work, no NaN image, atomic PNG/GIF/MP4 writes with no partial file."""
from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from pywarp.core.output import VideoWriter, check_output_path, to_uint8, write_png


def test_check_output_path_errors(tmp_path):
    assert check_output_path(tmp_path / "a.png", (".png",)) == tmp_path / "a.png"
    with pytest.raises(ValueError, match=r"--out must end in \.png"):
        check_output_path(tmp_path / "a.jpg", (".png",))
    with pytest.raises(ValueError, match="does not exist"):
        check_output_path(tmp_path / "nope" / "a.png", (".png",))
    (tmp_path / "d.png").mkdir()
    with pytest.raises(ValueError, match="is a folder"):
        check_output_path(tmp_path / "d.png", (".png",))


def test_to_uint8_rounds_clips_and_refuses_nan():
    img = np.array([[[0.0, 0.5, 1.0], [-1.0, 2.0, 0.2]]], dtype=np.float32)
    np.testing.assert_array_equal(to_uint8(img), [[[0, 128, 255], [0, 255, 51]]])
    img[0, 1, 1] = np.nan
    with pytest.raises(RuntimeError, match=r"1 non-finite pixels \(first at x=1, y=0\)"):
        to_uint8(img)


def test_write_png_roundtrip_and_no_partial_file_on_error(tmp_path):
    img = np.random.default_rng(1).random((8, 6, 3)).astype(np.float32)
    out = write_png(tmp_path / "x.png", img)
    np.testing.assert_array_equal(np.asarray(Image.open(out)), to_uint8(img))
    bad = img.copy()
    bad[2, 2, 0] = np.inf
    with pytest.raises(RuntimeError, match=r"1 non-finite pixels \(first at x=2, y=2\); not written"):
        write_png(tmp_path / "y.png", bad)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["x.png"]


@pytest.mark.parametrize("suffix", [".gif", ".mp4"])
def test_video_writer_atomic(tmp_path, suffix):
    frames = [np.full((16, 24, 3), v, np.float32) for v in (0.0, 0.5, 1.0)]
    path = tmp_path / f"v{suffix}"
    with VideoWriter(path, fps=10) as vw:
        for f in frames:
            vw.add(f)
    assert path.is_file() and path.stat().st_size > 0 and vw.count == 3
    # an error in the middle leaves nothing behind
    path2 = tmp_path / f"w{suffix}"
    with pytest.raises(RuntimeError, match="boom"):
        with VideoWriter(path2, fps=10) as vw:
            vw.add(frames[0])
            raise RuntimeError("boom")
    assert sorted(p.name for p in tmp_path.iterdir()) == [path.name]


def test_video_writer_validation(tmp_path):
    with pytest.raises(ValueError, match="must end in .mp4 or .gif"):
        VideoWriter(tmp_path / "a.avi")
    with pytest.raises(ValueError, match=r"fps must be in \(0, 240\]"):
        VideoWriter(tmp_path / "a.gif", fps=0)
    with pytest.raises(ValueError, match="even width and height"):
        with VideoWriter(tmp_path / "a.mp4") as vw:
            vw.add(np.zeros((5, 6, 3), np.float32))
    assert list(tmp_path.iterdir()) == []


def test_written_files_have_the_usual_permissions(tmp_path):
    import os
    import stat

    out = write_png(tmp_path / "p.png", np.zeros((4, 4, 3), np.float32))
    mask = os.umask(0)
    os.umask(mask)
    assert stat.S_IMODE(out.stat().st_mode) == 0o666 & ~mask
