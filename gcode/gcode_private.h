/* SPDX-License-Identifier: MPL-2.0 */
/* gcode_private.h -- the G-code front end's insides, shared by its files only.
 *
 * The pipeline, one line at a time (parse, check, commit, as grbl does):
 *   parser.c  streams bytes into lines; `%`, block delete, program end.
 *   oword.c   O-word control lines: records sub bodies and loops, runs
 *             stored lines (calls, while, do, repeat, if) with a program
 *             counter; other lines go straight to the block path.
 *   lexer.c   one line -> tokens (words, comments, assignments), values
 *             evaluated by expr.c with parameters from params.c.
 *   block.c   tokens -> a block: every word of the line, each G and M code
 *             filed under its modal group (codes.c holds the tables).
 *   check.c   the block against the modal state. Nothing is changed.
 *   interp.c  executes a checked block on a COPY of the state, in LinuxCNC's
 *             order; offsets.c (G10 G28 G30 G52 G92 G43), motion.c (G0-G3,
 *             arc.c for arcs) and cycle.c (G73 G81-G89) emit canonical
 *             calls into an out list (canon.c) that the parser hands out
 *             only when the whole block succeeded: a rejected block changes
 *             nothing.
 *   ccomp*.c  cutter radius compensation: compensated moves are held in
 *             the out list until the next move (LinuxCNC's queue); the
 *             parser carries held calls over to the next block.
 *   fault.c   the error record every step fills.
 *
 * Internal units: mm, degrees, mm/min; positions are program coordinates
 * (before work offsets, G92 and rotation); canon.c prints them in the
 * active unit and turns them into machine-frame swarf_moves. Codes are kept
 * as integers in tenths (G91.1 -> 911, M6 -> 60).
 */
#ifndef SWARF_GCODE_PRIVATE_H
#define SWARF_GCODE_PRIVATE_H

#include <stddef.h>

#include "gcode.h"

#define SWARF_GC_MM_PER_INCH 25.4
#define SWARF_GC_LINE_MAX ((size_t)1 << 20) /* longest line accepted, bytes */
#define SWARF_GC_NUMBER_MAX 1e9             /* largest magnitude of a word's value */
#define SWARF_GC_WORD_TEXT 40               /* a word as written, for messages */
#define SWARF_GC_NPARAMS 5602               /* numbered parameters #1..#5601 */
#define SWARF_GC_NAME_MAX 64                /* longest parameter or O-word name */
#define SWARF_GC_MAX_ASSIGN 50              /* parameter settings on one line */
#define SWARF_GC_NSYSTEMS 9                 /* G54..G59.3 */

/* ---- fault.c: what went wrong, and where on the line -------------------- */
/* Every step fills the project's swarf_error (swarf_status.h): status (the
 * identity's, errors.def), code (SWARF_GCODE_E_*), column on the current line
 * and message; the parser adds the file, the line and the word. */

/* The message formats of errors.def, one array an identity, named after it
 * (swarf_gc_fmt_SWARF_GCODE_E_NESTED_COMMENT), so that SWARF_GC_FAIL finds
 * the format from the identity and the compiler checks the arguments. */
#define X(id, status, format) static const char swarf_gc_fmt_SWARF_GCODE_E_##id[] = format;
#include "errors.def"
#undef X

/* Fails with identity `code`, written out (SWARF_GCODE_E_NESTED_COMMENT), at
 * `column`: SWARF_GC_FAIL(f, code, column, format arguments...). Fills `f`
 * and returns the identity's status, so callers can `return SWARF_GC_FAIL(...)`. */
#define SWARF_GC_FAIL(f, code, ...) swarf_gc_fail((f), (code), swarf_gc_fmt_##code, __VA_ARGS__)
swarf_status swarf_gc_fail(swarf_error *f, int code, const char *format, int column, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 5)))
#endif
    ;
/* The same for an identity held in a variable; its message takes no argument. */
swarf_status swarf_gc_fail_code(swarf_error *f, int code, int column);

/* Fails a call of the public API with identity `code`, written out, into the
 * caller's record: SWARF_GC_ERROR(code, err, format arguments...) sets
 * err's status, code and message (err may be NULL; its file, line, column
 * and word stay: swarf_error_at sets them) and returns the status. */
#define SWARF_GC_ERROR(code, ...) swarf_gc_error((code), swarf_gc_fmt_##code, __VA_ARGS__)
swarf_status swarf_gc_error(int code, const char *format, swarf_error *err, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 4)))
#endif
    ;

