# SPDX-License-Identifier: MPL-2.0
"""swarf's exceptions and the conversion of a C swarf_error into one
(the module's part of the one error convention: swarf_status + swarf_error)."""
import os
from ctypes import byref, create_string_buffer

from ._ffi import const, lib

# ---- Errors -----------------------------------------------------------------

class SwarfError(Exception):
    """A call failed. status is the code (an int), name its name
    ("SWARF_ERR_SYNTAX"), code the exact error identity (0 if none); file,
    line, column and word say where in the input (empty or 0 when unknown);
    message is written for the user. str() is "file:line:col: message"."""

    def __init__(self, status, message, file="", line=0, column=0, word="", code=0, text=None):
        super().__init__(text or message)
        self.status, self.message, self.code = status, message, code
        self.file, self.line, self.column, self.word = file, line, column, word
        self.name = lib.swarf_status_name(status).decode()


class InputError(SwarfError, ValueError):
    """The input is wrong (program, spec, file): the user can fix it."""


class InternalError(SwarfError, RuntimeError):
    """swarf or the system failed (memory, a disk, a bug)."""


class Aborted(SwarfError):
    """The run was stopped on request (a progress callback returned True)."""


def _error_class(status):
    cls = lib.swarf_status_classify(status)
    if cls == const["SWARF_CLASS_INPUT"]:
        return InputError
    if cls == const["SWARF_CLASS_ABORTED"]:
        return Aborted
    return InternalError


def _raise(err):
    """Raises the SwarfError that a swarf_error record describes."""
    buf = create_string_buffer(1024)
    lib.swarf_error_format(byref(err), buf, len(buf))
    status = err.status
    raise _error_class(status)(status, err.message.decode(errors="replace"),
                               err.file.decode(errors="replace"), err.line, err.column,
                               err.word.decode(errors="replace"), err.code,
                               buf.value.decode(errors="replace"))


def _raise_msg(status_name, msg, word=""):
    status = const[status_name]
    text = msg if isinstance(msg, str) else msg.decode(errors="replace")
    raise _error_class(status)(status, text, word=word)


def _path(p):
    return os.fsencode(os.fspath(p))
