/* SPDX-License-Identifier: MPL-2.0 */
/* test_conformance.c -- swarf's moves against LinuxCNC's own canonical output.
 *
 * For each real CAM file this version supports, the motion calls that
 * LinuxCNC's `rs274 -g` printed (real/canon/<file>.canon.xz, see its README)
 * are compared with the moves swarf emits: same count, same order, same kind,
 * end points, and for arcs the centre, rotation (sign = sense, magnitude =
 * turns) and the end on the third axis; all within 1e-4 program units
 * (canon prints 4 decimals; swarf's mm are turned back into inches where the
 * canon is in inches); these files have no offsets, so machine-frame moves
 * and program coordinates coincide. Then every real file (all 21) through
 * the canon listener: its printed motion calls against rs274's, call for call.
 *
 * Usage: test_conformance <conformance-dir>. A missing folder fails.
 * The canon is read with liblzma when it was found at configure time, else
 * with the xz program.
 */
#define _POSIX_C_SOURCE 200809L /* popen, strtok_r */
#ifdef SWARF_HAVE_LZMA
#include <lzma.h>
#endif
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "canon_compare.h"
#include "check.h"
#include "gcode.h"

#define TOL 1e-4
#define TWO_PI 6.283185307179586476925286766559

typedef enum { CANON_TRAVERSE, CANON_FEED, CANON_ARC, CANON_DWELL, CANON_OTHER } canon_kind;

typedef struct {
  canon_kind kind;
  double v[9];
  int nv;
  double scale; /* mm per canon unit at this call */
  long text_line;
} canon_call;

typedef struct {
  canon_call *calls;
  size_t n, cap;
} canon_list;

/* ---- reading the .xz canon --------------------------------------------- */

#ifdef SWARF_HAVE_LZMA
/* The whole decompressed text (NUL-terminated), or NULL. */
static char *read_xz(const char *path, size_t *out_len) {
  FILE *in = fopen(path, "rb");
  lzma_stream strm = LZMA_STREAM_INIT;
  uint8_t inbuf[65536];
  size_t cap = 1 << 20, len = 0;
  char *out = malloc(cap);
  lzma_ret ret = LZMA_OK;
  if (in == NULL || out == NULL || lzma_stream_decoder(&strm, UINT64_MAX, 0) != LZMA_OK) {
    if (in) fclose(in);
    free(out);
    return NULL;
  }
  while (ret == LZMA_OK) {
    if (strm.avail_in == 0 && !feof(in)) {
      strm.next_in = inbuf;
      strm.avail_in = fread(inbuf, 1, sizeof inbuf, in);
    }
    if (cap - len < 65536) out = realloc(out, cap *= 2);
    strm.next_out = (uint8_t *)out + len;
    strm.avail_out = cap - len - 1;
    ret = lzma_code(&strm, feof(in) ? LZMA_FINISH : LZMA_RUN);
    len = cap - 1 - strm.avail_out;
  }
  lzma_end(&strm);
  fclose(in);
  if (ret != LZMA_STREAM_END) {
    free(out);
    return NULL;
  }
  out[len] = '\0';
  *out_len = len;
  return out;
}
#else
/* Without liblzma: the xz program. */
static char *read_xz(const char *path, size_t *out_len) {
  char command[1200];
  size_t cap = 1 << 20, len = 0, got;
  char *out = malloc(cap);
  FILE *in;
  if (strchr(path, '\'') != NULL) return NULL;
  snprintf(command, sizeof command, "xz -dc '%s'", path);
  in = popen(command, "r");
  if (in == NULL || out == NULL) {
    if (in) pclose(in);
    free(out);
    return NULL;
  }
  while ((got = fread(out + len, 1, cap - len - 1, in)) > 0)
    if ((len += got) == cap - 1) out = realloc(out, cap *= 2);
  if (pclose(in) != 0 || len == 0) {
    free(out);
    return NULL;
  }
  out[len] = '\0';
  *out_len = len;
  return out;
}
#endif

static void push(canon_list *l, const canon_call *c) {
  if (l->n == l->cap) {
    l->cap = l->cap ? 2 * l->cap : 1024;
    l->calls = realloc(l->calls, l->cap * sizeof *l->calls);
  }
  l->calls[l->n++] = *c;
}