/* ---- the modal state ---------------------------------------------------- */

typedef struct {
  int motion;       /* 0 10 20 30 730 800 810..890 */
  int plane;        /* 170 180 190 */
  int units;        /* 200 (inch) or 210 (mm) */
  int distance;     /* 900 or 910 */
  int arc_distance; /* 901 or 911 */
  int feed_mode;    /* 930 940 950 */
  int cutter_comp;  /* 400 410 411 420 421 */
  int tool_length;  /* 430 431 490 */
  int coord_system; /* 540 550 ... 593 */
  int path_control; /* 610 611 640 */
  int retract;      /* 980 990 */
  int spindle_mode; /* 960 970 */
} swarf_gc_modal;

typedef struct {
  swarf_gc_modal modal;
  double pos[SWARF_NAXES];                            /* program coordinates, mm, degrees */
  double systems[SWARF_GC_NSYSTEMS][SWARF_NAXES];     /* G54..G59.3 origins, mm */
  double rotations[SWARF_GC_NSYSTEMS];                /* their XY rotations, degrees */
  double g92[SWARF_NAXES];                            /* G92/G52 offset in force, mm */
  double g92_saved[SWARF_NAXES];                      /* #5211-#5216 (kept by G92.2), mm */
  int g92_on;                                         /* #5210 */
  double g28[SWARF_NAXES], g30[SWARF_NAXES];          /* stored homes, machine mm */
  double tlo[SWARF_NAXES];                            /* tool length offset, mm */
  double feed;                                        /* mm/min, or inverse time (1/min) */
  double speed;                                       /* rpm, >= 0 */
  int spindle_dir;                                    /* +1 M3, -1 M4, 0 off */
  int tool;                                           /* in the spindle */
  int selected_tool;                                  /* last T */
  int ended;                                          /* M2 or M30 was executed */
  long units_line;                                    /* first G20/G21 run, 0: none */
  double cycle_r, cycle_q, cycle_p, cycle_k, cycle_z; /* sticky cycle words, mm */
  double cycle_clear;                                 /* G98 clearance of the running cycle */
  int cycle_r_set, cycle_q_set;
  double cycle_i, cycle_j; /* G87's sticky I J (mm); its K is cycle_k */
  double cycle_il;         /* the initial level: the drill axis at the first cycle block */
  int cycle_il_set;        /* cycle_il holds it (cleared when the motion leaves the cycles) */
  int cycle_after_g87;     /* the last cycle block was a G87 (rs274 then rapids to R first) */
  int dialect;             /* swarf_gcode_dialect */
  int motion01;            /* Fanuc/Haas: the last of G0-G3 (0 10 20 30), in force after G80 */
  int ext_system;          /* Fanuc/Haas: 1.. of G54.1 P (G154 P) in force, 0: none */
  double ext_origin[SWARF_NAXES]; /* its origin, mm (a copy of the parser's table) */
  double spline_pq[2];            /* G5: the last P Q (mm), for a G5 without I J */
  int spline_last;                /* the last motion was a G5 */
  /* Cutter radius compensation (ccomp.c): */
  int comp_side;       /* 0 off, SWARF_GC_COMP_LEFT or SWARF_GC_COMP_RIGHT */
  double comp_radius;  /* mm, >= 0 */
  int comp_first;      /* the next move is the entry move */
  double comp_pos[3];  /* the compensated tool point, program mm (pos: programmed) */
  int comp_exit;       /* after G40: the tool is at comp_pos until the next move */
  int arc_not_allowed; /* after G40: the next move must be straight */
  double comp_end[2];  /* plane: where the held move starts, as LinuxCNC records it */
  int comp_end_valid;  /* comp_end holds a point (LinuxCNC forgets it on a dequeue) */
} swarf_gc_state;

#define SWARF_GC_COMP_LEFT 1
#define SWARF_GC_COMP_RIGHT 2
/* Compensation moves the path (side set and a radius above zero). */
int swarf_gc_comp_active(const swarf_gc_state *st);

void swarf_gc_state_init(swarf_gc_state *st);
/* mm per program unit. */
double swarf_gc_scale(const swarf_gc_state *st);
/* Index 0..8 of the active work system. */
int swarf_gc_system_index(const swarf_gc_state *st);

/* ---- params.c: numbered, named and computed parameters ------------------ */

typedef struct swarf_gc_named swarf_gc_named;

