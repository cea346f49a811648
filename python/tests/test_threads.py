"""One Pipeline or Tracker used by two threads at once (issue 46, case 1: it killed the
interpreter): the second call is refused with attend.InUseError while the first runs, the first
finishes as if alone, and pipelines of their own still run side by side. A Python feature that
waits on an event holds the first call inside process(), so that each test is deterministic."""

import threading

import numpy as np
import pytest

import attend

FRAME = np.random.default_rng(46).integers(0, 256, (120, 160, 3), np.uint8)
TIMEOUT = 30  # seconds; a wait that lasts this long is a hang, and fails the test


class Gate:
    """A feature whose compute() says it has started (`inside`) and waits for `go`."""

    inside = None
    go = None

    def compute(self, context):
        type(self).inside.set()
        assert type(self).go.wait(TIMEOUT), "the test never let compute() finish"
        return np.zeros(context.left.shape[:2], np.float32)


def gated_pipeline():
    Gate.inside, Gate.go = threading.Event(), threading.Event()
    attend.register_feature("gate", Gate)
    return attend.Pipeline(config={"features": [{"name": "gate"},
                                                {"name": "colour_contrast"}]},
                           set=["threads=1"])


def during_process(pipeline, call):
    """Runs call(pipeline) from this thread while another thread is inside
    pipeline.process(); returns (what call raised or returned, the other thread's result)."""
    outcome = {}

    def first():
        try:
            outcome["result"] = pipeline.process(FRAME)
        except Exception as error:  # noqa: BLE001 (reported by the test)
            outcome["result"] = error

    thread = threading.Thread(target=first)
    thread.start()
    try:
        assert Gate.inside.wait(TIMEOUT), "process() never reached the feature"
        try:
            second = call(pipeline)
        except Exception as error:  # noqa: BLE001
            second = error
    finally:
        Gate.go.set()
        thread.join(TIMEOUT)
    assert not thread.is_alive()
    return second, outcome["result"]


@pytest.mark.parametrize("name, call", [
    ("process()", lambda p: p.process(FRAME)),
    ("reset()", lambda p: p.reset()),
    ("info", lambda p: p.info),
    ("buffers()", lambda p: p.buffers()),
])
def test_a_second_thread_on_one_pipeline_is_refused(name, call):
    pipeline = gated_pipeline()
    second, first = during_process(pipeline, call)
    assert isinstance(second, attend.InUseError), second
    message = str(second)
    assert "attend.Pipeline is in use by another thread (process() since" in message
    assert f"{name} cannot run beside it" in message
    assert "use one Pipeline a thread" in message
    assert second.status == 2 and isinstance(second, attend.Error)
    # The first call finished as if alone, and the pipeline is usable again.
    assert isinstance(first, attend.FrameResult), first
    assert first.frame == 0 and first.saliency.shape == (240, 320)
    assert pipeline.process(FRAME).frame == 1
    pipeline.reset()
    assert pipeline.info["started"] is False


def test_a_feature_calling_its_own_pipeline_is_refused():
    pipeline = None

    class Reentrant:
        def compute(self, context):
            pipeline.process(FRAME)

    attend.register_feature("reentrant", Reentrant)
    pipeline = attend.Pipeline(config={"features": [{"name": "reentrant"}]}, set=["threads=1"])
    with pytest.raises(attend.PluginError) as error:
        pipeline.process(FRAME)
    message = str(error.value)
    assert "feature 'reentrant' (Python): compute() raised" in message
    assert "InUseError: this attend.Pipeline is in use by this same thread" in message


def test_two_pipelines_in_two_threads_run_at_once():
    # Each pipeline's feature waits at a barrier for the other's: the barrier is passed only
    # when both frames are inside process() together (a lock shared by pipelines would make it
    # time out, a PluginError).
    barrier = threading.Barrier(2, timeout=TIMEOUT)

    class Meet:
        def compute(self, context):
            barrier.wait()
            return np.zeros(context.left.shape[:2], np.float32)

    attend.register_feature("meet", Meet)
    results = [None, None]

    def work(slot):
        pipeline = attend.Pipeline(config={"features": [{"name": "meet"}]}, set=["threads=1"])
        try:
            results[slot] = [pipeline.process(FRAME).frame for _ in range(3)]
        except Exception as error:  # noqa: BLE001
            results[slot] = error

    threads = [threading.Thread(target=work, args=(slot,)) for slot in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(2 * TIMEOUT)
    assert results == [[0, 1, 2], [0, 1, 2]]


def test_a_second_thread_on_one_tracker_is_refused():
    # No callback holds a tracker's call, so one thread tracks over and over (each call most
    # of its time without the GIL) while the other asks for the tracker's ids, until refused.
    frame = np.full((240, 320, 3), 110, np.uint8)
    frame[80:160, 100:180] = (30, 30, 220)
    tracker = attend.Tracker(kind="csrt")
    target = tracker.start(frame, box=(100, 80, 80, 80))
    done, refused, failures = threading.Event(), [], []

    def track():
        try:
            for _ in range(500):
                if refused:
                    break
                tracker.track(frame)
        except Exception as error:  # noqa: BLE001
            failures.append(error)
        finally:
            done.set()

    thread = threading.Thread(target=track)
    thread.start()
    while not done.is_set() and not refused:
        try:
            tracker.ids
        except attend.InUseError as error:
            refused.append(str(error))
    thread.join(TIMEOUT)
    assert failures == []
    assert refused, "ids was never asked while track() ran"
    assert "attend.Tracker is in use by another thread (track() since" in refused[0]
    assert "ids cannot run beside it; use one Tracker a thread" in refused[0]
    assert tracker.ids == [target]
