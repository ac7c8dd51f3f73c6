# SPDX-License-Identifier: MPL-2.0
"""swarf: CNC milling simulation from Python, on libswarf.

Plays a G-code program (RS274/NGC, LinuxCNC dialect) through the machine,
removes the exact volume swept by the cutter from a voxel stock (an OpenVDB
level set) and gives back the remaining material, with the same options as
the `swarf simulate` command:

    import swarf
    r = swarf.simulate("part.ngc", stock="box:0,0,-20,80,80,0",
                       tools=["T1=ball,D3.175,L25"], voxel=0.2)
    print(r.removed, r.report.machining_s, [(a.kind, a.line) for a in r.alarms])
    r.write_vdb("remaining.vdb")     # pyopenvdb.read("remaining.vdb", "stock")
    r.write_stl("remaining.stl")
    r.write_png("remaining.png")

Program text works too (simulate(text="G0 X0 ...")), and so does streaming
(Simulation: feed, feed_file, finish). Callbacks: progress(Progress) after
every move (return True to stop: swarf.Aborted), alarm(Alarm), line(LineResult)
per source line once its moves are removed. Exceptions: SwarfError and its
classes InputError (the program, a spec or a file is wrong: file, line,
column, word and message say where), InternalError, Aborted.

Units: mm, seconds. Calls release the GIL; callbacks run in the calling
thread. One thread at a time per Simulation; distinct ones are independent.
"""
import math
import numbers
import os
from ctypes import byref, c_size_t, c_void_p, create_string_buffer
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

from . import _abi
from ._ffi import S, const, lib, types

__all__ = ["simulate", "Simulation", "Stock", "Result", "Report", "Alarm", "LineResult",
           "Progress", "SwarfError", "InputError", "InternalError", "Aborted",
           "set_read_isolation", "read_isolation", "library_version", "__version__"]

__version__ = lib.swarf_version().decode()
if __version__ != _abi.VERSION:
    raise ImportError("swarf: the Python module is %s but libswarf is %s"
                      % (_abi.VERSION, __version__))

_OK = const["SWARF_OK"]
_ALARM_KINDS = {const["SWARF_ALARM_" + k.upper()]: k
                for k in ("rapid", "shank", "holder", "fixture", "gouge", "no_tool")}


def library_version() -> str:
    """The version of the libswarf shared library in use ("MAJOR.MINOR.PATCH")."""
    return __version__


from ._errors import (Aborted, InputError, InternalError, SwarfError,  # noqa: E402,F401
                      _path, _raise, _raise_msg)


# ---- Values -----------------------------------------------------------------

@dataclass
class Alarm:
    """Something on a tool's way a machinist must hear about (the cut is still
    made). kind: "rapid" (a G0 cuts material), "shank", "holder", "fixture",
    "gouge"; line and column of the move; depth (mm, NaN when not measured),
    at (mm, workpiece frame), index (FIXTURE: which fixture, 1-based)."""
    kind: str
    line: int
    column: int
    tool: int
    depth: float
    at: Tuple[float, float, float]
    index: int

    @classmethod
    def _from(cls, a):
        return cls(_ALARM_KINDS.get(a.kind, str(a.kind)), a.line, a.column, a.tool, a.depth,
                   tuple(a.at), a.index)


@dataclass
class LineResult:
    """A source line that moved the tool: its moves, time at programmed feeds
    (s), tip path (mm) and the volume it removed (mm^3; NaN unless
    line_volumes=True)."""
    line: int
    tool: int
    moves: int
    time_s: float
    path_mm: float
    removed: float

    @classmethod
    def _from(cls, r):
        return cls(r.line, r.tool, r.moves, r.time_s, r.path_mm, r.removed)