typedef struct {
  double num[SWARF_GC_NPARAMS]; /* #0 unused */
  swarf_gc_named *globals;      /* #<_name> */
  swarf_gc_named *locals;       /* #<name> of the running sub (or main) */
  const swarf_gc_state *state;  /* for the parameters that mirror it */
  double value;                 /* #<_value>: last sub return */
  int value_returned;
  double length_unit; /* mm per unit of the parameters backing offsets (25.4: rs274's inches) */
} swarf_gc_params;

void swarf_gc_params_init(swarf_gc_params *ps);
void swarf_gc_params_clear(swarf_gc_params *ps);
/* A numbered parameter; the ranges that mirror the state read from it. */
double swarf_gc_param_get(const swarf_gc_params *ps, int index);
/* Sets a numbered parameter; ranges mirroring offsets write into `st`. */
void swarf_gc_param_set(swarf_gc_params *ps, swarf_gc_state *st, int index, double v);
/* A named parameter (lower-case, blanks removed): 0 if found, else -1. */
int swarf_gc_param_named(const swarf_gc_params *ps, const char *name, double *v);
int swarf_gc_param_set_named(swarf_gc_params *ps, const char *name, double v);
/* Swap the local named list (sub call and return); returns the old one. */
swarf_gc_named *swarf_gc_params_swap_locals(swarf_gc_params *ps, swarf_gc_named *locals);
void swarf_gc_named_free(swarf_gc_named *list);

/* ---- lexer.c: one line -> tokens ---------------------------------------- */

typedef enum {
  SWARF_GC_TOKEN_END,     /* no more tokens on the line */
  SWARF_GC_TOKEN_WORD,    /* a letter and its value */
  SWARF_GC_TOKEN_COMMENT, /* ( ... ) or ; to the end of the line */
  SWARF_GC_TOKEN_ASSIGN   /* #n = value or #<name> = value */
} swarf_gc_token_kind;

typedef struct {
  swarf_gc_token_kind kind;
  char letter;      /* words: upper case */
  double value;     /* words, assignments */
  int column;       /* 1-based column of the letter, '(' , ';' or '#' */
  const char *text; /* comments: the text inside, not owned */
  size_t text_len;
  int index;                     /* assignments: numbered target, 0 if named */
  char name[SWARF_GC_NAME_MAX];  /* assignments: named target */
  char word[SWARF_GC_WORD_TEXT]; /* words: as written, blanks removed */
} swarf_gc_token;

typedef struct {
  const char *line; /* not owned, no terminator needed */
  size_t len;
  size_t pos;
  const swarf_gc_params *params; /* values of #; NULL: parameters refused */
} swarf_gc_lexer;

void swarf_gc_lexer_init(swarf_gc_lexer *lx, const char *line, size_t len,
                         const swarf_gc_params *params);
/* The next token; SWARF_OK or a syntax error in `f`. */
int swarf_gc_lexer_next(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_error *f);
void swarf_gc_lexer_skip_blanks(swarf_gc_lexer *lx);
int swarf_gc_lexer_peek(swarf_gc_lexer *lx); /* next non-blank char, -1 at end */
/* A plain number at the lexer's position (no sign handling beyond LinuxCNC's). */
int swarf_gc_lexer_number(swarf_gc_lexer *lx, double *v, swarf_error *f);

/* ---- expr.c: values, parameters, [expressions] and functions ------------- */

/* A real value at the lexer's position: number, #param, [expr] or
 * function[...] (LinuxCNC's read_real_value). */
int swarf_gc_expr_value(swarf_gc_lexer *lx, double *v, swarf_error *f);
/* `#...` target of an assignment or of EXISTS: index (>0) or name. */
int swarf_gc_expr_param_ref(swarf_gc_lexer *lx, int *index, char name[SWARF_GC_NAME_MAX],
                            swarf_error *f);
/* A <name> at the lexer's position (after '<'? no: at '<'), lower-cased. */
int swarf_gc_expr_name(swarf_gc_lexer *lx, char name[SWARF_GC_NAME_MAX], swarf_error *f);

/* ---- codes.c: G and M codes and their modal groups ---------------------- */

