"""The library's callbacks for one call: log messages to the `neuv` logger,
progress to the caller's function.

ctypes releases the GIL for the whole foreign call and takes it back for
each callback, so other Python threads run meanwhile. An exception raised
inside a callback (the caller's, or KeyboardInterrupt arriving while Python
code runs there) must not unwind through C: it is kept, the call is
cancelled through the progress callback's return value, and the exception
is raised again once the call has returned (Session.finish)."""
import logging

from . import _capi, _errors

logger = logging.getLogger("neuv")
_LEVELS = {0: logging.DEBUG, 1: logging.INFO, 2: logging.WARNING}


def _text(b):
    return None if b is None else b.decode("utf-8", "replace")


class Session:
    """Callbacks for one call. progress(stage, fraction, detail) returns
    False (or 0) to cancel; None or True go on."""

    def __init__(self, progress=None):
        if progress is not None and not callable(progress):
            raise TypeError(f"progress must be a function (stage, fraction, detail) -> bool or None, got {progress!r}")
        self.progress = progress
        self.exception = None
        # The C function pointers live as long as this object; the caller
        # keeps it until the call has returned.
        self._log = _capi.LOG_FN(self._on_log)
        self._progress = _capi.PROGRESS_FN(self._on_progress)
        self.struct = _capi.Callbacks(self._log, self._progress, None)

    def _on_log(self, user, level, message):
        try:
            logger.log(_LEVELS.get(level, logging.INFO), "%s", _text(message))
        except BaseException as e:  # noqa: B036 -- nothing may cross into C
            if self.exception is None:
                self.exception = e

    def _on_progress(self, user, stage, fraction, detail):
        if self.exception is not None:
            return 0
        if self.progress is None:
            return 1
        try:
            go_on = self.progress(_text(stage), fraction, _text(detail))
        except BaseException as e:  # noqa: B036 -- nothing may cross into C
            self.exception = e
            return 0
        return 0 if go_on is not None and not go_on else 1

    def finish(self, status):
        """After the call: the callback's exception if one was raised, else
        the call's Error if it failed. Reads neuv_last_error, so it must
        follow the call directly."""
        if self.exception is not None:
            e, self.exception = self.exception, None
            raise e
        _errors.check(status)
