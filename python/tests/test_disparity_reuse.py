"""attend.disparity keeps one estimator a thread between calls with the same keywords (issue 47:
a fresh one a call took its buffers from the kernel as new pages, a third of the call). The
maps must not depend on what was computed before: another size, other keywords, another
thread."""

import threading

import numpy as np

import attend


def same(a, b):
    return np.array_equal(np.nan_to_num(a, nan=-7.0), np.nan_to_num(b, nan=-7.0))


def test_a_map_does_not_depend_on_the_calls_before_it(lab_frames):
    left, right = lab_frames[5]
    small_left, small_right = left[40:200, 30:290].copy(), right[40:200, 30:290].copy()
    first = attend.disparity(left, right, max_disparity=32)
    first_small = attend.disparity(small_left, small_right, max_disparity=32)
    other = attend.disparity(left, right, max_disparity=16)
    assert not same(first, other) or np.isnan(first).all()
    # The same keywords again, after another size and other keywords.
    assert same(attend.disparity(left, right, max_disparity=32), first)
    assert same(attend.disparity(small_left, small_right, max_disparity=32), first_small)
    assert same(attend.disparity(left, right, max_disparity=16), other)
    # Another frame, then the first again: no state carried from frame to frame.
    attend.disparity(*lab_frames[9], max_disparity=32)
    assert same(attend.disparity(left, right, max_disparity=32), first)


def test_threads_each_get_the_same_map(lab_frames):
    left, right = lab_frames[5]
    expected = attend.disparity(left, right, max_disparity=32)
    results = [None] * 4

    def work(k):
        for _ in range(3):
            results[k] = attend.disparity(left, right, max_disparity=32)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert all(same(result, expected) for result in results)