/* G modal groups, numbered as in LinuxCNC. */
enum {
  SWARF_GC_GROUP_NONMODAL = 0,      /* G4 G10 G28 G30 G52 G53 G92 G92.1-3 */
  SWARF_GC_GROUP_MOTION = 1,        /* G0 G1 G2 G3 G73 G80-G89 */
  SWARF_GC_GROUP_PLANE = 2,         /* G17 G18 G19 */
  SWARF_GC_GROUP_DISTANCE = 3,      /* G90 G91 */
  SWARF_GC_GROUP_ARC_DISTANCE = 4,  /* G90.1 G91.1 */
  SWARF_GC_GROUP_FEED_MODE = 5,     /* G93 G94 G95 */
  SWARF_GC_GROUP_UNITS = 6,         /* G20 G21 */
  SWARF_GC_GROUP_CUTTER_COMP = 7,   /* G40 G41 G42 G41.1 G42.1 */
  SWARF_GC_GROUP_TOOL_LENGTH = 8,   /* G43 G43.1 G49 */
  SWARF_GC_GROUP_RETURN_MODE = 10,  /* G98 G99 */
  SWARF_GC_GROUP_COORD_SYSTEM = 12, /* G54-G59.3 */
  SWARF_GC_GROUP_PATH_CONTROL = 13, /* G61 G61.1 G64 */
  SWARF_GC_GROUP_SPINDLE_MODE = 14, /* G96 G97 */
  SWARF_GC_GROUP_LATHE = 15,        /* (G7 G8: later) */
  SWARF_GC_GROUP_VENDOR = 16,       /* Fanuc/Haas: G5.1 Q1, G8, G103, G187...: noted, no motion */
  SWARF_GC_NGROUPS = 17
};

/* M modal groups, numbered as in LinuxCNC. */
enum {
  SWARF_GC_MGROUP_STOP = 4,     /* M0 M1 M2 M30 M60 */
  SWARF_GC_MGROUP_IO = 5,       /* M62-M68 (no motion: accepted, ignored) */
  SWARF_GC_MGROUP_TOOL = 6,     /* M6 M61 */
  SWARF_GC_MGROUP_SPINDLE = 7,  /* M3 M4 M5 */
  SWARF_GC_MGROUP_COOLANT = 8,  /* M7 M8 M9 */
  SWARF_GC_MGROUP_OVERRIDE = 9, /* M48-M53 */
  SWARF_GC_MGROUP_USER = 10,    /* M100-M199, M4xx (REMAP-style user codes) */
  SWARF_GC_MGROUP_VENDOR = 11,  /* Fanuc/Haas machine codes (M29, M31, ...): noted, no motion */
  SWARF_GC_NMGROUPS = 12
};
#define SWARF_GC_MAX_M_PER_LINE 4 /* as LinuxCNC */

typedef struct {
  int code; /* tenths */
  int group;
  const char *later; /* NULL when supported; else what it is (for the message) */
} swarf_gc_code;

/* The entry for a G or M code in tenths, or NULL if the code is unknown
 * (a binary search: the tables are sorted by code). */
const swarf_gc_code *swarf_gc_g_code(int tenths);
const swarf_gc_code *swarf_gc_m_code(int tenths);

/* ---- block.c: the words of one line ------------------------------------- */

typedef struct {
  int present;
  double value; /* as written: program units, not yet converted */
  int column;
  char text[SWARF_GC_WORD_TEXT];
} swarf_gc_word;

typedef struct {
  int code; /* tenths, -1 when the group has no code on this line */
  int column;
  char text[SWARF_GC_WORD_TEXT];
} swarf_gc_code_word;

typedef struct {
  int index; /* > 0 numbered, 0 named */
  char name[SWARF_GC_NAME_MAX];
  double value;
} swarf_gc_assign;

/* The bit of a letter in swarf_gc_block.letters. */
#define SWARF_GC_LETTER(c) (1u << ((c) - 'A'))

typedef struct {
  swarf_gc_word words[26];                 /* by letter - 'A'; not G or M */
  unsigned letters;                        /* SWARF_GC_LETTER bits of the words present */
  swarf_gc_code_word g[SWARF_GC_NGROUPS];  /* by G modal group */
  swarf_gc_code_word m[SWARF_GC_NMGROUPS]; /* by M modal group */
  int m_count;
  int word_count; /* words of any letter, N included */
  swarf_gc_assign assigns[SWARF_GC_MAX_ASSIGN];
  int assign_count;
  const char *comment; /* last comment of the line, not owned */
  size_t comment_len;
  /* Set by check.c: */
  int motion;        /* motion this block makes (tenths), -1: none */
  int motion_column; /* motion word, else the first axis (or I J K) word */
} swarf_gc_block;

/* Reads every token of the line into `b`: repeated words, two codes of one
 * modal group, unknown or not-yet-supported codes and letters are errors. */
int swarf_gc_block_read(const char *line, size_t len, const swarf_gc_params *ps, swarf_gc_block *b,
                        swarf_error *f);

