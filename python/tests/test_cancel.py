"""Progress through a Python function: returning False cancels
(neuv.Cancelled); an exception raised inside it cancels the call and comes
out of it unchanged; the atlas stays usable."""
import logging

import pytest

import neuv
from meshes import torus

V, F = torus(12, 6)
QUICK = dict(method="lscm", iters=30, use_cache=False, resolution=256, threads=1)


class Boom(Exception):
    pass


def test_progress_is_called():
    seen = []

    def progress(stage, fraction, detail):
        assert isinstance(stage, str) and 0 <= fraction <= 1 and (detail is None or isinstance(detail, str))
        seen.append(stage)

    neuv.unwrap(V, F, progress=progress, **QUICK)
    assert seen and len(set(seen)) >= 1


def test_cancel_by_returning_false():
    calls = []

    def progress(stage, fraction, detail):
        calls.append(stage)
        return len(calls) < 3  # go on twice, then cancel

    with neuv.Atlas() as atlas:
        atlas.add_mesh(V, F)
        with pytest.raises(neuv.Cancelled) as e:
            atlas.generate(progress=progress, **QUICK)
        assert e.value.status == 5 and isinstance(e.value, neuv.Error) and str(e.value)
        assert len(calls) == 3 and atlas.stage == 0
        # The atlas is usable afterwards; a cancelled stage leaves the one before it.
        atlas.compute_charts(iters=30, use_cache=False, threads=1)
        with pytest.raises(neuv.Cancelled):
            atlas.compute_charts(iters=30, use_cache=False, threads=1, progress=lambda *a: False)
        assert atlas.stage == 0
        atlas.generate(**QUICK)
        assert atlas.stage == 3


def test_exception_in_callback_is_raised_after_the_call():
    def progress(stage, fraction, detail):
        raise Boom(f"from the callback at {stage}")

    with neuv.Atlas(progress=progress) as atlas:
        atlas.add_mesh(V, F)
        with pytest.raises(Boom, match="from the callback"):
            atlas.generate(**QUICK)
        assert atlas.stage == 0
        atlas.generate(progress=lambda *a: None, **QUICK)  # a per-call function overrides the atlas's
        assert atlas.stage == 3


def test_keyboard_interrupt_cancels():
    def progress(stage, fraction, detail):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        neuv.unwrap(V, F, progress=progress, **QUICK)


def test_cancel_training():
    with pytest.raises(neuv.Cancelled):
        neuv.train_category([(V, F)], iters=5, patch_iters=5, use_cache=False, threads=1,
                            progress=lambda *a: False)
    with pytest.raises(Boom):
        neuv.train_category([(V, F)], iters=5, patch_iters=5, use_cache=False, threads=1,
                            progress=lambda *a: (_ for _ in ()).throw(Boom()))


def test_reentrant_call_is_refused():
    with neuv.Atlas() as atlas:
        atlas.add_mesh(V, F)

        def progress(stage, fraction, detail):
            atlas.compute_charts()

        with pytest.raises(RuntimeError, match="from inside one of its own callbacks"):
            atlas.generate(progress=progress, **QUICK)


def test_log_messages_reach_logging(caplog):
    with caplog.at_level(logging.DEBUG, logger="neuv"):
        neuv.unwrap(V, F, **QUICK)
    assert caplog.records and all(r.name == "neuv" for r in caplog.records)
