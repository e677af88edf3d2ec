"""Safe output: path validation before work, no NaN image, atomic PNG/GIF/MP4 writes with no partial file."""
from __future__ import annotations

import os

import numpy as np
import pytest
from PIL import Image

from pywarp.core.output import (VideoWriter, atomic_path, check_output_dir, check_output_path, remove_temporaries,
                                to_uint8, write_png)


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
    with pytest.raises(ValueError, match=r"fps must be in \[0.01, 240\]"):
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


def test_check_output_path_more_errors(tmp_path):
    (tmp_path / "f").write_text("x")
    with pytest.raises(ValueError, match="--out: '.*f' is not a folder"):
        check_output_path(tmp_path / "f" / "a.png", (".png",))
    with pytest.raises(ValueError, match="--video: folder"):
        check_output_path(tmp_path / "nope" / "a.mp4", (".mp4",), option="--video")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f"]  # the writability probe leaves nothing


@pytest.mark.skipif(not hasattr(os, "geteuid") or os.geteuid() == 0, reason="the superuser may write anywhere")
def test_check_output_path_refuses_a_read_only_folder(tmp_path):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        with pytest.raises(ValueError, match="--out: cannot write in folder"):
            check_output_path(ro / "a.png", (".png",))
    finally:
        ro.chmod(0o700)


def test_check_output_dir(tmp_path):
    assert check_output_dir(tmp_path / "new" / "deeper") == tmp_path / "new" / "deeper"
    assert not (tmp_path / "new").exists()  # checked, not created
    (tmp_path / "f").write_text("x")
    with pytest.raises(ValueError, match="--out: '.*f' is not a folder"):
        check_output_dir(tmp_path / "f")
    with pytest.raises(ValueError, match="--out: cannot create folder"):
        check_output_dir(tmp_path / "f" / "sub")


def test_write_errors_name_the_option_and_path_never_the_temporary_file(tmp_path, monkeypatch):
    from PIL import Image

    def full_disk(self, fp, *a, **k):
        raise OSError(28, "No space left on device", str(fp))

    out = check_output_path(tmp_path / "c.png", (".png",))
    monkeypatch.setattr(Image.Image, "save", full_disk)
    with pytest.raises(OSError) as exc:
        write_png(out, np.zeros((4, 4, 3), np.float32))
    assert str(exc.value) == f"--out: cannot write {str(out)!r}: disk full (No space left on device)"
    assert ".part" not in str(exc.value) and exc.value.errno == 28
    gif = out.with_suffix(".gif")
    with pytest.raises(OSError, match=r"cannot write .*c.gif': disk full \(No space left on device\)") as exc:
        with VideoWriter(gif) as vw:  # not checked by check_output_path: no option to name
            vw.add(np.zeros((4, 4, 3), np.float32))
    assert ".part" not in str(exc.value)
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("exc_type", [KeyboardInterrupt, RuntimeError])
def test_mp4_writer_kills_ffmpeg_and_removes_the_temporary_file(tmp_path, exc_type):
    path = tmp_path / "v.mp4"
    with pytest.raises(exc_type):
        with VideoWriter(path, fps=10) as vw:
            vw.add(np.zeros((16, 24, 3), np.float32))
            proc = vw._enc.proc
            assert proc.poll() is None and any(p.name.endswith(".part") for p in tmp_path.iterdir())
            raise exc_type()
    assert proc.poll() is not None  # ffmpeg was stopped
    assert list(tmp_path.iterdir()) == []


def test_video_writer_refuses_a_changing_frame_size(tmp_path):
    with pytest.raises(ValueError, match="every frame must be 24x16, got 26x16"):
        with VideoWriter(tmp_path / "v.mp4") as vw:
            vw.add(np.zeros((16, 24, 3), np.float32))
            vw.add(np.zeros((16, 26, 3), np.float32))
    assert list(tmp_path.iterdir()) == []


def test_atomic_path_and_remove_temporaries(tmp_path):
    with atomic_path(tmp_path / "a.txt") as tmp:
        assert tmp.name.startswith(".a.") and tmp.name.endswith(".txt.part")
        tmp.write_text("done")
    assert (tmp_path / "a.txt").read_text() == "done"
    with pytest.raises(KeyboardInterrupt):
        with atomic_path(tmp_path / "b.txt") as tmp:
            tmp.write_text("half")
            raise KeyboardInterrupt
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]
    vw = VideoWriter(tmp_path / "c.gif").__enter__()  # a writer left open, e.g. by an interrupt in another frame
    assert len(list(tmp_path.glob(".c.*.gif.part"))) == 1
    assert [p.name for p in remove_temporaries()] == [vw._tmp.name]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]
