/* gcode_private.h -- the G-code front end's insides, shared by its files only.
 *
 * The pipeline, one line at a time (parse, check, commit, as grbl does):
 *   parser.c  streams bytes into lines; `%`, block delete, program end.
 *   lexer.c   one line -> tokens (words with their columns, comments).
 *   block.c   tokens -> a block: every word of the line, each G and M code
 *             filed under its modal group (codes.c holds the tables).
 *   check.c   the block against the modal state: what motion it asks for,
 *             which words are out of place. Nothing is changed.
 *   interp.c  executes a checked block on a COPY of the state, in LinuxCNC's
 *             order, and collects the moves it makes (arc.c does arcs).
 *             The parser commits the copy and hands the moves out only when
 *             the whole block succeeded: a rejected block changes nothing.
 *   fault.c   the error record every step fills.
 *
 * Internal units: mm, degrees, mm/min. G codes and M codes are kept as
 * integers in tenths (G91.1 -> 911, M6 -> 60) so that G38.2 and G38 differ.
 */
#ifndef SWARF_GCODE_PRIVATE_H
#define SWARF_GCODE_PRIVATE_H

#include <stddef.h>

#include "gcode.h"

#define SWARF_GC_MM_PER_INCH 25.4
#define SWARF_GC_LINE_MAX ((size_t)1 << 20) /* longest line accepted, bytes */
#define SWARF_GC_NUMBER_MAX 1e9             /* largest magnitude of a word's value */
#define SWARF_GC_WORD_TEXT 40               /* a word as written, for messages */

/* ---- fault.c: what went wrong, and where on the line -------------------- */

typedef struct {
  int status; /* a swarf_gcode_status */
  int column; /* 1-based column on the current line */
  char message[256];
} swarf_gc_fault;

/* Fills `f` and returns `status`, so callers can `return swarf_gc_fail(...)`. */
int swarf_gc_fail(swarf_gc_fault *f, int status, int column, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* ---- lexer.c: one line -> tokens ---------------------------------------- */

typedef enum {
  SWARF_GC_TOKEN_END,    /* no more tokens on the line */
  SWARF_GC_TOKEN_WORD,   /* a letter and its value */
  SWARF_GC_TOKEN_COMMENT /* ( ... ) or ; to the end of the line */
} swarf_gc_token_kind;

/* How the value of a word was written. Only numbers exist in this dialect;
 * parameters (#1) and expressions ([1+2]) will be further kinds. */
typedef enum { SWARF_GC_VALUE_NUMBER } swarf_gc_value_kind;

typedef struct {
  swarf_gc_token_kind kind;
  char letter;                    /* words: upper case */
  swarf_gc_value_kind value_kind; /* words */
  double value;                   /* words */
  int column;                     /* 1-based column of the letter, '(' or ';' */
  const char *text;               /* comments: the text inside, not owned */
  size_t text_len;
  char word[SWARF_GC_WORD_TEXT]; /* words: as written, blanks removed */
} swarf_gc_token;

typedef struct {
  const char *line; /* not owned, no terminator needed */
  size_t len;
  size_t pos;
} swarf_gc_lexer;

void swarf_gc_lexer_init(swarf_gc_lexer *lx, const char *line, size_t len);
/* The next token; SWARF_GCODE_OK or a syntax error in `f`. */
int swarf_gc_lexer_next(swarf_gc_lexer *lx, swarf_gc_token *tok, swarf_gc_fault *f);

/* ---- codes.c: G and M codes and their modal groups ---------------------- */

/* G modal groups, numbered as in LinuxCNC. */
enum {
  SWARF_GC_GROUP_NONMODAL = 0,      /* G4 G53 (G10 G28 G30 G52 G92...: later) */
  SWARF_GC_GROUP_MOTION = 1,        /* G0 G1 G2 G3 G80 (G33 G38.x G73 G76 G81-G89: later) */
  SWARF_GC_GROUP_PLANE = 2,         /* G17 G18 G19 (G17.1 G18.1 G19.1: later) */
  SWARF_GC_GROUP_DISTANCE = 3,      /* G90 G91 */
  SWARF_GC_GROUP_ARC_DISTANCE = 4,  /* G90.1 G91.1 */
  SWARF_GC_GROUP_FEED_MODE = 5,     /* G94 (G93 G95: later) */
  SWARF_GC_GROUP_UNITS = 6,         /* G20 G21 */
  SWARF_GC_GROUP_CUTTER_COMP = 7,   /* G40 (G41 G42 G41.1 G42.1: later) */
  SWARF_GC_GROUP_TOOL_LENGTH = 8,   /* G43 G49 (G43.1 G43.2: later) */
  SWARF_GC_GROUP_RETURN_MODE = 10,  /* (G98 G99: later) */
  SWARF_GC_GROUP_COORD_SYSTEM = 12, /* G54 (G55-G59.3: later) */
  SWARF_GC_GROUP_PATH_CONTROL = 13, /* G61 G61.1 G64 */
  SWARF_GC_GROUP_SPINDLE_MODE = 14, /* G97 (G96: later) */
  SWARF_GC_GROUP_LATHE = 15,        /* (G7 G8: later) */
  SWARF_GC_NGROUPS = 16
};

/* M modal groups, numbered as in LinuxCNC. */
enum {
  SWARF_GC_MGROUP_STOP = 4,     /* M0 M1 M2 M30 M60 */
  SWARF_GC_MGROUP_IO = 5,       /* (M62-M68: later) */
  SWARF_GC_MGROUP_TOOL = 6,     /* M6 (M61: later) */
  SWARF_GC_MGROUP_SPINDLE = 7,  /* M3 M4 M5 (M19: later) */
  SWARF_GC_MGROUP_COOLANT = 8,  /* M7 M8 M9 */
  SWARF_GC_MGROUP_OVERRIDE = 9, /* (M48-M53: later) */
  SWARF_GC_MGROUP_USER = 10,    /* (M100-M199: later) */
  SWARF_GC_NMGROUPS = 11
};
#define SWARF_GC_MAX_M_PER_LINE 4 /* as LinuxCNC */

typedef struct {
  int code; /* tenths */
  int group;
  const char *later; /* NULL when supported; else what it is (for the message) */
} swarf_gc_code;

/* The entry for a G or M code in tenths, or NULL if the code is unknown. */
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
  swarf_gc_word words[26];                 /* by letter - 'A'; not G or M */
  swarf_gc_code_word g[SWARF_GC_NGROUPS];  /* by G modal group */
  swarf_gc_code_word m[SWARF_GC_NMGROUPS]; /* by M modal group */
  int m_count;
  int word_count; /* words of any letter, N included */
  /* Set by check.c: */
  int motion;        /* motion this block makes (tenths), -1: none */
  int motion_column; /* motion word, else the first axis (or I J K) word */
} swarf_gc_block;