@dataclass
class Deviation:
    """The result against the design (mm, mm^3): material left outside it
    (excess) and cut away inside it (gouge), beyond the tolerance; the
    largest of each and where (None when there is none)."""
    tolerance: float
    gouge_volume: float
    gouge_depth: float
    gouge_at: Optional[Tuple[float, float, float]]
    excess_volume: float
    excess_height: float
    excess_at: Optional[Tuple[float, float, float]]

    @classmethod
    def _from(cls, d):
        at = lambda p: None if math.isnan(p[0]) else tuple(p)
        return cls(d.tolerance, d.gouge_volume, d.gouge_depth, at(d.gouge_at), d.excess_volume,
                   d.excess_height, at(d.excess_at))


@dataclass
class Report:
    """Counts of a run (final after finish). Volumes in mm^3 (volume_after is
    NaN before the end), path in mm, times in s; alarm_count by kind."""
    lines: int
    moves: int
    cutting_moves: int
    rapids: int
    arcs: int
    tool_changes: int
    path_mm: float
    machining_s: float
    volume_before: float
    volume_after: float
    seconds: float
    alarms: int
    alarm_count: Dict[str, int] = field(default_factory=dict)
    start: Tuple[float, float, float] = (0.0, 0.0, 0.0)  # where the tool tip started, mm
    units_line: int = 0          # the program's first G20/G21 (0: none)
    units_missing_line: int = 0  # the first move run before any G20/G21 (0: none)
    deviation: Optional[Deviation] = None  # against the design, after finish (design=)

    @property
    def removed(self) -> float:
        """volume_before - volume_after, mm^3."""
        return self.volume_before - self.volume_after

    @classmethod
    def _from(cls, r):
        counts = {name: r.alarm_count[k] for k, name in _ALARM_KINDS.items()}
        return cls(r.lines, r.moves, r.cutting_moves, r.rapids, r.arcs, r.tool_changes, r.path_mm,
                   r.machining_s, r.volume_before, r.volume_after, r.seconds, r.alarms, counts,
                   tuple(r.start), r.units_line, r.units_missing_line,
                   Deviation._from(r.deviation) if r.has_deviation else None)


@dataclass
class Progress:
    """After every move: fraction of the program read (0..1, < 0 while
    unknown), the move's source line, the tool in the spindle, the counts so
    far."""
    fraction: float
    line: int
    tool: int
    report: Report


# ---- The stock --------------------------------------------------------------