static int parse_args(const char *open, double *v) {
  int n = 0;
  const char *s = open + 1;
  char *end;
  while (n < 9) {
    v[n] = strtod(s, &end);
    if (end == s) break;
    n++;
    s = end;
    while (*s == ' ' || *s == ',')
      s++;
  }
  return n;
}

static void parse_canon_line(const char *line, double *scale, long text_line, canon_list *l) {
  static const struct {
    const char *name;
    canon_kind kind;
  } names[] = {
      {"STRAIGHT_TRAVERSE(", CANON_TRAVERSE},
      {"STRAIGHT_FEED(", CANON_FEED},
      {"ARC_FEED(", CANON_ARC},
      {"DWELL(", CANON_DWELL},
      {"STRAIGHT_PROBE(", CANON_OTHER},
      {"RIGID_TAP(", CANON_OTHER},
      {"NURBS_FEED(", CANON_OTHER},
  };
  const char *p;
  if (strstr(line, "USE_LENGTH_UNITS(CANON_UNITS_INCHES)")) *scale = 25.4;
  if (strstr(line, "USE_LENGTH_UNITS(CANON_UNITS_MM)")) *scale = 1.0;
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
    if ((p = strstr(line, names[i].name)) != NULL && !strstr(line, "COMMENT(") &&
        !strstr(line, "MESSAGE(")) {
      canon_call c;
      memset(&c, 0, sizeof c);
      c.kind = names[i].kind;
      c.nv = parse_args(strchr(p, '('), c.v);
      c.scale = *scale;
      c.text_line = text_line;
      push(l, &c);
      return;
    }
  }
}

static int load_canon(const char *path, canon_list *l) {
  size_t len;
  char *text = read_xz(path, &len), *line, *save = NULL;
  double scale = 1.0;
  long n = 0;
  if (text == NULL) return 0;
  for (line = strtok_r(text, "\n", &save); line; line = strtok_r(NULL, "\n", &save))
    parse_canon_line(line, &scale, ++n, l);
  free(text);
  return 1;
}

typedef struct {
  swarf_move *arc;
  int n;
} collect_arc_ctx;

static int collect_arc(const swarf_move *mv, void *user) {
  collect_arc_ctx *cx = user;
  if (mv->kind == SWARF_MOVE_ARC) *cx->arc = *mv, cx->n++;
  return 0;
}

/* ---- comparing swarf's moves -------------------------------------------- */

/* Known, explained differences: LinuxCNC's value = swarf's + delta. */
typedef struct {
  const char *file;
  long line; /* source line */
  int axis;
  double delta; /* canon units */
} deviation;

/* (Files with G43 H1 -- cameo, HeatSink, Cereal -- are not in the move
 * comparison: their machine-frame moves include rs274's built-in 0.511 in
 * tool 1; the canon comparison covers them.) */
static const deviation deviations[] = {
    {"lcnc-Cereal.ngc", 2269, 2, -12.9794},
    {"lcnc-Cereal.ngc", 2270, 2, -12.9794},
};

static double deviation_of(const char *file, long line, int axis) {
  for (size_t i = 0; i < sizeof deviations / sizeof deviations[0]; i++)
    if (strcmp(deviations[i].file, file) == 0 && deviations[i].line == line &&
        deviations[i].axis == axis)
      return deviations[i].delta;
  return 0;
}

typedef struct {
  const char *file;
  const canon_list *canon;
  size_t next;
  int mismatches;
  double worst;
} compare_ctx;

static int report(compare_ctx *cx, const swarf_move *mv, const char *what, double got,
                  double want) {
  if (cx->mismatches++ < 5)
    fprintf(stderr, "%s: source line %ld, canon line %ld: %s: swarf %.6f, LinuxCNC %.6f\n",
            cx->file, mv->line, cx->canon->calls[cx->next].text_line, what, got, want);
  return 0;
}

static void near(compare_ctx *cx, const swarf_move *mv, const char *what, double got, double want) {
  double d = fabs(got - want);
  if (d > cx->worst) cx->worst = d;
  if (!(d <= TOL)) report(cx, mv, what, got, want);
}

