"""Many images in one run (``jdraw draw A B ... --out-dir``, ``plan_image([...])``) and the
pixel limit read from the file header."""

import json
import struct
import zlib

import cv2
import numpy as np
import pytest

from jdraw import cli
from jdraw.images import load
from jdraw.tiling import plan_image as tiling
from tests.doubles import trace_planner
from tests.synthetic import photo_like, text_centrelines


def _word(text: str, seed: int = 0) -> np.ndarray:
    lines, shape = text_centrelines(text, 3.0)
    return photo_like(lines, shape, width=6, gradient=0.3, noise=0.03, seed=seed)


def _png_header(width: int, height: int) -> bytes:
    """A PNG whose header says ``width x height`` but that holds a few bytes of pixel data."""

    def chunk(kind: bytes, data: bytes) -> bytes:
        crc = zlib.crc32(kind + data) & 0xFFFFFFFF
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", crc)

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    idat = zlib.compress(b"\0" * 100)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", idat) + chunk(b"IEND", b"")


def _same(a, b) -> bool:
    return len(a.strokes) == len(b.strokes) and all(
        np.array_equal(p, q) for p, q in zip(a.strokes, b.strokes)
    )


def test_a_list_plans_like_each_image_alone():
    """Tiles of several images share planner batches; every plan is the one it gets alone."""
    images = [_word("hi"), _word("x"), np.zeros((40, 40), np.uint8), _word("ok", seed=1)]
    images[2][10:30, 19:22] = 255  # light line on black: the other polarity
    alone = [
        tiling.plan_image(im, planner=trace_planner, batch_size=2, progress=False) for im in images
    ]
    together = tiling.plan_image(images, planner=trace_planner, batch_size=2, progress=False)
    assert isinstance(together, list) and len(together) == len(images)
    assert sum(len(p.tiles) for p in alone) > 2  # some batches mix images
    for a, b in zip(alone, together):
        assert _same(a, b) and a.shape == b.shape and len(a.tiles) == len(b.tiles)


def test_a_stream_reports_a_bad_image_and_goes_on(tmp_path):
    blank = np.full((50, 60), 250, np.uint8)
    missing = tmp_path / "nope.png"
    out = list(
        tiling.plan_images(
            [_word("a"), blank, str(missing), _word("b")], planner=trace_planner, progress=False
        )
    )
    assert isinstance(out[0], tiling.ImagePlan) and isinstance(out[3], tiling.ImagePlan)
    assert isinstance(out[1], load.BlankImageError)
    assert isinstance(out[2], load.ImageError) and "no such file" in str(out[2])
    with pytest.raises(load.BlankImageError):
        tiling.plan_image([_word("a"), blank], planner=trace_planner, progress=False)


def test_real_planner_same_plans_alone_and_in_a_set():
    """With :func:`jdraw.plan`: a one-tile kanji and a tiled word, alone and together."""
    kanji = cv2.imread("examples/images/kanji.png", cv2.IMREAD_GRAYSCALE)
    word = _word("minimum")
    alone = [tiling.plan_image(im, progress=False) for im in (kanji, word)]
    assert len(alone[0].tiles) == 1 and len(alone[1].tiles) > 1
    together = tiling.plan_image([kanji, word], progress=False)
    for a, b in zip(alone, together):
        assert _same(a, b)