class Stock:
    """A stock: an OpenVDB narrow-band level set (mm; negative inside the
    material). Read one with Stock.read(path); a simulation's result holds
    one. Writes are atomic (a temporary name, then a rename)."""

    def __init__(self, *args, _handle=None):
        if args or not _handle:
            raise TypeError("swarf.Stock: read one with swarf.Stock.read(path), or take a "
                            "simulation's result.stock; a Stock is not made from a number")
        self._h = c_void_p(_handle)

    @classmethod
    def read(cls, path) -> "Stock":
        """The grid named "stock" (or the first float level set) of a .vdb
        file (read in a child process unless set_read_isolation(False))."""
        err = S["swarf_error"]()
        h = c_void_p()
        if lib.swarf_stock_read(_path(path), byref(h), byref(err)) != 0:
            _raise(err)
        return cls(_handle=h.value)

    @classmethod
    def from_numpy(cls, values, origin, voxel, band=3) -> "Stock":
        """A stock from a NumPy array of signed distances (mm, < 0 inside)
        on voxel centres: values[i, j, k] at origin + voxel * (i, j, k). The
        array must hold the whole surface with air around it (the signs
        beyond the band are filled from it); band: half-width in voxels."""
        import numpy as np
        a = np.ascontiguousarray(values, dtype=np.float32)
        if a.ndim != 3 or 0 in a.shape:
            raise ValueError("from_numpy: a 3-D array with no empty axis, not shape %r"
                             % (a.shape,))
        o = (types["c_double"] * 3)(*_point(origin, "origin"))
        dims = (types["c_int"] * 3)(*a.shape)
        err, h = S["swarf_error"](), c_void_p()
        if lib.swarf_stock_from_dense(o, _number(voxel, "voxel", 0.0, math.inf), dims,
                                      a.ctypes.data, _whole(band, "band", 3, 64), byref(h),
                                      byref(err)) != 0:
            _raise(err)
        return cls(_handle=h.value)

    def to_numpy(self):
        """(values, origin, voxel): the signed distances (mm, float32, < 0
        inside, +-the band beyond it) on the voxel centres of the box of the
        active voxels, values[i, j, k] at origin + voxel * (i, j, k)."""
        import numpy as np
        lo, dims, o = (types["c_int"] * 3)(), (types["c_int"] * 3)(), (types["c_double"] * 3)()
        lib.swarf_stock_dense_box(self._handle(), lo, dims, o)
        shape = tuple(max(d, 0) for d in dims)
        a = np.empty(shape, dtype=np.float32)
        voxel = self.voxel
        if a.size:
            err = S["swarf_error"]()
            if lib.swarf_stock_to_dense(self._handle(), lo, dims, a.ctypes.data, byref(err)) != 0:
                _raise(err)
        return a, tuple(o[k] + voxel * lo[k] for k in range(3)), voxel

    def _handle(self):
        if self._h is None or not self._h.value:
            raise ValueError("swarf.Stock: closed (or given to a Simulation)")
        return self._h

    def _release(self):
        """The C handle, now owned by the caller (the Stock is empty after)."""
        h = self._handle()
        self._h = None
        return h

    def close(self):
        """Frees the grid now (also done when the object goes away)."""
        if getattr(self, "_h", None) is not None and self._h.value:
            lib.swarf_stock_free(self._h)
        self._h = None

    __del__ = close

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @property
    def volume(self) -> float:
        """Enclosed volume, mm^3."""
        return lib.swarf_stock_volume(self._handle())

    @property
    def voxel(self) -> float:
        """Voxel edge, mm."""
        return lib.swarf_stock_voxel(self._handle())

    @property
    def half_width(self) -> int:
        """Narrow band half width, voxels."""
        return lib.swarf_stock_half_width(self._handle())

    @property
    def active_voxels(self) -> int:
        return lib.swarf_stock_active_voxels(self._handle())

    @property
    def bounds(self):
        """((xmin, ymin, zmin), (xmax, ymax, zmax)) of the active voxels, mm."""
        lo, hi = (types["c_double"] * 3)(), (types["c_double"] * 3)()
        lib.swarf_stock_bounds(self._handle(), lo, hi)
        return tuple(lo), tuple(hi)

    def sample(self, x, y, z) -> float:
        """Interpolated level-set value at a point (mm; < 0 inside material)."""
        p = [_number(v, name, -math.inf, math.inf) for v, name in ((x, "x"), (y, "y"), (z, "z"))]
        return lib.swarf_stock_sample(self._handle(), *p)

    def check(self):
        """Raises InternalError unless the grid is a valid narrow-band level set."""
        err = S["swarf_error"]()
        if lib.swarf_stock_check(self._handle(), byref(err)) != 0:
            _raise_msg("SWARF_ERR_INTERNAL", err.message)

    def _write(self, fn, path, *args):
        err = S["swarf_error"]()
        if fn(self._handle(), _path(path), *args, byref(err)) != 0:
            _raise(err)

    def write_vdb(self, path):
        """OpenVDB file with one float level-set grid named "stock"."""
        self._write(lib.swarf_stock_write_vdb, path)

    def write_stl(self, path) -> int:
        """Binary STL of the surface; returns the triangle count."""
        n = c_size_t(0)
        self._write(lib.swarf_stock_write_stl, path, byref(n))
        return n.value

    def write_png(self, path, width=1024, height=768):
        """Shaded picture (OpenVDB's level-set ray tracer)."""
        self._write(lib.swarf_stock_write_png, path, _whole(width, "width", 1, 16384),
                    _whole(height, "height", 1, 16384))


def set_read_isolation(on: bool):
    """Whether reading a .vdb runs OpenVDB's reader in a forked child process
    (default on, or the environment's SWARF_VDB_ISOLATE). Process-wide."""
    lib.swarf_stock_set_read_isolation(1 if on else 0)


