/* SPDX-License-Identifier: MPL-2.0 */
/* gcode.h -- the G-code front end: a streaming RS274/NGC interpreter.
 *
 * Role: turn program text (LinuxCNC dialect) into canonical moves, each with
 * the source line and column of the block that produced it. The parser is
 * streaming, in cmark's shape: new, feed(buffer, length) any number of times,
 * finish, free. Moves are handed to a callback as soon as they are produced;
 * memory does not grow with the length of the program.
 *
 * Units at this boundary: positions in mm (G20 programs are converted),
 * rotary axes in degrees, feed in mm/min, spindle in rpm, dwell in seconds.
 * Positions of moves are in the machine frame: program coordinates with G92
 * or G52, the work system's XY rotation, its origin (G54-G59.3, G10) and the
 * tool length offset (G43) applied, as LinuxCNC's motion controller does.
 * The canon listener (swarf_gcode_parser_set_canon) sees program
 * coordinates instead, as `rs274 -g` prints them.
 *
 * Errors: every call that can fail returns a swarf_status (swarf_status.h).
 * A program the front end rejects leaves a swarf_error with the file, line,
 * column and word, the message the user reads and, in .code, the error's
 * identity: one of the SWARF_GCODE_E_* of errors.def, one per distinct error
 * (like LinuxCNC's NCE_ codes), so callers and tests can match identities.
 *
 * Thread safety: a parser is used by one thread at a time; distinct parsers
 * are independent. The error table is constant.
 */
#ifndef SWARF_GCODE_H
#define SWARF_GCODE_H

#include <stddef.h>

#include "swarf_status.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Axis indices into the 6-vectors of a move. */
enum { SWARF_AXIS_X, SWARF_AXIS_Y, SWARF_AXIS_Z, SWARF_AXIS_A, SWARF_AXIS_B, SWARF_AXIS_C };
#define SWARF_NAXES 6

typedef enum {
  SWARF_MOVE_RAPID,      /* G0: straight traverse */
  SWARF_MOVE_LINE,       /* G1: straight feed */
  SWARF_MOVE_ARC,        /* G2/G3: circular or helical feed */
  SWARF_MOVE_DWELL,      /* G4: no motion, `dwell` seconds */
  SWARF_MOVE_TOOL_CHANGE /* M6: tool `tool` is now in the spindle; no motion */
} swarf_move_kind;

/* One canonical move. For an arc, the motion is
 *   p(a) = center + Rot(normal, a * angle) (start - center) + a * rise * normal,
 * for a in [0, 1], where Rot(n, th) turns by th about n by the right-hand
 * rule; `angle` > 0 (radians) includes full extra turns; `rise` is the
 * displacement along `normal` (mm); `center` lies in the plane of `start`.
 * For G2 in G17 normal = (0,0,-1), for G3 normal = (0,0,1). */
typedef struct {
  swarf_move_kind kind;
  double start[SWARF_NAXES]; /* mm, degrees */
  double end[SWARF_NAXES];   /* mm, degrees */
  double center[3];          /* arcs only, mm */
  double normal[3];          /* arcs only, unit */
  double angle;              /* arcs only, radians, > 0 */
  double rise;               /* arcs only, mm */
  double feed;               /* mm/min; 0 for rapids */
  double spindle;            /* rpm, signed: negative for M4 */
  double dwell;              /* seconds, dwell moves only */
  int tool;                  /* tool in the spindle (0: none) */
  long line;                 /* 1-based source line of the block */
  int column;                /* 1-based column of the block's motion word */
} swarf_move;

/* The identities of the front end's errors (errors.def), the .code of its
 * swarf_errors: SWARF_GCODE_E_NESTED_COMMENT, SWARF_GCODE_E_ARC_RADIUS_MISMATCH, ...
 * Values follow the table (new identities are added at its end). */
typedef enum {
  SWARF_GCODE_E_NONE = 0,
#define X(id, status, format) SWARF_GCODE_E_##id,
#include "errors.def"
#undef X
  SWARF_GCODE_E_END_
} swarf_gcode_error_code;

/* "SWARF_GCODE_E_NESTED_COMMENT"; NULL for a value that is no identity. */
SWARF_API const char *swarf_gcode_error_name(int code);
/* The status an identity fails with (SWARF_ERR_SYNTAX, ...); SWARF_ERR_INTERNAL
 * for a value that is no identity. */
SWARF_API swarf_status swarf_gcode_error_status(int code);
/* Its message's printf format (errors.def); NULL for a value that is no identity. */
SWARF_API const char *swarf_gcode_error_format(int code);