/* The arc's axes as LinuxCNC names them: (first, second, third). */
static void arc_axes(const swarf_move *mv, int ax[3]) {
  if (fabs(mv->normal[0]) > 0.5) {
    ax[0] = 1, ax[1] = 2, ax[2] = 0;
  } else if (fabs(mv->normal[1]) > 0.5) {
    ax[0] = 2, ax[1] = 0, ax[2] = 1;
  } else {
    ax[0] = 0, ax[1] = 1, ax[2] = 2;
  }
}

static void compare_arc(compare_ctx *cx, const swarf_move *mv, const canon_call *c) {
  int ax[3];
  double k = 1.0 / c->scale, sign, turns;
  arc_axes(mv, ax);
  sign = mv->normal[ax[2]] > 0 ? 1 : -1;
  turns = fmax(1, ceil(mv->angle / TWO_PI - 1e-9));
  near(cx, mv, "arc first end", mv->end[ax[0]] * k, c->v[0]);
  near(cx, mv, "arc second end", mv->end[ax[1]] * k, c->v[1]);
  near(cx, mv, "arc first centre", mv->center[ax[0]] * k, c->v[2]);
  near(cx, mv, "arc second centre", mv->center[ax[1]] * k, c->v[3]);
  near(cx, mv, "arc rotation", sign * turns, c->v[4]);
  near(cx, mv, "arc axis end", mv->end[ax[2]] * k, c->v[5]);
  for (int i = 0; i < 3; i++)
    near(cx, mv, "arc rotary end", mv->end[3 + i], c->v[6 + i]);
}

static void compare_straight(compare_ctx *cx, const swarf_move *mv, const canon_call *c) {
  static const char *names[6] = {"x", "y", "z", "a", "b", "c"};
  for (int i = 0; i < 6; i++)
    near(cx, mv, names[i],
         mv->end[i] * (i < 3 ? 1.0 / c->scale : 1.0) + deviation_of(cx->file, mv->line, i),
         c->v[i]);
}

static canon_kind kind_of(const swarf_move *mv) {
  switch (mv->kind) {
  case SWARF_MOVE_RAPID:
    return CANON_TRAVERSE;
  case SWARF_MOVE_LINE:
    return CANON_FEED;
  case SWARF_MOVE_ARC:
    return CANON_ARC;
  default:
    return CANON_DWELL;
  }
}

static int on_move(const swarf_move *mv, void *user) {
  compare_ctx *cx = user;
  const canon_call *c;
  if (mv->kind == SWARF_MOVE_TOOL_CHANGE) return 0;
  if (cx->next >= cx->canon->n) {
    if (cx->mismatches++ < 5)
      fprintf(stderr, "%s: source line %ld: swarf emits more moves than LinuxCNC\n", cx->file,
              mv->line);
    return 0;
  }
  c = &cx->canon->calls[cx->next];
  if (kind_of(mv) != c->kind)
    report(cx, mv, "kind of move", kind_of(mv), c->kind);
  else if (c->kind == CANON_ARC)
    compare_arc(cx, mv, c);
  else if (c->kind == CANON_DWELL)
    near(cx, mv, "dwell", mv->dwell, c->v[0]);
  else
    compare_straight(cx, mv, c);
  cx->next++;
  return 0;
}

static void path_join(char *out, size_t cap, const char *dir, const char *sub, const char *name,
                      const char *ext) {
  snprintf(out, cap, "%s/%s/%s%s", dir, sub, name, ext);
}

static void conform(const char *dir, const char *name) {
  char src[1024], canon_path[1024];
  canon_list canon = {0};
  compare_ctx cx = {0};
  swarf_error err;
  int status;
  path_join(src, sizeof src, dir, "real", name, "");
  path_join(canon_path, sizeof canon_path, dir, "real/canon", name, ".canon.xz");
  CHECK(load_canon(canon_path, &canon), "%s: cannot read %s", name, canon_path);
  cx.file = name;
  cx.canon = &canon;
  status = swarf_gcode_parse_file(src, on_move, &cx, &err);
  CHECK(status == SWARF_OK, "%s: rejected at %ld:%d: %s", name, err.line, err.column, err.message);
  CHECK(cx.next == canon.n, "%s: swarf emitted %zu motion calls, LinuxCNC %zu", name, cx.next,
        canon.n);
  CHECK(cx.mismatches == 0, "%s: %d values differ from LinuxCNC", name, cx.mismatches);
  printf("%-40s %7zu motion calls, worst difference %.2g\n", name, canon.n, cx.worst);
  free(canon.calls);
}