def read_isolation() -> bool:
    return bool(lib.swarf_stock_read_isolation())


# ---- A simulation -----------------------------------------------------------

@dataclass
class Result:
    """The end of a run: the remaining stock (owned), the final report, every
    alarm, every line that moved the tool."""
    stock: Stock
    report: Report
    alarms: List[Alarm]
    lines: List[LineResult]

    @property
    def removed(self) -> float:
        """Volume removed from the stock, mm^3."""
        return self.report.removed

    def line_array(self):
        """The lines as a NumPy structured array, one record a line in program
        order: line, tool, moves, time_s, path_mm, removed (mm^3; NaN unless
        line_volumes=True), for sorting and summing without a loop."""
        import numpy as np
        dtype = [("line", np.int64), ("tool", np.int32), ("moves", np.int64),
                 ("time_s", np.float64), ("path_mm", np.float64), ("removed", np.float64)]
        return np.array([(r.line, r.tool, r.moves, r.time_s, r.path_mm, r.removed)
                         for r in self.lines], dtype=dtype)

    def write_vdb(self, path):
        self.stock.write_vdb(path)

    def write_stl(self, path) -> int:
        return self.stock.write_stl(path)

    def write_png(self, path, width=1024, height=768):
        self.stock.write_png(path, width, height)


_DIALECTS = {"linuxcnc": 0, "fanuc": 1, "haas": 2, "grbl": 3}  # swarf_gcode_dialect
_UNITS = {"mm": "SWARF_GCODE_UNITS_MM", "in": "SWARF_GCODE_UNITS_INCH",
          "inch": "SWARF_GCODE_UNITS_INCH"}


def _point(value, what):
    try:
        x, y, z = (float(v) for v in value)
    except (TypeError, ValueError):
        _raise_msg("SWARF_ERR_ARG", "%s: give three numbers X, Y, Z (mm), not %r"
                   % (what, value), what)
    return x, y, z


def _spec(v, name):
    """A spec string as bytes for the C parser, or TypeError naming the argument."""
    if not isinstance(v, str):
        raise TypeError("%s: a spec string, not %r" % (name, v))
    return v.encode()


def _whole(v, name, lo, hi):
    """An int within [lo, hi], or TypeError/ValueError naming the argument
    (ctypes would wrap 2**32+3 into 3)."""
    if isinstance(v, bool) or not isinstance(v, numbers.Integral):
        raise TypeError("%s: a whole number, not %r" % (name, v))
    if not lo <= v <= hi:
        raise ValueError("%s: %d to %d, not %d" % (name, lo, hi, v))
    return int(v)


def _number(v, name, lo, hi):
    """A finite number in (lo, hi), or TypeError/ValueError naming it."""
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise TypeError("%s: a number, not %r" % (name, v))
    if not (lo < v < hi):
        raise ValueError("%s: a finite number above %g, not %r" % (name, lo, v))
    return float(v)


def _specs(v, name):
    """A spec string or a sequence of them, as a list."""
    if v is None:
        return []
    if isinstance(v, (str, bytes, os.PathLike)):
        return [v]
    try:
        return list(v)
    except TypeError:
        raise TypeError("swarf: %s: a spec string or a sequence of them, not %s"
                        % (name, type(v).__name__)) from None


def _tool_files(cfg, err, tool_table, tool_table_units, tool_library):
    """The tool table and the library into cfg, as --tool-table and --tool-library."""
    if tool_table_units not in ("mm", "in"):
        _raise_msg("SWARF_ERR_ARG", "tool_table_units: mm or in, not %r" % (tool_table_units,),
                   "tool_table_units")
    if tool_table is not None:
        per_unit = 25.4 if tool_table_units == "in" else 1.0
        if lib.swarf_sim_config_load_tool_table(byref(cfg), _path(tool_table), per_unit,
                                                byref(err)) != _OK:
            _raise(err)
    if tool_library is not None:
        if lib.swarf_sim_config_load_tool_library(byref(cfg), _path(tool_library),
                                                  byref(err)) != _OK:
            _raise(err)