/* Shorthands for the words of a block (`letter`: 'A'..'Z'). */
static inline const swarf_gc_word *swarf_gc_block_word(const swarf_gc_block *b, char letter) {
  return &b->words[letter - 'A'];
}
static inline int swarf_gc_block_has(const swarf_gc_block *b, char letter) {
  return (b->letters & SWARF_GC_LETTER(letter)) != 0;
}
int swarf_gc_block_has_axis(const swarf_gc_block *b);

/* ---- check.c: the block against the state ------------------------------- */

int swarf_gc_block_check(swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f);

/* ---- canon.c: the calls a block makes ----------------------------------- */

typedef enum {
  SWARF_GC_CALL_TRAVERSE,
  SWARF_GC_CALL_FEED,
  SWARF_GC_CALL_ARC,
  SWARF_GC_CALL_DWELL,
  SWARF_GC_CALL_TOOL,
  SWARF_GC_CALL_TEXT /* any other canonical call: printed only */
} swarf_gc_call_kind;

typedef struct {
  swarf_gc_call_kind kind;
  swarf_move move; /* motions: machine frame, mm (program frame while held) */
  double prog[9];  /* motions: the values rs274 prints (program units) */
  int nprog;
  size_t text_at; /* TEXT: offset of the text in the out list's buffer */
  int turns;      /* arcs: rs274's signed rotation */
  double sweep;   /* held arcs: signed sweep as enqueued (radians, LinuxCNC's find_turn) */
  double dir[2];  /* held lines: programmed direction in the plane */
  int print;      /* motions: SWARF_GC_PRINT_* (how the canon shows it) */
} swarf_gc_call;

enum {
  SWARF_GC_PRINT_MOTION = 0, /* STRAIGHT_TRAVERSE, STRAIGHT_FEED, ARC_FEED */
  SWARF_GC_PRINT_PROBE = 1,  /* STRAIGHT_PROBE (G38.x) */
  SWARF_GC_PRINT_NONE = 2    /* a piece of a spline: its NURBS_FEED text was printed */
};
/* The origin (machine mm) and XY rotation (degrees) of the work system in force. */
const double *swarf_gc_origin(const swarf_gc_state *st);
double swarf_gc_rotation(const swarf_gc_state *st);

/* The calls of one block. calls[0, ready) are final and go out when the
 * block commits; calls[ready, count) are held (LinuxCNC's queue under
 * cutter compensation: a move waits for the next one, which may move its
 * end point) and carry the parser over to the next block.
 * The calls held by earlier blocks (`prefix`, owned by the parser, not
 * changed by the block) come between the two parts; they are copied in
 * only when the block touches them (swarf_gc_out_take_held), so that a long
 * run of held calls costs nothing per block. */
typedef struct swarf_gc_out swarf_gc_out;
struct swarf_gc_out {
  swarf_gc_call *calls;
  size_t count, cap, ready;
  char *text;
  size_t text_len, text_cap;
  const swarf_gc_out *prefix; /* earlier blocks' held calls, or NULL */
  size_t pending;             /* prefix calls not copied in yet */
  long line;                  /* source line stamped on the moves pushed */
  int want_text;              /* format TEXT calls (a canon callback is set) */
  int overflow;               /* out of memory or over the limit */
};

void swarf_gc_out_init(swarf_gc_out *o);
void swarf_gc_out_clear(swarf_gc_out *o);
void swarf_gc_out_reset(swarf_gc_out *o);
/* A text call (printf-style), e.g. "SET_FEED_RATE(10.0000)": queued
 * behind held calls, as LinuxCNC's enqueue_* calls are. */
