"""Makes examples/images/kanji.png: a held-out KanjiVG character drawn like ink on paper.

  python examples/make_example.py

The character comes from the test split (never trained on); its strokes are
drawn 9 px wide on a 320x320 page with a lighting gradient and a little noise.
"""

import cv2
import numpy as np

from jdraw.data import kanji

CODE = "04eac"  # 京  # from the test split (jdraw/data/split.json)


def main(out="examples/images/kanji.png"):
    ks = kanji.load()
    i = int(np.flatnonzero(ks.names == CODE)[0])
    assert i in set(kanji.split_indices(ks, "test").tolist())
    page = np.zeros((320, 320), np.float32)
    for c in ks.strokes(i):
        pts = kanji.sample_cubics(c) * 3.2
        cv2.polylines(
            page, [np.round(pts * 4).astype(np.int32)], False, 1.0, 9, cv2.LINE_AA, shift=2
        )
    yy, xx = np.mgrid[0:320, 0:320] / 320.0
    paper = 0.95 - 0.25 * xx * yy
    rng = np.random.default_rng(0)
    img = paper * (1 - 0.85 * page) + rng.normal(0, 0.02, page.shape)
    cv2.imwrite(out, np.clip(img * 255, 0, 255).astype(np.uint8))
    print("wrote", out)


if __name__ == "__main__":
    main()