/* A file of a later version's dialect: rejected, at the expected line. */
static void refuse(const char *dir, const char *name, long line, const char *words) {
  char src[1024];
  swarf_error err;
  int status;
  path_join(src, sizeof src, dir, "real", name, "");
  status = swarf_gcode_parse_file(src, NULL, NULL, &err);
  CHECK(status != SWARF_OK, "%s: accepted, but it needs a later version", name);
  if (status == SWARF_OK) return;
  CHECK(err.line == line, "%s: rejected at line %ld, expected %ld (%s)", name, err.line, line,
        err.message);
  CHECK(strstr(err.message, words) != NULL, "%s: message \"%s\" lacks \"%s\"", name, err.message,
        words);
  printf("%-40s refused at %ld:%d: %s\n", name, err.line, err.column, err.message);
}

/* ---- LinuxCNC's arc radius tolerance cases (tests/interp good and bad) --- */

typedef struct {
  const char *dir;  /* linuxcnc/<dir>/ */
  const char *file; /* its .ngc: first line of a bad one is LinuxCNC's message */
  const char *units;
  double x, i; /* the arc's X and I, the ngc's expressions evaluated here */
} arc_tolerance_case;

static int first_line(const char *path, char *out, size_t cap) {
  FILE *in = fopen(path, "r");
  int ok = in != NULL && fgets(out, (int)cap, in) != NULL;
  if (in) fclose(in);
  if (ok) out[strcspn(out, "\r\n")] = '\0';
  return ok;
}

static int expected_arc(const char *path, double v[9]) {
  FILE *in = fopen(path, "r");
  char line[512];
  int found = 0;
  while (in != NULL && !found && fgets(line, sizeof line, in) != NULL) {
    const char *p = strstr(line, "ARC_FEED(");
    if (p != NULL) found = parse_args(strchr(p, '('), v) == 9;
  }
  if (in) fclose(in);
  return found;
}

static int arc_of_program(const arc_tolerance_case *k, swarf_move *arc, swarf_error *err) {
  char text[256];
  collect_arc_ctx ctx = {arc, 0};
  swarf_gcode_parser *p = NULL;
  swarf_gcode_parser_new(k->file, collect_arc, &ctx, &p);
  int status;
  snprintf(text, sizeof text, "%s\nf1\ng0x0y0z0\ng2 x%.17g y0 i%.17g\nm2\n", k->units, k->x, k->i);
  status = swarf_gcode_parser_feed(p, text, strlen(text));
  if (status == SWARF_OK) status = swarf_gcode_parser_finish(p);
  if (swarf_gcode_parser_error(p)) *err = *swarf_gcode_parser_error(p);
  swarf_gcode_parser_free(p);
  if (status == SWARF_OK && ctx.n != 1) return -1;
  return status;
}

static void arc_tolerance_good(const char *dir, const arc_tolerance_case *k) {
  char path[1024];
  double v[9];
  swarf_move arc;
  swarf_error err;
  double scale = strcmp(k->units, "g20") == 0 ? 25.4 : 1.0;
  snprintf(path, sizeof path, "%s/linuxcnc/%s/%s.expected", dir, k->dir, k->file);
  CHECK(expected_arc(path, v), "%s: no ARC_FEED in %s", k->dir, path);
  CHECK(arc_of_program(k, &arc, &err) == SWARF_OK, "%s: refused: %s", k->dir, err.message);
  CHECK_NEAR(arc.center[0] / scale, v[2], TOL, k->dir);
  CHECK_NEAR(arc.end[0] / scale, v[0], TOL, k->dir);
  CHECK_NEAR(arc.normal[2] > 0 ? 1 : -1, v[4], 0, k->dir);
}

