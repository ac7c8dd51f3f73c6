/* SPDX-License-Identifier: MPL-2.0 */
/* dialect.c -- what differs between LinuxCNC, Fanuc, Haas and grbl, and the
 * parser's switches (dialect, block delete, subroutine path, notes).
 *
 * The block path is LinuxCNC's for every dialect; this file holds the
 * tables that change what a code means in another dialect (a Fanuc code
 * that LinuxCNC lacks, a vendor M code accepted without motion, the codes
 * grbl 1.1 has) and the setters of gcode.h. Program structure (O program
 * numbers, M98/M99, G65, GOTO) is fanuc.c's. The tables are constant data;
 * the parser owns the strings set here.
 */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"

static const char *const names[] = {"linuxcnc", "fanuc", "haas", "grbl"};

int swarf_gcode_dialect_from_name(const char *name, swarf_gcode_dialect *out) {
  for (int i = 0; name != NULL && i < 4; i++)
    if (strcmp(name, names[i]) == 0) {
      if (out != NULL) *out = (swarf_gcode_dialect)i;
      return 0;
    }
  return -1;
}

const char *swarf_gcode_dialect_name(swarf_gcode_dialect d) {
  return (int)d >= 0 && (int)d < 4 ? names[d] : NULL;
}

/* The switches are set before the program starts, as setup.c's calls. */
static swarf_status check_setup(const swarf_gcode_parser *p, swarf_error *err) {
  if (p == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_SETUP_NO_PARSER, err);
  if (p->lines > 0 || p->partial_len > 0) return SWARF_GC_ERROR(SWARF_GCODE_E_SETUP_STARTED, err);
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_set_dialect(swarf_gcode_parser *p, swarf_gcode_dialect d,
                                            swarf_error *err) {
  swarf_status s = check_setup(p, err);
  if (s != SWARF_OK) return s;
  if ((int)d < 0 || (int)d > 3) return SWARF_GC_ERROR(SWARF_GCODE_E_DIALECT_VALUE, err, (int)d);
  p->states[0].dialect = p->states[1].dialect = (int)d;
  /* Fanuc and Haas start in G98 (initial level), rs274 in G99. */
  p->state->modal.retract =
      d == SWARF_GCODE_DIALECT_FANUC || d == SWARF_GCODE_DIALECT_HAAS ? 980 : 990;
  if (d == SWARF_GCODE_DIALECT_FANUC || d == SWARF_GCODE_DIALECT_HAAS) {
    if (p->fanuc == NULL) p->fanuc = swarf_gc_fanuc_new(p);
    if (p->fanuc == NULL) return SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, err);
  }
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_set_block_delete(swarf_gcode_parser *p, int on, swarf_error *err) {
  swarf_status s = check_setup(p, err);
  if (s == SWARF_OK) p->block_delete = on != 0;
  return s;
}

swarf_status swarf_gcode_parser_set_fragment(swarf_gcode_parser *p, int on, swarf_error *err) {
  swarf_status s = check_setup(p, err);
  if (s == SWARF_OK) p->fragment = on != 0;
  return s;
}

swarf_status swarf_gcode_parser_set_work_limit(swarf_gcode_parser *p, long lines,
                                               swarf_error *err) {
  swarf_status s = check_setup(p, err);
  if (s != SWARF_OK) return s;
  if (lines < 1 || lines > SWARF_GCODE_WORK_LIMIT_MAX)
    return SWARF_GC_ERROR(SWARF_GCODE_E_WORK_LIMIT_VALUE, err, lines, SWARF_GCODE_WORK_LIMIT_MAX);
  p->work_limit = lines;
  swarf_gc_flow_set_limit(p->flow, lines);
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_set_subroutine_path(swarf_gcode_parser *p, const char *dirs,
                                                    swarf_error *err) {
  swarf_status s = check_setup(p, err);
  char *copy = NULL;
  if (s != SWARF_OK) return s;
  if (dirs != NULL && (copy = malloc(strlen(dirs) + 1)) == NULL)
    return SWARF_GC_ERROR(SWARF_GCODE_E_OUT_OF_MEMORY, err);
  if (copy != NULL) strcpy(copy, dirs);
  free(p->subpath);
  p->subpath = copy;
  swarf_gc_flow_set_path(p->flow, copy);
  return SWARF_OK;
}

swarf_status swarf_gcode_parser_set_notes(swarf_gcode_parser *p, swarf_gcode_note_fn fn,
                                          void *user) {
  if (p == NULL) return SWARF_ERR_ARG;
  if (p->lines > 0) return SWARF_ERR_STATE;
  p->note_fn = fn;
  p->note_user = user;
  return SWARF_OK;
}

void swarf_gc_note(swarf_gc_notes *n, int column, const char *fmt, ...) {
  va_list ap;
  if (n == NULL || n->n >= SWARF_GC_NOTES_MAX) return;
  va_start(ap, fmt);
  vsnprintf(n->text[n->n], sizeof n->text[0], fmt, ap);
  va_end(ap);
  n->column[n->n++] = column;
}

void swarf_gc_parser_note(swarf_gcode_parser *p, int column, const char *fmt, ...) {
  char text[240];
  va_list ap;
  if (p->note_fn == NULL) return;
  va_start(ap, fmt);
  vsnprintf(text, sizeof text, fmt, ap);
  va_end(ap);
  p->note_fn(p->cur_line, column, text, p->note_user);
}

char *swarf_gc_scratch(swarf_gcode_parser *p, const char *text, size_t n) {
  if (n + 1 > p->scratch_cap) {
    size_t cap = n + 1 > 256 ? n + 1 : 256;
    char *grown = realloc(p->scratch, cap);
    if (grown == NULL) return NULL;
    p->scratch = grown;
    p->scratch_cap = cap;
  }
  memcpy(p->scratch, text, n);
  p->scratch[n] = '\0';
  return p->scratch;
}

/* ---- Fanuc and Haas codes ------------------------------------------------ */

/* Codes whose meaning differs from LinuxCNC's (sorted by code). `later`:
 * a real code of theirs that swarf refuses, saying what it is. */
static const swarf_gc_code fanuc_g[] = {
    {50, SWARF_GC_GROUP_VENDOR, NULL},                       /* G05 P10000: HPCC (high speed) */
    {51, SWARF_GC_GROUP_VENDOR, NULL},                       /* G05.1 Q1: AI contour control */
    {80, SWARF_GC_GROUP_VENDOR, NULL},                       /* G08 P1: look-ahead */
    {120, SWARF_GC_GROUP_MOTION, "circular pocket milling"}, /* Haas G12 */
    {130, SWARF_GC_GROUP_MOTION, "circular pocket milling"}, /* Haas G13 */
    {150, SWARF_GC_GROUP_VENDOR, "polar coordinates"},       /* G15/G16 */
    {160, SWARF_GC_GROUP_VENDOR, "polar coordinates"},
    {434, SWARF_GC_GROUP_TOOL_LENGTH, "tool centre point control"},
    {470, SWARF_GC_GROUP_MOTION, "engraving"}, /* Haas G47 */
    {500, SWARF_GC_GROUP_VENDOR, "scaling"},   /* G50/G51 */
    {510, SWARF_GC_GROUP_VENDOR, "scaling"},
    {541, SWARF_GC_GROUP_COORD_SYSTEM, NULL},            /* G54.1 P: extended work offsets */
    {680, SWARF_GC_GROUP_VENDOR, "coordinate rotation"}, /* G68/G69 */
    {690, SWARF_GC_GROUP_VENDOR, "coordinate rotation"},
    {740, SWARF_GC_GROUP_MOTION, NULL},              /* G74: counter tapping */
    {760, SWARF_GC_GROUP_MOTION, NULL},              /* G76: fine boring */
    {1030, SWARF_GC_GROUP_VENDOR, NULL},             /* Haas G103: block look-ahead */
    {1500, SWARF_GC_GROUP_MOTION, "pocket milling"}, /* Haas G150 */
    {1540, SWARF_GC_GROUP_COORD_SYSTEM, NULL},       /* Haas G154 P: extended offsets */
    {1870, SWARF_GC_GROUP_VENDOR, NULL},             /* Haas G187: smoothness */
};

static const swarf_gc_code *find(const swarf_gc_code *t, size_t n, int tenths) {
  for (size_t i = 0; i < n; i++)
    if (t[i].code == tenths) return &t[i];
  return NULL;
}

const swarf_gc_code *swarf_gc_dialect_g(int dialect, int tenths) {
  if (dialect != SWARF_GCODE_DIALECT_FANUC && dialect != SWARF_GCODE_DIALECT_HAAS) return NULL;
  if (dialect == SWARF_GCODE_DIALECT_FANUC && tenths == 1540) return NULL;
  return find(fanuc_g, sizeof fanuc_g / sizeof fanuc_g[0], tenths);
}

/* M codes that keep LinuxCNC's meaning in Fanuc and Haas programs; every
 * other M code is the machine builder's: accepted, no motion, a note. */
static int fanuc_keeps_m(int tenths) {
  static const int keep[] = {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 190, 300};
  for (size_t i = 0; i < sizeof keep / sizeof keep[0]; i++)
    if (keep[i] == tenths) return 1;
  return 0;
}

const swarf_gc_code *swarf_gc_dialect_m(int dialect, int tenths) {
  static const swarf_gc_code vendor = {0, SWARF_GC_MGROUP_VENDOR, NULL};
  static const swarf_gc_code haas_m16 = {60, SWARF_GC_MGROUP_TOOL, NULL};
  if (dialect == SWARF_GCODE_DIALECT_GRBL) return tenths == 560 ? &vendor : NULL;
  if (dialect != SWARF_GCODE_DIALECT_FANUC && dialect != SWARF_GCODE_DIALECT_HAAS) return NULL;
  if (dialect == SWARF_GCODE_DIALECT_HAAS && tenths == 160) return &haas_m16;
  if (fanuc_keeps_m(tenths)) return NULL;
  return &vendor;
}

/* Haas's mill M codes (Haas Mill Operator's Manual, "M-codes"). */
static const struct {
  int code;
  const char *what;
} haas_m[] = {
    {10, "4th axis brake on"},
    {11, "4th axis brake release"},
    {12, "5th axis brake on"},
    {13, "5th axis brake release"},
    {21, "optional user M with M-Fin"},
    {29, "set output relay with M-Fin"},
    {31, "chip auger forward"},
    {33, "chip auger stop"},
    {34, "coolant spigot increment"},
    {35, "coolant spigot decrement"},
    {36, "pallet part ready"},
    {39, "rotate tool turret"},
    {41, "low gear override"},
    {42, "high gear override"},
    {46, "jump if pallet loaded (not taken)"},
    {48, "check validity of current program"},
    {49, "set pallet status"},
    {50, "pallet change"},
    {59, "set output relay"},
    {69, "clear output relay"},
    {75, "set G35 or G136 reference point"},
    {76, "control display inactive"},
    {77, "control display active"},
    {78, "alarm if skip signal found"},
    {79, "alarm if skip signal not found"},
    {80, "automatic door open"},
    {81, "automatic door close"},
    {82, "tool unclamp"},
    {83, "automatic air gun on"},
    {84, "automatic air gun off"},
    {86, "tool clamp"},
    {88, "through-spindle coolant on"},
    {89, "through-spindle coolant off"},
    {95, "sleep mode"},
    {96, "jump if no input (not taken)"},
    {104, "probe arm extend"},
    {105, "probe arm retract"},
    {109, "interactive user input"},
    {130, "display media"},
    {131, "cancel display media"},
    {138, "spindle speed variation on"},
    {139, "spindle speed variation off"},
    {158, "mist condenser on"},
    {159, "mist condenser off"},
};

const char *swarf_gc_vendor_m_name(int dialect, int code) {
  if (dialect == SWARF_GCODE_DIALECT_GRBL) return "parking motion override (grbl M56)";
  if (dialect == SWARF_GCODE_DIALECT_FANUC)
    return code == 29 ? "rigid tapping mode" : "a machine builder's M code";
  for (size_t i = 0; i < sizeof haas_m / sizeof haas_m[0]; i++)
    if (haas_m[i].code == code) return haas_m[i].what;
  if (code >= 21 && code <= 28) return "optional user M with M-Fin";
  if (code >= 51 && code <= 58) return "set optional user M";
  if (code >= 61 && code <= 68) return "clear optional user M";
  return "a Haas M code";
}

/* ---- grbl 1.1 ------------------------------------------------------------- */

/* grbl 1.1's G codes (its wiki, "Grbl v1.1 Commands", supported G-codes). */
static int grbl_g(int tenths) {
  static const int g[] = {0,   10,  20,  30,  40,  100, 170, 180, 190, 200, 210, 280, 281,
                          300, 301, 382, 383, 384, 385, 400, 431, 490, 530, 540, 550, 560,
                          570, 580, 590, 610, 800, 900, 910, 911, 920, 921, 930, 940};
  for (size_t i = 0; i < sizeof g / sizeof g[0]; i++)
    if (g[i] == tenths) return 1;
  return 0;
}

/* Its M codes: M0 M1 M2 M30, M3 M4 M5, M7 M8 M9, M56; M6 and the T word
 * are accepted as a tool change (no table: lengths are the simulator's). */
static int grbl_m(int tenths) {
  static const int m[] = {0, 10, 20, 300, 30, 40, 50, 60, 70, 80, 90, 560};
  for (size_t i = 0; i < sizeof m / sizeof m[0]; i++)
    if (m[i] == tenths) return 1;
  return 0;
}

int swarf_gc_grbl_check(const swarf_gc_block *b, swarf_error *f) {
  static const char letters[] = "FIJKLNPRSTXYZ";
  for (int g = 0; g < SWARF_GC_NGROUPS; g++)
    if (b->g[g].code >= 0 && !grbl_g(b->g[g].code))
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_DIALECT_CODE, b->g[g].column, b->g[g].text);
  for (int m = 0; m < SWARF_GC_NMGROUPS; m++)
    if (b->m[m].code >= 0 && !grbl_m(b->m[m].code))
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_DIALECT_CODE, b->m[m].column, b->m[m].text);
  for (int i = 0; i < 26; i++)
    if (b->words[i].present && strchr(letters, 'A' + i) == NULL)
      return SWARF_GC_FAIL(f, SWARF_GCODE_E_DIALECT_LETTER, b->words[i].column, b->words[i].text,
                           'A' + i);
  if (b->g[SWARF_GC_GROUP_NONMODAL].code == 100) {
    const swarf_gc_word *l = swarf_gc_block_word(b, 'L');
    int lv = l->present ? (int)(l->value + 0.5) : 0;
    if (lv != 2 && lv != 20) return SWARF_GC_FAIL(f, SWARF_GCODE_E_DIALECT_G10, b->g[0].column, lv);
  }
  return SWARF_OK;
}