/* Reads every token of the line into `b`: repeated words, two codes of one
 * modal group, unknown or not-yet-supported codes and letters are errors. */
int swarf_gc_block_read(const char *line, size_t len, swarf_gc_block *b, swarf_gc_fault *f);

/* Shorthands for the words of a block. */
const swarf_gc_word *swarf_gc_block_word(const swarf_gc_block *b, char letter);
int swarf_gc_block_has(const swarf_gc_block *b, char letter);

/* ---- the modal state ---------------------------------------------------- */

typedef struct {
  int motion;       /* 0 10 20 30 or 800 (G80: no motion) */
  int plane;        /* 170 180 190 */
  int units;        /* 200 (inch) or 210 (mm) */
  int distance;     /* 900 or 910 */
  int arc_distance; /* 901 or 911 */
  int feed_mode;    /* 940 */
  int cutter_comp;  /* 400 */
  int tool_length;  /* 430 or 490 (no offset is applied in this version) */
  int coord_system; /* 540 */
  int path_control; /* 610 611 640 */
} swarf_gc_modal;

typedef struct {
  swarf_gc_modal modal;
  double pos[SWARF_NAXES]; /* mm, degrees */
  double feed;             /* mm/min */
  double speed;            /* rpm, >= 0 */
  int spindle_dir;         /* +1 M3, -1 M4, 0 off */
  int tool;                /* in the spindle */
  int selected_tool;       /* last T */
  int ended;               /* M2 or M30 was executed */
} swarf_gc_state;

void swarf_gc_state_init(swarf_gc_state *st);

/* ---- check.c: the block against the state ------------------------------- */

/* Sets b->motion and b->motion_column, and checks the block as LinuxCNC's
 * enhance_block and check_items do. Changes nothing else. */
int swarf_gc_block_check(swarf_gc_block *b, const swarf_gc_state *st, swarf_gc_fault *f);

/* ---- interp.c: execute a checked block ---------------------------------- */

#define SWARF_GC_MAX_MOVES 3 /* tool change, dwell, motion */

typedef struct {
  swarf_move moves[SWARF_GC_MAX_MOVES];
  int count;
} swarf_gc_moves;

/* Runs a checked block on `next` (a copy of the state the caller made) and
 * appends the moves it makes to `out` (line numbers left for the caller).
 * On error `next` is garbage and must be dropped. */
int swarf_gc_execute(const swarf_gc_block *b, swarf_gc_state *next, swarf_gc_moves *out,
                     swarf_gc_fault *f);

/* ---- arc.c: G2/G3 geometry ---------------------------------------------- */

/* Fills the arc fields of `mv` (start and end are set) for the block's arc in
 * the state's plane, with LinuxCNC's checks and tolerances. */
int swarf_gc_arc(const swarf_gc_block *b, const swarf_gc_state *st, swarf_move *mv,
                 swarf_gc_fault *f);

#endif
