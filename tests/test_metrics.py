import numpy as np

from jdraw.evaluation import metrics


def _img(*pixels):
    a = np.zeros((10, 10), bool)
    for x, y in pixels:
        a[y, x] = True
    return a


def test_pixel_accuracy_hand_made():
    t = _img((0, 0), (1, 0), (2, 0), (3, 0))
    p = _img((1, 0), (2, 0), (3, 0), (4, 0), (5, 0))
    # TP = 3, T = 4, P = 5 -> 3 / 6
    assert metrics.pixel_accuracy(t, p) == 0.5
    assert metrics.pixel_accuracy(t, t) == 1.0
    assert metrics.pixel_accuracy(np.zeros((3, 3)), np.zeros((3, 3))) == 1.0
    assert metrics.pixel_accuracy(t, np.zeros_like(t)) == 0.0


def test_stroke_accuracy_hand_made():
    a = _img((0, 0), (1, 0), (2, 0), (3, 0))  # horizontal
    b = _img((5, 0), (5, 1), (5, 2), (5, 3))  # vertical
    target = np.stack([a, b])
    assert metrics.stroke_accuracy(target, target) == 1.0
    # Drawing the horizontal stroke in two halves: each half has IoU 2/4 with it.
    halves = np.stack([_img((0, 0), (1, 0)), _img((2, 0), (3, 0)), b])
    assert abs(metrics.stroke_accuracy(target, halves) - (0.5 + 0.5 + 1.0) / 3) < 1e-9
    # One stroke covering both: IoU 4/8 with each target stroke.
    merged = np.stack([a | b])
    assert metrics.stroke_accuracy(target, merged) == 0.5


def test_order_and_direction():
    a = _img((0, 0), (1, 0), (2, 0))
    b = _img((5, 0), (5, 1), (5, 2))
    tp = [np.array([[0, 0], [2, 0]]), np.array([[5, 0], [5, 2]])]
    same = metrics.order_and_direction(np.stack([a, b]), tp, np.stack([a, b]), tp)
    assert same == (1.0, 1.0, 1.0)
    rev = [tp[1][::-1], tp[0][::-1]]
    order, direction, matched = metrics.order_and_direction(
        np.stack([a, b]), tp, np.stack([b, a]), rev
    )
    assert (order, direction, matched) == (0.0, 0.0, 1.0)