static void arc_tolerance_bad(const char *dir, const arc_tolerance_case *k) {
  char path[1024], expected[512];
  swarf_move arc;
  swarf_error err;
  snprintf(path, sizeof path, "%s/linuxcnc/%s/%s", dir, k->dir, k->file);
  CHECK(first_line(path, expected, sizeof expected), "%s: cannot read %s", k->file, path);
  CHECK(arc_of_program(k, &arc, &err) == SWARF_ERR_SEMANTIC, "%s: accepted", k->file);
  CHECK(err.line == 4 && strcmp(err.message, expected + 1) == 0,
        "%s: line %ld\n  swarf:    %s\n  LinuxCNC: %s", k->file, err.line, err.message,
        expected + 1);
}

static void arc_tolerance(const char *dir) {
  const double s2 = sqrt(2.0);
  const arc_tolerance_case good[] = {
      {"good-arc-big-metric", "good-arc.big.metric.center-format.ngc", "g21", 6000,
       3000 + 100 * (0.0099 * s2)},
      {"good-arc-big-imperial", "good-arc.big.imperial.center-format.ngc", "g20", 600,
       300 + 100 * (0.00099 * s2)},
      {"good-arc-medium-metric", "good-arc.medium.metric.center-format.ngc", "g21", 2000,
       0.9995 * 1000},
      {"good-arc-medium-imperial", "good-arc.medium.imperial.center-format.ngc", "g20", 200,
       0.9995 * 100},
      {"good-arc-small-metric", "good-arc.small.metric.center-format.ngc", "g21", 50,
       25.00 - 0.0099 * s2},
      {"good-arc-small-imperial", "good-arc.small.imperial.center-format.ngc", "g20", 5,
       2.500 - 0.00099 * s2},
  };
  const arc_tolerance_case bad[] = {
      {"bad-rejected", "bad-arc.big.metric.center-format.ngc", "g21", 6000,
       3000 + 100 * (0.0101 * s2)},
      {"bad-rejected", "bad-arc.big.imperial.center-format.ngc", "g20", 600,
       300 + 100 * (0.00101 * s2)},
      {"bad-rejected", "bad-arc.medium.metric.center-format.ngc", "g21", 2000, 0.9985 * 1000},
      {"bad-rejected", "bad-arc.medium.imperial.center-format.ngc", "g20", 200, 0.9985 * 100},
      {"bad-rejected", "bad-arc.small.metric.center-format.ngc", "g21", 50, 25.00 - 0.0101 * s2},
      {"bad-rejected", "bad-arc.small.imperial.center-format.ngc", "g20", 5, 2.500 - 0.00101 * s2},
  };
  for (size_t i = 0; i < sizeof good / sizeof good[0]; i++)
    arc_tolerance_good(dir, &good[i]);
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
    arc_tolerance_bad(dir, &bad[i]);
}

/* The in-scope files of LinuxCNC's bad-rejected folder (the message texts
 * differ in wording; the refusal, its line and its subject must match). */
static void rejected(const char *dir, const char *file, const char *words) {
  char path[1024];
  swarf_error err;
  snprintf(path, sizeof path, "%s/linuxcnc/bad-rejected/%s", dir, file);
  CHECK(swarf_gcode_parse_file(path, NULL, NULL, &err) == SWARF_ERR_SEMANTIC && err.line == 2 &&
            strstr(err.message, words) != NULL,
        "%s: %ld:%d %s", file, err.line, err.column, err.message);
}

/* Every real file: swarf's canon (program coordinates, as rs274 prints)
 * against LinuxCNC's, call for call. For the file LinuxCNC needed edited
 * (canon/README.md), the same edit: lines starting with % deleted. */