/* Called for every move, in program order. Return 0 to go on, non-zero to
 * stop the parser (feed/finish then return SWARF_ERR_ABORTED, identity
 * SWARF_GCODE_E_STOPPED). The move is only valid during the call. */
typedef int (*swarf_gcode_move_fn)(const swarf_move *move, void *user);

typedef struct swarf_gcode_parser swarf_gcode_parser;

/* A new parser for a program called `filename` (used in error messages; it is
 * not opened) into *out. The machine starts at 0,0,0 (all axes), G17 G21 G90
 * G91.1 G94, feed 0, spindle off, no tool. SWARF_ERR_MEMORY (*out = NULL)
 * when out of memory, SWARF_ERR_ARG when out is NULL. */
SWARF_API swarf_status swarf_gcode_parser_new(const char *filename, swarf_gcode_move_fn fn,
                                              void *user, swarf_gcode_parser **out);

/* Called with each canonical call, formatted as `rs274 -g` prints it (a
 * sequence number, the N field, the call; no newline), in program
 * coordinates and the active unit: motions (STRAIGHT_TRAVERSE,
 * STRAIGHT_FEED, ARC_FEED, DWELL) and the offset, unit, feed, tool, comment
 * and message calls around them. The text is only valid during the call. */
typedef void (*swarf_gcode_canon_fn)(const char *call, void *user);

/* Sets the canon listener; call before the first feed (SWARF_ERR_STATE after). */
SWARF_API swarf_status swarf_gcode_parser_set_canon(swarf_gcode_parser *p, swarf_gcode_canon_fn fn,
                                                    void *user);

/* Loads a LinuxCNC tool table (lines "T1 P1 Z0.511 D0.125 ;comment"; values
 * in inches, as rs274 reads a table without an INI file). Call before the
 * first feed. SWARF_ERR_OPEN (identity SWARF_GCODE_E_TOOL_TABLE_OPEN) when it
 * cannot be read; *err (may be NULL) says why. */
SWARF_API swarf_status swarf_gcode_parser_load_tools(swarf_gcode_parser *p, const char *path,
                                                     swarf_error *err);

/* Empties the tool table (the built-in one of rs274 too: without a table,
 * tools 1-3 have rs274's lengths 0.511, 0.1 and 1.273 in), so that only tools
 * given with swarf_gcode_parser_set_tool exist; then sets tool `tool`
 * (1..999): its length offset (mm, what G43 H<tool> applies) and diameter
 * (mm). Call before the first feed. The simulator gives every cutter length
 * 0: it follows the tool tip, so G43 with the right H changes nothing. */
SWARF_API swarf_status swarf_gcode_parser_clear_tools(swarf_gcode_parser *p);
SWARF_API swarf_status swarf_gcode_parser_set_tool(swarf_gcode_parser *p, int tool, double length,
                                                   double diameter);

/* Feed `len` bytes of program text (any split, CRLF or LF). Complete lines are
 * interpreted at once. Returns SWARF_OK or the status of the first error;
 * after an error the parser refuses further input (returning that status
 * again) and swarf_gcode_parser_error says what and where. Feeding after
 * finish is SWARF_ERR_STATE. */
SWARF_API swarf_status swarf_gcode_parser_feed(swarf_gcode_parser *p, const char *buf, size_t len);

/* Interpret the last, unterminated line if any, and end the program. */
SWARF_API swarf_status swarf_gcode_parser_finish(swarf_gcode_parser *p);

/* The error that stopped the parser, or NULL if none. Owned by the parser. */
SWARF_API const swarf_error *swarf_gcode_parser_error(const swarf_gcode_parser *p);

/* Number of lines read so far and whether the program ended (M2/M30/%). */
SWARF_API long swarf_gcode_parser_lines(const swarf_gcode_parser *p);
/* The bytes of the lines read so far, newlines included (a line's moves see
 * it counted): with the program's size, the fraction of it read. */
SWARF_API long long swarf_gcode_parser_bytes(const swarf_gcode_parser *p);
SWARF_API int swarf_gcode_parser_ended(const swarf_gcode_parser *p);

SWARF_API void swarf_gcode_parser_free(swarf_gcode_parser *p);

/* ---- The machine's setup (call before the first feed) ----------------------
 * Without these calls a parser starts as rs274 without an INI file: the
 * controlled point at machine 0,0,0 (all axes), G21, every offset zero, and
 * the parameters that back offsets (#5161-#5189, #5211-#5219, #5221-#5399,
 * #5401-#5409) read in inches. These calls describe the machine a program
 * runs on instead, as LinuxCNC's INI and parameter file do. Each returns
 * SWARF_ERR_ARG for a NULL parser or a value out of range and
 * SWARF_ERR_STATE once the first byte was fed; err (may be NULL) says why. */