def _tools(cfg, err, tools, holders):
    """Each tool spec (replacing a table's or library's tool of its number, as
    --tool does), then each holder spec (--holder)."""
    given = set()
    for spec in _specs(tools, "tools"):
        tool = S["swarf_sim_tool"]()
        if lib.swarf_sim_parse_tool(_spec(spec, "tools"), byref(tool), byref(err)) != _OK:
            _raise(err)
        if tool.number in given:
            _raise_msg("SWARF_ERR_ARG", "tools: T%d is given twice" % tool.number, "tools")
        given.add(tool.number)
        if lib.swarf_sim_config_put_tool(byref(cfg), byref(tool), byref(err)) != _OK:
            _raise(err)
    for spec in _specs(holders, "holders"):
        tool = S["swarf_sim_tool"]()
        if (lib.swarf_sim_parse_holder(_spec(spec, "holders"), byref(tool), byref(err)) != _OK
                or lib.swarf_sim_config_put_holder(byref(cfg), byref(tool), byref(err)) != _OK):
            _raise(err)


def _fixtures(cfg, err, fixtures):
    """The fixture specs into cfg (--fixture); returns the encoded specs, which
    an STL fixture's path points into until swarf_sim_new returns."""
    kept = []
    for spec in _specs(fixtures, "fixtures"):
        if cfg.nfixtures == const["SWARF_SIM_MAX_FIXTURES"]:
            _raise_msg("SWARF_ERR_ARG", "fixtures: %d at most" % const["SWARF_SIM_MAX_FIXTURES"],
                       "fixtures")
        text = create_string_buffer(_spec(spec, "fixtures"))
        kept.append(text)
        if lib.swarf_sim_parse_fixture(text, byref(cfg.fixtures[cfg.nfixtures]),
                                       byref(err)) != _OK:
            _raise(err)
        cfg.nfixtures += 1
    return kept


def _config(tools, voxel, machine, band, batch, line_volumes, start, g54, units, offsets,
            tool_table=None, tool_table_units="mm", tool_library=None, holders=None,
            fixtures=None, collision_depths=None):
    """The swarf_sim_config of the options; also returns what it borrows."""
    cfg = S["swarf_sim_config"]()
    lib.swarf_sim_config_init(byref(cfg))
    err = S["swarf_error"]()
    if machine is not None:
        if lib.swarf_machine_parse(byref(cfg.machine), _spec(machine, "machine"), byref(err)) != _OK:
            _raise(err)
    if start is not None:
        cfg.start_set, cfg.start[:] = 1, _point(start, "start")
    if g54 is not None:
        cfg.g54_set, cfg.g54[:] = 1, _point(g54, "g54")
    if units is not None:
        if units not in _UNITS:
            _raise_msg("SWARF_ERR_ARG", "units: mm or in, not %r" % (units,), "units")
        cfg.units = const[_UNITS[units]]
    borrowed = None
    if offsets is not None:
        borrowed = _path(offsets)
        cfg.offsets_file = borrowed
    if voxel is not None:
        cfg.voxel = _number(voxel, "voxel", 0.0, math.inf)
    if band is not None:
        cfg.half_width = _whole(band, "band", 3, 64)
    if batch is not None:
        cfg.batch = _whole(batch, "batch", 1, 2**31 - 1)
    cfg.line_volumes = 1 if line_volumes else 0
    if collision_depths is not None:
        cfg.collision_depths = _whole(collision_depths, "collision_depths", 0, 10**9)
    _tool_files(cfg, err, tool_table, tool_table_units, tool_library)
    _tools(cfg, err, tools, holders)
    return cfg, (borrowed, _fixtures(cfg, err, fixtures))