def test_out_dir_writes_each_format_per_image(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    src = tmp_path / "scans"
    src.mkdir()
    for name, text in (("one", "hi"), ("two", "ok")):
        cv2.imwrite(str(src / f"{name}.png"), _word(text))
    (src / "notes.txt").write_text("not an image, not picked up from a folder")
    (src / "broken.png").write_bytes(b"\x89PNG\r\n\x1a\n" + b"\0" * 40)
    extra = tmp_path / "three.jpg"
    cv2.imwrite(str(extra), _word("x"))
    out = tmp_path / "plans"
    argv = ["draw", str(src), str(extra), "--out-dir", str(out), "--svg", "--json", "--gcode"]
    assert cli.main([*argv, "--no-progress"]) == 2  # broken.png failed
    cap = capsys.readouterr()
    lines = cap.out.strip().splitlines()
    assert len(lines) == 3 and all("strokes" in x for x in lines)
    assert [x.split(":")[0] for x in lines] == [
        str(src / "one.png"),
        str(src / "two.png"),
        str(extra),
    ]
    errors = [x for x in cap.err.splitlines() if x.startswith("jdraw: error:")]
    assert len(errors) == 1 and "broken.png" in errors[0]
    for stem in ("one", "two", "three"):
        for ext in ("svg", "json", "gcode"):
            assert (out / f"{stem}.{ext}").stat().st_size > 0
        alone = tiling.plan_image(
            str(extra if stem == "three" else src / f"{stem}.png"),
            planner=trace_planner,
            progress=False,
        )
        strokes = json.loads((out / f"{stem}.json").read_text())["strokes"]
        assert len(strokes) == len(alone.strokes)
    assert not (out / "broken.svg").exists()
    # All good: status 0.
    (src / "broken.png").unlink()
    assert cli.main([*argv, "--no-progress"]) == 0


def test_set_options_are_checked(tmp_path, capsys):
    a, b = tmp_path / "a.png", tmp_path / "b.png"
    for p in (a, b):
        cv2.imwrite(str(p), _word("a"))
    cases = [
        (["draw", str(a), str(b), "--svg", str(tmp_path / "o.svg")], "--out-dir"),
        (["draw", str(a), "--out-dir", str(tmp_path), "--svg", str(tmp_path / "o.svg")], "format"),
        (["draw", str(a), "--svg"], "needs a file name"),
        (["draw", str(a), "--out-dir", str(tmp_path), "--trajectory", "t.json"], "one image"),
        (["draw", str(a), str(tmp_path / "a.jpg"), "--out-dir", str(tmp_path), "--svg"], "rename"),
        (["draw", str(tmp_path / "empty")], "no such file"),
    ]
    (tmp_path / "empty").mkdir()
    cases[-1] = (["draw", str(tmp_path / "empty")], "no image files")
    for argv, words in cases:
        assert cli.main(argv) == 2, argv
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and words in err[0], (argv, err)


def test_pixel_limit_from_the_header(tmp_path, capsys, monkeypatch):
    big = tmp_path / "big.png"
    big.write_bytes(_png_header(20000, 20000))  # no pixel data: must not be decoded
    assert load.image_size(big) == (20000, 20000)

    def no_decode(*a, **k):
        raise AssertionError("decoded an image over the limit")

    monkeypatch.setattr(load.cv2, "imread", no_decode)
    assert cli.main(["draw", str(big), "--svg", str(tmp_path / "o.svg")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "20000x20000" in err[0] and "--max-mpx 400" in err[0]
    with pytest.raises(load.TooLargeError, match="max_pixels="):
        tiling.plan_image(str(big), planner=trace_planner)
    monkeypatch.undo()
    # Under a raised limit the same check passes (and decoding then fails: no pixel data).
    assert cli.main(["draw", str(big), "--max-mpx", "400", "--svg", str(tmp_path / "o.svg")]) == 2
    assert "over the limit" not in capsys.readouterr().err
    # Arrays are held to the limit too.
    with pytest.raises(load.TooLargeError, match="max_pixels="):
        tiling.plan_image(np.zeros((300, 200), np.uint8), planner=trace_planner, max_pixels=50_000)


def test_pipeline_runs_calls_side_by_side_and_keeps_each_tile_in_place():
    """Two planner calls in flight at once (a slow planner), the same tiles' strokes as in turn."""
    import threading
    import time

    from jdraw.tiling import tiles

    busy, most, lock = [0], [0], threading.Lock()

    def slow(batch, **kw):
        with lock:
            busy[0] += 1
            most[0] = max(most[0], busy[0])
        time.sleep(0.05 * (1 + int(batch.sum()) % 3))  # calls finish out of order
        try:
            return trace_planner(batch, **kw)
        finally:
            with lock:
                busy[0] -= 1

    def jobs():
        return [
            tiles._lay_out(_word(w, seed=i), "auto", 4.0, None)
            for i, w in enumerate(["minimum", "hello"])
        ]

    cfg = tiles._settings(slow, None, None, None, "auto", 4.0, 2, 0.5, None, None)
    serial, threaded = jobs(), jobs()
    for job in serial:
        for i in range(len(job.tiles)):
            tiles._plan_tiles([(job, i)], cfg)
    with tiles.Pipeline(cfg, workers=2) as pipe:
        for job in threaded:
            for i in range(len(job.tiles)):
                pipe.submit([(job, i)])
    assert most[0] == 2 and all(job.done for job in threaded)
    assert len(threaded[0].tiles) > 2  # a tiled word: its tiles in several calls
    for a, b in zip(serial, threaded):
        assert len(a.planned) == len(b.planned)
        for pa, pb in zip(a.planned, b.planned):
            assert len(pa) == len(pb) and all(np.array_equal(p, q) for p, q in zip(pa, pb))


def test_a_planner_error_reaches_the_caller():
    def broken(batch, **kw):
        raise RuntimeError("planner broke")

    with pytest.raises(RuntimeError, match="planner broke"):
        list(tiling.plan_images([_word("hi"), _word("ok")], planner=broken, progress=False))


def test_a_reader_that_goes_away_stops_the_lines_not_the_plans(tmp_path, monkeypatch):
    """``jdraw draw DIR --out-dir OUT ... | head -0``: every plan is still written, no error."""
    import os
    import sys

    monkeypatch.setattr(tiling, "default_planner", trace_planner)
    src = tmp_path / "scans"
    src.mkdir()
    for name, text in (("one", "hi"), ("two", "ok")):
        cv2.imwrite(str(src / f"{name}.png"), _word(text))
    r, w = os.pipe()
    os.close(r)  # the reader has gone: a write raises BrokenPipeError
    gone = os.fdopen(w, "w")
    monkeypatch.setattr(sys, "stdout", gone)
    out = tmp_path / "plans"
    try:
        assert cli.main(["draw", str(src), "--out-dir", str(out), "--svg", "--no-progress"]) == 0
    finally:
        gone.close()
    assert sorted(p.name for p in out.iterdir()) == ["one.svg", "two.svg"]