typedef enum {
  SWARF_GCODE_UNITS_MM = 1,  /* G21 */
  SWARF_GCODE_UNITS_INCH = 2 /* G20 */
} swarf_gcode_units;

/* The machine's length unit (LinuxCNC's [TRAJ]LINEAR_UNITS): the program
 * starts in it (G21 or G20 until it gives its own), and the parameters that
 * back offsets hold values in it, as the machine's parameter file does.
 * Call it first: SWARF_ERR_STATE once a parameter was set. */
SWARF_API swarf_status swarf_gcode_parser_set_units(swarf_gcode_parser *p, swarf_gcode_units u,
                                                    swarf_error *err);

/* Sets numbered parameter `index` (1..5601) as `#index = value` would just
 * before the first line: #5221-#5223 move G54's origin (values in the
 * machine's length unit), #5161 G28's home, and so on. Two follow LinuxCNC's
 * start-up: #5220 (1..9) selects the work system in force (G54..G59.3), and
 * #5210 = 1 puts the G92 offset #5211-#5216 in force. The parameters the
 * interpreter computes (#5021-#5029, #5400, #5420-#5428) are refused
 * (SWARF_ERR_ARG), as is a value that is not finite. */
SWARF_API swarf_status swarf_gcode_parser_set_param(swarf_gcode_parser *p, int index, double value,
                                                    swarf_error *err);

/* Reads LinuxCNC's parameter file (the machine's .var: one parameter a line,
 * "NUMBER VALUE", e.g. "5221 10.000000" for G54's X origin) and sets each
 * as swarf_gcode_parser_set_param does. Strict: every line that is not blank
 * must be an integer, blanks and a number and nothing else; a number twice,
 * a value out of range or a parameter that cannot be set is an error too
 * (SWARF_ERR_FORMAT, err->file and err->line say where); SWARF_ERR_OPEN when
 * the file cannot be read. On failure the parser is unchanged. */
SWARF_API swarf_status swarf_gcode_parser_load_params(swarf_gcode_parser *p, const char *path,
                                                      swarf_error *err);

/* Where the controlled point is when the program starts, in machine
 * coordinates (mm, degrees; before any offset). The program's current point
 * (what G91 adds to, what #5420 reads) follows from the offsets set up, in
 * any order with the calls above. Default: all zero. */
SWARF_API swarf_status swarf_gcode_parser_set_start(swarf_gcode_parser *p,
                                                    const double machine[SWARF_NAXES],
                                                    swarf_error *err);

/* Work system `system` (1 = G54 ... 9 = G59.3) as it stands: its origin
 * (machine mm, degrees) and XY rotation (degrees). SWARF_ERR_ARG when
 * system is out of range. */
SWARF_API swarf_status swarf_gcode_parser_work_system(const swarf_gcode_parser *p, int system,
                                                      double origin[SWARF_NAXES], double *rotation);

/* The source line of the first G20 or G21 the program ran; 0 while none
 * (the program then runs in the machine's unit). */
SWARF_API long swarf_gcode_parser_units_line(const swarf_gcode_parser *p);

/* ---- Dialects and the operator's switches (call before the first feed) ---
 * The dialect the program is read in (tools/doc/dialects.md has the
 * table of what differs):
 *   LINUXCNC  LinuxCNC's RS274/NGC, as `rs274` reads it (the default);
 *   FANUC     Fanuc 0i/30i-style: O program numbers, M98/M99 subprograms
 *             (also in the same file, after the main program), G65 macro
 *             calls with arguments, #1-#33 locals, #100-#999 variables,
 *             GOTO/IF/WHILE, canned cycles in their own modal group (G80
 *             leaves the last G0-G3 in force), K repeats, G10 L2/L20/L10-L13,
 *             G54.1 P1-P300; dwell P in milliseconds without a point;
 *   HAAS      Fanuc's plus Haas's: M97 local subprograms (P = N number),
 *             G154 P1-P99, vendor M codes (M29, M31, M33, ...) and G187, G103
 *             accepted without motion, each with a note;
 *   GRBL      grbl 1.1's subset: its G and M codes and words only, no
 *             parameters, expressions or O words, `$` lines and `%` lines
 *             ignored (with a note), no tool table (G43.1 only).
 * FANUC and HAAS programs are read whole before they run (a subprogram may
 * follow the main program in the file): moves come out at finish (or at
 * the closing `%`), and memory grows with the program. */