class Simulation:
    """A streaming simulation (swarf_sim.h):

        with swarf.Simulation("box:0,0,-10,40,40,0", ["T1=flat,D6"]) as sim:
            sim.feed("G0 X0 Y0 Z5\\nG1 Z-1 F100\\n")
            sim.feed("G1 X30\\n")
            result = sim.finish()

    stock: a spec ("box:XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX" or
    "cylinder:AXIS,RADIUS,START,END", mm) or a Stock (an earlier result, a
    .vdb read back), which the simulation then owns. tools: spec strings
    "T<n>=<shape>,D<diameter>[,R<corner>][,L<length>]" (ball, flat, bull).
    voxel (mm, default 0.2), machine ("xyz", "xyza[,pivot=Y,Z]",
    "xyzac-trt[,mode=tcp|joint][,pivot=X,Y,Z]", "xyzab-tdr", "xyzbc-hh,mode=joint,head=L",
    "xyzbc-ht[,pivot=X,Y][,head=L]", ...), band (voxels, >= 3),
    line_volumes (measure each line's removed volume) as `swarf simulate`.
    The machine's setup, as `swarf simulate` --start, --g54, --units,
    --offsets: start (X, Y, Z: the tool tip when the program starts, mm,
    workpiece frame; default X0 Y0 10 mm above the stock), g54 (G54's origin
    in machine coordinates, mm), units ("mm" or "in": the machine's unit),
    offsets (LinuxCNC's parameter file). How the program is read, as
    --dialect and --block-delete: dialect ("linuxcnc", the default, "fanuc",
    "haas" or "grbl"), block_delete (True: `/` blocks are skipped),
    subroutine_path (where `o<name> call` finds <name>.ngc: directories
    joined by ':'), design (a closed STL or .vdb path, or a Stock: each move
    cutting into it beyond tolerance mm is a gouge alarm, and the result's
    report.deviation compares the part with it; a Stock given stays the
    caller's and must stay open), fragment (True: the text is not a whole program and need
    not end; False, the default: a LinuxCNC program must end with M2, M30 or
    a closing %, as rs274 requires). The tools as `swarf simulate` takes
    them: tool_table (a LinuxCNC tool table; tool_table_units "mm" or "in"),
    tool_library (a JSON library of assemblies), then tools (spec strings
    that replace a table's tool of the same number), holders ("T1=20x40,
    20-32x10": the holder of a tool with a stick-out S), fixtures ("box:..."
    or "stl:FILE": bodies no part of the tool may enter), collision_depths
    (how many collisions of each kind get their depth measured, 0: all).
    Collisions come as alarms "shank", "holder" and "fixture". design_cache:
    where an STL design's band is kept for the next run (a folder; None: the
    user's cache folder, as the command; False or "off": none). name is the
    program's name in messages."""

    def __init__(self, stock, tools=(), *, voxel=None, machine=None, band=None, batch=None,
                 line_volumes=False, start=None, g54=None, units=None, offsets=None,
                 dialect=None, block_delete=False, subroutine_path=None, fragment=False,
                 design=None, tolerance=None, tool_table=None, tool_table_units="mm",
                 tool_library=None, holders=None, fixtures=None, collision_depths=None,
                 design_cache=None, name="program", progress=None, alarm=None, line=None):
        self._h = c_void_p()
        self._exc = None
        self._busy = False  # inside a C call (feed, feed_file, finish)
        self._close_pending = False  # close() from a callback: done when the call returns
        self._user = (progress, alarm, line)
        self.alarms: List[Alarm] = []
        self.lines: List[LineResult] = []
        self.name = os.fsdecode(name)
        cfg, borrowed = _config(tools, voxel, machine, band, batch, line_volumes, start, g54,
                                units, offsets, tool_table, tool_table_units, tool_library,
                                holders, fixtures, collision_depths)
        if dialect is not None:
            if dialect not in _DIALECTS:
                _raise_msg("SWARF_ERR_ARG", "dialect: linuxcnc, fanuc, haas or grbl, not %r"
                           % (dialect,), "dialect")
            cfg.dialect = _DIALECTS[dialect]
        cfg.block_delete = 1 if block_delete else 0
        cfg.fragment = 1 if fragment else 0
        subpath = None
        if subroutine_path is not None:
            subpath = _path(subroutine_path)  # borrowed by new (it copies it)
            cfg.subroutine_path = subpath
        self._design = self._read_design(cfg, stock, design, tolerance, design_cache)
        # The C callbacks; kept alive as long as the handle.
        self._cbs = (types["PROGRESS_FN"](self._on_progress), types["ALARM_FN"](self._on_alarm),
                     types["LINE_FN"](self._on_line))
        cfg.cb.progress, cfg.cb.alarm, cfg.cb.line = self._cbs
        err = S["swarf_error"]()
        if isinstance(stock, Stock):
            rc = lib.swarf_sim_new_with_stock(byref(cfg), self.name.encode(), stock._release(),
                                              byref(self._h), byref(err))
        else:
            if lib.swarf_sim_parse_stock(_spec(stock, "stock"), byref(cfg.stock),
                                         byref(err)) != _OK:
                _raise(err)
            rc = lib.swarf_sim_new(byref(cfg), self.name.encode(), byref(self._h), byref(err))
        del borrowed, subpath  # the offsets file's name, the path: read by new
        if rc != _OK:
            self._h = c_void_p()
            _raise(err)

    # Callbacks from C: never let an exception escape into ctypes; the first
    # one stops the run (progress returns 1) and is raised when the call returns.
    def _on_progress(self, user, p):
        if self._exc is not None or self._close_pending:
            return 1
        fn = self._user[0]
        try:
            if fn is not None:
                q = p.contents
                if fn(Progress(q.fraction, q.line, q.tool, Report._from(q.report.contents))):
                    return 1
        except BaseException as e:  # noqa: B902 (Ctrl-C stops the run too)
            self._exc = e
            return 1
        return 0

    def _on_alarm(self, user, a):
        try:
            alarm = Alarm._from(a.contents)
            self.alarms.append(alarm)
            if self._user[1] is not None and self._exc is None:
                self._user[1](alarm)
        except BaseException as e:  # noqa: B902
            self._exc = self._exc or e

    def _on_line(self, user, r):
        try:
            result = LineResult._from(r.contents)
            self.lines.append(result)
            if self._user[2] is not None and self._exc is None:
                self._user[2](result)
        except BaseException as e:  # noqa: B902
            self._exc = self._exc or e

    def _handle(self):
        if not self._h.value:
            raise ValueError("swarf.Simulation: closed")
        return self._h

    def _run(self, fn, *args):
        """A C call on the handle; a close() from one of its callbacks stops
        the run and frees the handle when the call has returned."""
        h = self._handle()
        self._busy = True
        try:
            rc = fn(h, *args)
        finally:
            self._busy = False
        if self._close_pending:
            self._close_pending = False
            self._exc = None
            self.close()
            _raise_msg("SWARF_ERR_ABORTED", "closed from a callback: the run stopped")
        self._check(rc)

    def _check(self, rc):
        if self._exc is not None:
            e, self._exc = self._exc, None
            raise e
        if rc != _OK:
            _raise(lib.swarf_sim_error(self._handle()).contents)

    @staticmethod
    def _read_design(cfg, stock, design, tolerance, design_cache=None):
        """The design as a Stock (a path read at the run's voxel, with the band
        the comparison needs, as `swarf simulate --design`, through the design
        cache), put into cfg."""
        if tolerance is not None:
            if design is None:
                _raise_msg("SWARF_ERR_ARG", "tolerance: the design's; give design= too",
                           "tolerance")
            cfg.tolerance = _number(tolerance, "tolerance", 0.0, 100.0)
        if design is None:
            return None
        if not isinstance(design, Stock):
            voxel = stock.voxel if isinstance(stock, Stock) else cfg.voxel
            band = lib.swarf_stock_design_band(None, voxel, cfg.tolerance, 0)
            err, h = S["swarf_error"](), c_void_p()
            cache = S["swarf_design_cache"]()
            if design_cache is False or design_cache == "off":
                cache.off = 1
            elif design_cache is not None:
                cache_dir = _path(design_cache)  # borrowed by the call
                cache.dir = cache_dir
            if lib.swarf_sim_read_design_cached(_path(design), voxel, band, byref(cache),
                                                byref(h), None, byref(err)) != 0:
                _raise(err)
            design = Stock(_handle=h.value)
        cfg.design = design._handle().value
        return design

    def feed(self, text):
        """Program text (str or bytes, any split); complete lines run at once."""
        if isinstance(text, str):
            data = text.encode()
        elif isinstance(text, (bytes, bytearray, memoryview)):
            data = bytes(text)
        else:
            raise TypeError("feed: program text as str or bytes, not %r" % (text,))
        self._run(lib.swarf_sim_feed, data, len(data))

    def set_program_size(self, size):
        """The program's size in bytes, when it is fed as text (feed) and known:
        progress then gives the fraction read after every move (simulate(text=)
        sets it)."""
        self._run(lib.swarf_sim_set_program_size, _whole(size, "size", 0, 2**62))

    def feed_file(self, path):
        """The whole file at path (progress then has a fraction)."""
        self._run(lib.swarf_sim_feed_file, _path(path))

    @property
    def report(self) -> Report:
        """The counts so far."""
        return Report._from(lib.swarf_sim_get_report(self._handle()).contents)

    def finish(self) -> Result:
        """Ends the program (the last line, the last batch) and returns the
        Result, which owns the stock; the simulation takes no more input."""
        self._run(lib.swarf_sim_finish)
        report = self.report
        stock = Stock(_handle=lib.swarf_sim_take_stock(self._handle()))
        return Result(stock, report, list(self.alarms), list(self.lines))

    def close(self):
        """Frees the simulation; from one of its own callbacks, the run stops
        first (the call in progress raises Aborted)."""
        if getattr(self, "_busy", False):
            self._close_pending = True
            return
        if getattr(self, "_h", None) is not None and self._h.value:
            lib.swarf_sim_free(self._h)
            self._h = c_void_p()

    __del__ = close

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def simulate(program=None, *, text=None, stock, tools=(), voxel=None, machine=None, band=None,
             batch=None, line_volumes=False, start=None, g54=None, units=None, offsets=None,
             dialect=None, block_delete=False, subroutine_path=None, fragment=False,
             design=None, tolerance=None, tool_table=None, tool_table_units="mm",
             tool_library=None, holders=None, fixtures=None, collision_depths=None,
             design_cache=None, name=None, progress=None, alarm=None, line=None) -> Result:
    """Runs a program: the G-code file at `program`, or the string `text`.
    Options as Simulation (and `swarf simulate`). Returns the Result; raises
    InputError with file, line and column for a bad program or option."""
    if (program is None) == (text is None):
        raise TypeError("swarf.simulate: give a program path or text=, not both")
    if name is None:
        name = os.fspath(program) if program is not None else "<text>"
    with Simulation(stock, tools, voxel=voxel, machine=machine, band=band, batch=batch,
                    line_volumes=line_volumes, start=start, g54=g54, units=units,
                    offsets=offsets, dialect=dialect, block_delete=block_delete,
                    subroutine_path=subroutine_path, fragment=fragment,
                    design=design, tolerance=tolerance, tool_table=tool_table,
                    tool_table_units=tool_table_units, tool_library=tool_library,
                    holders=holders, fixtures=fixtures, collision_depths=collision_depths,
                    design_cache=design_cache, name=name, progress=progress, alarm=alarm,
                    line=line) as sim:
        if text is not None:
            data = text.encode() if isinstance(text, str) else text
            if isinstance(data, (bytes, bytearray, memoryview)):
                sim.set_program_size(len(bytes(data)))
            sim.feed(data)
        else:
            sim.feed_file(program)
        return sim.finish()