void swarf_gc_out_text(swarf_gc_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* A text call that goes out at once, before held calls (MESSAGE,
 * SELECT_TOOL, USE_LENGTH_UNITS...: LinuxCNC does not queue them). */
void swarf_gc_out_text_now(swarf_gc_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* Starts a block's list: empty, after the calls `held` by earlier blocks. */
void swarf_gc_out_start(swarf_gc_out *o, const swarf_gc_out *held, long line);
/* Copies the earlier blocks' held calls in, to read or change them. */
void swarf_gc_out_take_held(swarf_gc_out *o);
/* Calls in the list, the earlier blocks' held ones included: call
 * swarf_gc_out_size(o) - o->pending is the one that was pushed at that size. */
static inline size_t swarf_gc_out_size(const swarf_gc_out *o) {
  return o->count + o->pending;
}
/* Appends copies of src's calls [from, count) to o, held. */
void swarf_gc_out_append_held(swarf_gc_out *o, const swarf_gc_out *src, size_t from);
/* Makes the held calls final with the offsets and unit of `st`. */
void swarf_gc_out_flush(swarf_gc_out *o, const swarf_gc_state *st);
/* A held straight motion or arc, in program mm (ccomp.c moves their ends). */
swarf_gc_call *swarf_gc_out_hold_line(swarf_gc_out *o, const swarf_gc_state *st,
                                      swarf_gc_call_kind kind, const double start[SWARF_NAXES],
                                      const double end[SWARF_NAXES], int column);
swarf_gc_call *swarf_gc_out_hold_arc(swarf_gc_out *o, const swarf_gc_state *st,
                                     const swarf_move *mv, int turns, int column);
/* The tool's position (program mm): pos, or the compensated point. */
void swarf_gc_tool_pos(const swarf_gc_state *st, double p[SWARF_NAXES]);
/* Plane axes (first, second, normal) of the state's plane, as rs274 prints. */
void swarf_gc_plane_axes(const swarf_gc_state *st, int ax[3]);
/* Straight motion from st->pos to `end` (program mm); kind TRAVERSE/FEED. */
void swarf_gc_out_straight(swarf_gc_out *o, const swarf_gc_state *st, swarf_gc_call_kind kind,
                           const double end[SWARF_NAXES], int column);
/* An arc: `mv` holds start, end, centre, normal, angle, rise in program mm;
 * `turns` is the signed rotation rs274 prints. */
void swarf_gc_out_arc(swarf_gc_out *o, const swarf_gc_state *st, const swarf_move *mv, int turns,
                      int column);
void swarf_gc_out_dwell(swarf_gc_out *o, const swarf_gc_state *st, double seconds, int column);
void swarf_gc_out_tool(swarf_gc_out *o, const swarf_gc_state *st, int column);
/* Program mm -> machine mm (G92, rotation, work offset, tool length). */
void swarf_gc_to_machine(const swarf_gc_state *st, const double p[SWARF_NAXES],
                         double m[SWARF_NAXES]);
/* Machine mm -> program mm. */
void swarf_gc_from_machine(const swarf_gc_state *st, const double m[SWARF_NAXES],
                           double p[SWARF_NAXES]);
/* Offsets and rotation calls for the active system. */
void swarf_gc_out_g5x(swarf_gc_out *o, const swarf_gc_state *st);
void swarf_gc_out_g92(swarf_gc_out *o, const swarf_gc_state *st);
void swarf_gc_out_tlo(swarf_gc_out *o, const swarf_gc_state *st);

/* ---- interp.c: execute a checked block ---------------------------------- */

#define SWARF_GC_NOTES_MAX 4 /* notes kept per block */
typedef struct {
  int n;
  int column[SWARF_GC_NOTES_MAX];
  char text[SWARF_GC_NOTES_MAX][200];
} swarf_gc_notes;

/* Adds a note (printf-style) to the block's list; they go out when the
 * block commits. Extra notes past SWARF_GC_NOTES_MAX are dropped. */
void swarf_gc_note(swarf_gc_notes *n, int column, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

#define SWARF_GC_NEXT (300 + 1) /* G54.1 P1..P300 (Fanuc), G154 P1..P99 (Haas) */

typedef struct {
  swarf_gc_params *params; /* read and written (param writes of G10 etc.) */
  swarf_gc_out *out;
  double (*tools)[2]; /* tool table by tool number: Z offset, diameter (mm) */
  int ntools;
  swarf_gc_notes *notes;      /* the block's notes */
  double (*ext)[SWARF_NAXES]; /* extended work offsets by P (mm) */
} swarf_gc_exec;

int swarf_gc_execute(const swarf_gc_block *b, swarf_gc_state *next, swarf_gc_exec *ex,
                     swarf_error *f);

/* grbl's homing cycle ($H): rapids in machine coordinates, Z to the home
 * first, then the other axes (offsets.c); no move for an axis already there. */
void swarf_gc_home_cycle(swarf_gc_state *st, swarf_gc_exec *ex, const double home[SWARF_NAXES],
                         int column);

/* ---- motion.c, offsets.c, cycle.c ---------------------------------------- */

/* The end point of the block's axis words (program mm, absolute). */
void swarf_gc_find_end(const swarf_gc_block *b, const swarf_gc_state *st, double end[SWARF_NAXES]);
int swarf_gc_motion(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f);
int swarf_gc_offsets(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                     swarf_error *f);
int swarf_gc_select_system(int code, swarf_gc_state *st, swarf_gc_exec *ex);
int swarf_gc_tool_length(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                         swarf_error *f);
int swarf_gc_cycle(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f);

/* ---- spline.c: G5 and G5.1 ------------------------------------------------ */

#define SWARF_GC_SPLINE_TOLERANCE 0.001 /* chord tolerance of a spline's lines, mm */
int swarf_gc_spline(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f);
/* G38.2-G38.5 (motion.c). */
int swarf_gc_probe(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex, swarf_error *f);
/* G54.1 P / G154 P (offsets.c). */
int swarf_gc_select_ext(const swarf_gc_block *b, int code, swarf_gc_state *st, swarf_gc_exec *ex,
                        swarf_error *f);

/* ---- arc.c: G2/G3 geometry ---------------------------------------------- */

/* Fills the arc fields of `mv` (start and end are set, program mm) for the
 * block's arc in the state's plane, with LinuxCNC's checks and tolerances;
 * *turns gets rs274's signed rotation. */
int swarf_gc_arc(const swarf_gc_block *b, const swarf_gc_state *st, swarf_move *mv, int *turns,
                 swarf_error *f);
/* Sweep (radians, in (0, 2 pi]) from start to end about the centre, plane
 * coordinates in mm, as LinuxCNC's motion planner takes it (one turn). */
double swarf_gc_arc_sweep(double s1, double s2, double e1, double e2, double c1, double c2,
                          int ccw);

/* ---- ccomp.c: cutter radius compensation -------------------------------- */

/* G40, G41, G42, G41.1, G42.1 of the block (execution order of group 7). */
int swarf_gc_comp_set(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                      swarf_error *f);
/* Refuses what LinuxCNC refuses while compensation is on (group 0, plane,
 * tool, offsets, path control codes of the block). */
int swarf_gc_comp_check(const swarf_gc_block *b, const swarf_gc_state *st, swarf_error *f);
/* A compensated G0/G1 to the programmed `end`, or G2/G3 (mv: programmed
 * start, end, centre and turns from arc.c). */
int swarf_gc_comp_straight(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                           const double end[SWARF_NAXES], swarf_error *f);
int swarf_gc_comp_arc(const swarf_gc_block *b, swarf_gc_state *st, swarf_gc_exec *ex,
                      const swarf_move *mv, int turns, swarf_error *f);

/* ---- oword.c: O-word control flow --------------------------------------- */

typedef struct swarf_gc_flow swarf_gc_flow;

/* Runs one ordinary (non-O) line, numbered `line`; the parser's block path. */
typedef int (*swarf_gc_line_fn)(void *ctx, const char *text, size_t len, long line);

swarf_gc_flow *swarf_gc_flow_new(swarf_gc_params *ps, swarf_gc_line_fn run, void *ctx);
void swarf_gc_flow_free(swarf_gc_flow *fl);
/* One line of the program as it streams in. On error, *column and the
 * fault say where (the line is `line` or a stored line: *err_line). */
int swarf_gc_flow_line(swarf_gc_flow *fl, const char *text, size_t len, long line, long *err_line,
                       swarf_error *f);
/* Where `o<name> call` looks for <name>.ngc when no such sub was defined
 * (borrowed: the parser owns the string). */
void swarf_gc_flow_set_path(swarf_gc_flow *fl, const char *dirs);
/* The bound on stored lines run (swarf_gcode_parser_set_work_limit). */
void swarf_gc_flow_set_limit(swarf_gc_flow *fl, long lines);
/* The parser's count of moves and arc turns beyond one a line, run by stored
 * lines (the work bound counts them with the lines: a loop of helixes or
 * pecks is bounded by its work, not its lines). */
void swarf_gc_flow_set_extra(swarf_gc_flow *fl, const long *extra);
/* Stored lines (a loop, a call) are running. */
int swarf_gc_flow_running(const swarf_gc_flow *fl);
/* A construct still open at the end of the program (0: none). */
long swarf_gc_flow_open_line(const swarf_gc_flow *fl);

/* The flow's line entry for fanuc.c (LinuxCNC programs with M98). */
int swarf_gc_parser_flow_line(swarf_gcode_parser *p, const char *text, size_t len, long line);

/* ---- parser.c: the parser itself (setup.c sets up its machine) ----------- */

#define SWARF_GC_NTOOLS 1000 /* tool numbers 1..999 */

struct swarf_gcode_parser {
  swarf_gcode_move_fn fn;
  void *user;
  swarf_gcode_canon_fn canon;
  void *canon_user;
  long seq;                 /* rs274's call counter */
  int canon_started;        /* the preamble was printed */
  swarf_gc_state states[2]; /* the committed state and the next block's copy */
  swarf_gc_state *state;    /* the committed one */
  swarf_gc_params params;
  swarf_gc_flow *flow;
  swarf_gc_out out;
  swarf_gc_out held; /* calls held back at the end of the last block (ccomp.c) */
  double tools[SWARF_GC_NTOOLS][2];
  long cur_line;       /* line of the block being run (stored lines too) */
  swarf_error error;   /* .file holds the program's name from the start */
  swarf_status status; /* first error, sticky */
  long lines;          /* lines read so far */
  long long bytes;     /* bytes of those lines, newlines included */
  int seen_code;       /* a non-blank line was read */
  int percent_open;    /* the program opened with a `%` line */
  int ended;           /* M2, M30 or a closing `%` */
  int finished;        /* swarf_gcode_parser_finish was called */
  char *partial;       /* the unterminated line so far */
  size_t partial_len, partial_cap;
  /* The machine's setup (swarf_gcode_parser_set_*): */
  double start[SWARF_NAXES]; /* controlled point at the start, machine mm, degrees */
  int params_set;            /* a parameter was set (the unit can no longer change) */
  int g92_restore;           /* #5210 = 1: the G92 offset #5211-#5216 is in force */
  /* The dialect and the operator's switches (dialect.c): */
  int block_delete;  /* skip `/` blocks */
  int fragment;      /* the text need not end (swarf_gcode_parser_set_fragment) */
  long work_limit;   /* lines run by loops, calls and subprograms, at most */
  long work_extra;   /* and the moves and arc turns beyond one a line they ran */
  int fanuc_running; /* a Fanuc/Haas program kept whole is running */
  char *subpath;     /* ':'-separated directories of subroutine files, or NULL */
  swarf_gcode_note_fn note_fn;
  void *note_user;
  swarf_gc_notes notes; /* the running block's */
  char *scratch;        /* a line rewritten (block delete, Fanuc macros) */
  size_t scratch_cap;
  struct swarf_gc_fanuc *fanuc;           /* Fanuc/Haas programs: the whole program (fanuc.c) */
  double ext[SWARF_GC_NEXT][SWARF_NAXES]; /* G54.1 P / G154 P origins, mm */
};

/* ---- dialect.c: what differs by dialect ----------------------------------- */

static inline int swarf_gc_fanuc_like(const swarf_gc_state *st) {
  return st->dialect == SWARF_GCODE_DIALECT_FANUC || st->dialect == SWARF_GCODE_DIALECT_HAAS;
}
/* Hands a note to the listener (line: the parser's current line). */
void swarf_gc_parser_note(swarf_gcode_parser *p, int column, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* A copy of `text` in the parser's scratch buffer (NULL: out of memory). */
char *swarf_gc_scratch(swarf_gcode_parser *p, const char *text, size_t n);
/* grbl: refuses what grbl 1.1 does not have (a G or M code, a letter). */
int swarf_gc_grbl_check(const swarf_gc_block *b, swarf_error *f);
/* A G or M code's entry in a dialect other than LinuxCNC (NULL: as LinuxCNC). */
const swarf_gc_code *swarf_gc_dialect_g(int dialect, int tenths);
const swarf_gc_code *swarf_gc_dialect_m(int dialect, int tenths);
/* What a vendor code does, for its note ("chip conveyor forward"), or NULL. */
const char *swarf_gc_vendor_m_name(int dialect, int code);

/* Runs one ordinary line through the block path (parser.c): block delete,
 * then read, check, execute, commit. */
int swarf_gc_parser_run_line(void *ctx, const char *text, size_t len, long line);

/* ---- fanuc.c: Fanuc and Haas programs (stored whole, then run) ------------ */

typedef struct swarf_gc_fanuc swarf_gc_fanuc;
swarf_gc_fanuc *swarf_gc_fanuc_new(swarf_gcode_parser *p);
void swarf_gc_fanuc_free(swarf_gc_fanuc *fa);
/* Keeps one line of the program. */
int swarf_gc_fanuc_store(swarf_gc_fanuc *fa, const char *text, size_t len, long line,
                         swarf_error *f);
/* Runs the program kept; *err_line says where a fault is. */
int swarf_gc_fanuc_run(swarf_gc_fanuc *fa, long *err_line, swarf_error *f);

#endif
