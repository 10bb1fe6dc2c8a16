"""neuv.Error and neuv.Cancelled, raised from the library's neuv_status."""
import os

from . import _capi


class Error(RuntimeError):
    """A call into libneuv failed. str(e) is neuv_last_error()'s one-line
    message; e.status is the neuv_status code (2: bad input, 3: I/O, ...)."""

    def __init__(self, message, status):
        super().__init__(message)
        self.status = status

    @property
    def status_name(self):
        """"bad input", "I/O error", ... (neuv_status_name)."""
        return _capi.lib.neuv_status_name(self.status).decode()


class Cancelled(Error):
    """The progress callback returned False (NEUV_ERR_CANCELLED)."""


Error.__module__ = Cancelled.__module__ = "neuv"


def check(status, path=None):
    """Raises the Error of a failed call; must run on the thread that made it
    (neuv_last_error is per thread), before any other call into neuv. path:
    the file the call read or wrote, named first in the message as the CLI
    does."""
    if status == _capi.OK:
        return
    message = _capi.lib.neuv_last_error().decode("utf-8", "replace")
    if path is not None:
        message = f"{os.fsdecode(path)}: {message}"
    raise (Cancelled if status == _capi.ERR_CANCELLED else Error)(message, status)


def take_string(ptr):
    """The text of a char * the library returned (released with neuv_free),
    or None for NULL."""
    if not ptr:
        return None
    try:
        return _capi.ctypes.string_at(ptr).decode("utf-8")
    finally:
        _capi.lib.neuv_free(ptr)