static void conform_canon(const char *dir, const char *name) {
  char src[1024], canon_path[1100], why[200];
  size_t len, clen;
  char *text, *expected;
  canon_text out;
  canon_calls got, want;
  swarf_error err;
  int status;
  snprintf(src, sizeof src, "%s/real/%s", dir, name);
  snprintf(canon_path, sizeof canon_path, "%s/real/canon/%s.canon.xz", dir, name);
  text = canon_slurp(src, &len);
  expected = read_xz(canon_path, &clen);
  CHECK(text != NULL && expected != NULL, "%s: cannot read the file or its canon", name);
  if (text == NULL || expected == NULL) return free(text), free(expected);
  if (strncmp(name, "ghettotator", 11) == 0) { /* drop the % lines, as for rs274 */
    size_t o = 0;
    for (size_t i = 0; i < len;) {
      const char *nl = memchr(text + i, '\n', len - i);
      size_t n = nl ? (size_t)(nl - (text + i)) + 1 : len - i;
      if (text[i] != '%') memmove(text + o, text + i, n), o += n;
      i += n;
    }
    len = o;
  }
  status = canon_run(name, text, len, NULL, &out, &err);
  if (strncmp(name, "ghettotator", 11) == 0) /* no M2/M30: rs274 stops at the end, exit 1 */
    CHECK(status == SWARF_ERR_SEMANTIC && err.code == SWARF_GCODE_E_NO_PROGRAM_END,
          "%s: the missing program end: %s", name, err.message);
  else
    CHECK(status == SWARF_OK, "%s: rejected at %ld:%d: %s", name, err.line, err.column,
          err.message);
  canon_extract(out.text, 0, &got);
  canon_extract(expected, 0, &want);
  why[0] = '\0';
  CHECK(!canon_differ(&got, &want, 1.01e-4, why, sizeof why), "%s: %s", name, why);
  printf("%-42s %zu motion calls match rs274\n", name, want.n);
  free(got.v);
  free(want.v);
  free(out.text);
  free(text);
  free(expected);
}

int main(int argc, char **argv) {
  static const char *supported[] = {
      "camotics-bear.nc",          "camotics-tiger.nc",        "camotics-flower_mold.nc",
      "ugs-Gates_combined_R12.nc", "ugs-arc_rword_test.gcode", "sergeypopov-4axis_bracet.nc",
      "camotics-vcarve.ngc",       "lcnc-LHchips4.ngc",        "lcnc-stellabee1.ngc",
      "lcnc-wheels.ngc",
  };
  static const char *all[] = {"camotics-bear.nc",
                              "camotics-botomata_bottom.nc",
                              "camotics-cameo.nc",
                              "camotics-flower_mold.nc",
                              "camotics-tiger.nc",
                              "camotics-tiny_cat_outline.ngc",
                              "camotics-vcarve.ngc",
                              "ghettotator-wiggler-7-front0125mill.gcode",
                              "lcnc-3D_Chips.ngc",
                              "lcnc-Cereal.ngc",
                              "lcnc-LHchips4.ngc",
                              "lcnc-boat-xyzac.ngc",
                              "lcnc-boat-xyzbc.ngc",
                              "lcnc-impeller-7bl-xyzac.ngc",
                              "lcnc-stellabee1.ngc",
                              "lcnc-wheels.ngc",
                              "sergeypopov-4axis_bracet.nc",
                              "sergeypopov-HeatSink_mill.tap",
                              "ugs-Gates_combined_R12.nc",
                              "ugs-arc_rword_test.gcode",
                              "ugs-rotation.ngc"};
  FILE *probe;
  char readme[1024];
  if (argc < 2) {
    fprintf(stderr, "usage: %s <conformance-dir>\n", argv[0]);
    return 2;
  }
  snprintf(readme, sizeof readme, "%s/real/canon/README.md", argv[1]);
  probe = fopen(readme, "r");
  if (probe == NULL) { /* a clone without ../shared beside it */
    printf("SKIPPED: the conformance corpus is not here (%s): it lives in ../shared beside a "
           "checkout\n",
           readme);
    return 77;
  }
  fclose(probe);
  for (size_t i = 0; i < sizeof supported / sizeof supported[0]; i++)
    conform(argv[1], supported[i]);
  for (size_t i = 0; i < sizeof all / sizeof all[0]; i++)
    conform_canon(argv[1], all[i]);
  /* LinuxCNC itself refuses this line ("% vfd enable"): */
  refuse(argv[1], "ghettotator-wiggler-7-front0125mill.gcode", 37, "Bad character '%'");
  arc_tolerance(argv[1]);
  rejected(argv[1], "no-feed-rate.ngc", "zero feed rate");
  rejected(argv[1], "no-ijr.ngc", "all missing for arc");
  return check_done();
}