typedef enum {
  SWARF_GCODE_DIALECT_LINUXCNC = 0,
  SWARF_GCODE_DIALECT_FANUC = 1,
  SWARF_GCODE_DIALECT_HAAS = 2,
  SWARF_GCODE_DIALECT_GRBL = 3
} swarf_gcode_dialect;

/* "linuxcnc", "fanuc", "haas", "grbl" -> *out: 0, or -1 for another name. */
SWARF_API int swarf_gcode_dialect_from_name(const char *name, swarf_gcode_dialect *out);
/* The name of a dialect; NULL for a value that is none. */
SWARF_API const char *swarf_gcode_dialect_name(swarf_gcode_dialect d);

/* Sets the dialect. SWARF_ERR_ARG for a value that is no dialect,
 * SWARF_ERR_STATE once the first byte was fed. */
SWARF_API swarf_status swarf_gcode_parser_set_dialect(swarf_gcode_parser *p, swarf_gcode_dialect d,
                                                      swarf_error *err);

/* The text is a fragment, not a whole program (MDI lines, an excerpt, a
 * test): it need not end. Off by default, and then a LinuxCNC program that
 * ends with no M2, M30 or closing `%` is an error at its last line, as rs274
 * gives it ("File ended with no percent sign or program end"); Fanuc, Haas
 * and grbl programs never need an end. */
SWARF_API swarf_status swarf_gcode_parser_set_fragment(swarf_gcode_parser *p, int on,
                                                       swarf_error *err);

/* The operator's block delete switch (LinuxCNC's "/" button, Fanuc's block
 * skip): off by default, and then blocks that start with `/` run, as rs274
 * runs them; on, they are skipped. */
SWARF_API swarf_status swarf_gcode_parser_set_block_delete(swarf_gcode_parser *p, int on,
                                                           swarf_error *err);

/* The bound on work: lines run by loops, calls and subprograms together
 * (O-word flow, M98/M97/G65 and GOTO/WHILE), beyond the program's own lines,
 * and the moves and arc turns beyond one a line those lines make (a loop of
 * many-turn helixes or of pecking cycles is bounded by its work, not its
 * lines). A program that would do more stops with a work-limit error at its
 * line. Default SWARF_GCODE_WORK_LIMIT (a few seconds of interpreting); lower
 * it for quick checks (the fuzz target runs at 100,000), raise it up to
 * SWARF_GCODE_WORK_LIMIT_MAX for long generated programs. SWARF_ERR_ARG
 * outside 1..SWARF_GCODE_WORK_LIMIT_MAX, SWARF_ERR_STATE once the first byte
 * was fed. */
#define SWARF_GCODE_WORK_LIMIT 5000000L
#define SWARF_GCODE_WORK_LIMIT_MAX 1000000000L
SWARF_API swarf_status swarf_gcode_parser_set_work_limit(swarf_gcode_parser *p, long lines,
                                                         swarf_error *err);

/* Where `o<name> call` finds a subroutine that the program does not define
 * (LinuxCNC's [RS274NGC]SUBROUTINE_PATH): directories separated by ':', each
 * searched for <name>.ngc, which holds `o<name> sub` ... `o<name> endsub`.
 * The string is copied. Default: none (an undefined subroutine is an error). */
SWARF_API swarf_status swarf_gcode_parser_set_subroutine_path(swarf_gcode_parser *p,
                                                              const char *dirs, swarf_error *err);

/* Notes: what the front end accepted without acting on it (a vendor M code,
 * a grbl `$` line, a probing move that found nothing) or chose where the
 * controller would ask the operator. Called once per note, in program
 * order; `line` and `column` are 1-based; the text is only valid during
 * the call. Set before the first feed. */
typedef void (*swarf_gcode_note_fn)(long line, int column, const char *note, void *user);
SWARF_API swarf_status swarf_gcode_parser_set_notes(swarf_gcode_parser *p, swarf_gcode_note_fn fn,
                                                    void *user);

/* Convenience: stream a whole file through a parser. On error *err (if not
 * NULL) is filled: the parser's error, or the file's (SWARF_ERR_OPEN,
 * identity SWARF_GCODE_E_FILE_OPEN or _FILE_READ, line 0). */
SWARF_API swarf_status swarf_gcode_parse_file(const char *path, swarf_gcode_move_fn fn, void *user,
                                              swarf_error *err);

#ifdef __cplusplus
}
#endif
#endif
