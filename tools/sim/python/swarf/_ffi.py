# SPDX-License-Identifier: MPL-2.0
"""libswarf through ctypes: the library, its structs and its functions.

The layouts and signatures come from _abi.py, which a C program compiled
against libswarf's headers wrote (tools/sim/python/abi.c): fields the module
does not use are padding, so every struct has the library's size and the
library's *_init functions fill in whatever the module does not know.
"""
import ctypes
import os
from ctypes import (CFUNCTYPE, POINTER, c_char, c_char_p, c_double, c_int, c_long,  # noqa: F401
                    c_longlong,
                    c_size_t, c_ulonglong, c_void_p)

from . import _abi

_here = os.path.dirname(os.path.abspath(__file__))


def _library_path():
    path = os.environ.get("SWARF_LIBRARY") or _abi.LIBRARY
    if not os.path.isabs(path):
        path = os.path.normpath(os.path.join(_here, path))
    return path


def _load():
    """The library beside the module (as installed together), else by its
    SONAME through the dynamic loader's search path."""
    path = _library_path()
    if not os.path.exists(path) and not os.environ.get("SWARF_LIBRARY"):
        path = os.path.basename(path)
    try:
        return ctypes.CDLL(path)
    except OSError as e:
        raise ImportError("swarf: cannot load libswarf (%s): %s; set SWARF_LIBRARY to its path"
                          % (path, e)) from None


lib = _load()

# The namespace the type names of _abi.py are written in.
types = {name: getattr(ctypes, name) for name in dir(ctypes) if name.startswith("c_")}
types["POINTER"] = POINTER


def _type(text):
    return eval(text, {"__builtins__": {}}, types)  # text from _abi.py, written by abi.c


def _struct(name, size, fields):
    """A ctypes Structure with the C layout: known fields at their offsets,
    padding between and after them."""
    layout, at = [], 0
    for fname, off, fsize, ftext in fields:
        if off > at:
            layout.append(("_pad%d" % at, c_char * (off - at)))
        elif off < at:
            raise ImportError("swarf: %s.%s overlaps the field before it" % (name, fname))
        t = _type(ftext)
        if ctypes.sizeof(t) != fsize:
            raise ImportError("swarf: %s.%s is %d bytes in C but %d as %s" % (
                name, fname, fsize, ctypes.sizeof(t), ftext))
        layout.append((fname, t))
        at = off + fsize
    if size > at:
        layout.append(("_pad%d" % at, c_char * (size - at)))
    cls = type(name, (ctypes.Structure,), {"_fields_": layout})
    for fname, off, _, _ in fields:
        if getattr(cls, fname).offset != off:
            raise ImportError("swarf: %s.%s is at offset %d in C but %d in ctypes" % (
                name, fname, off, getattr(cls, fname).offset))
    if ctypes.sizeof(cls) != size:
        raise ImportError("swarf: %s is %d bytes in C but %d in ctypes" % (
            name, size, ctypes.sizeof(cls)))
    return cls


def _callback(ret, args):
    return CFUNCTYPE(_type(ret) if ret else None, *[_type(a) for a in args])


for _name, _size, _fields in _abi.STRUCTS:
    if _name == "swarf_sim_callbacks":  # its function pointers need the structs before it
        for _cb, (_ret, _args) in _abi.CALLBACKS.items():
            types[_cb] = _callback(_ret, _args)
    types[_name] = _struct(_name, _size, _fields)

for _name, (_ret, _args) in _abi.FUNCTIONS.items():
    _f = getattr(lib, _name)
    _f.restype = _type(_ret) if _ret else None
    _f.argtypes = [_type(a) for a in _args]

const = dict(_abi.CONSTANTS)
S = types  # struct classes by C name: S["swarf_sim_config"]
