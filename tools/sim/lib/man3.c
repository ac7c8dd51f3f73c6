/* SPDX-License-Identifier: MPL-2.0 */
/* man3.c -- writes libswarf's section-3 man pages from its public headers.
 *
 *   swarf-man3 OUTDIR VERSION HEADER...
 *
 * Every declaration marked SWARF_API is a call of the C API; the comment
 * just above it (or above the group of declarations it heads) says what it
 * does. OUTDIR/libswarf.3 lists every call under its header with that
 * comment, and OUTDIR/<call>.3 for each call is a one-line page that sources
 * it (`man swarf_sim_new` opens libswarf(3) there). The pages say exactly
 * what the headers say: they cannot drift from them.
 */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { TEXT_MAX = 1 << 16, NAME_MAX_LEN = 128 };

/* Appends `s` to the roff page, escaping what roff would take for requests
 * or escapes: backslashes, a leading dot or quote, and minus signs. */
static void roff_put(FILE *out, const char *s) {
  int bol = 1;
  for (; *s; s++) {
    if (bol && (*s == '.' || *s == '\'')) fputs("\\&", out);
    if (*s == '\\')
      fputs("\\e", out);
    else if (*s == '-')
      fputs("\\-", out);
    else
      fputc(*s, out);
    bol = *s == '\n';
  }
}

/* The comment text of the lines in `comment` without the markers. */
static void comment_clean(char *c) {
  char *w = c;
  for (char *r = c; *r;) {
    if (r[0] == '/' && r[1] == '*') {
      r += 2;
      continue;
    }
    if (r[0] == '*' && r[1] == '/') {
      r += 2;
      continue;
    }
    if (*r == '\n') {
      *w++ = *r++;
      while (*r == ' ' || *r == '\t')
        r++;
      if (*r == '*' && r[1] != '/') r++;
      if (*r == ' ') r++;
      continue;
    }
    *w++ = *r++;
  }
  *w = '\0';
  while (w > c && isspace((unsigned char)w[-1]))
    *--w = '\0';
  char *s = c;
  while (isspace((unsigned char)*s))
    s++;
  memmove(c, s, strlen(s) + 1);
}

/* The called name of a declaration: the identifier before its first '('. */
static int decl_name(const char *decl, char name[NAME_MAX_LEN]) {
  const char *p = strchr(decl, '(');
  if (p == NULL) return 0;
  while (p > decl && isspace((unsigned char)p[-1]))
    p--;
  const char *e = p;
  while (p > decl && (isalnum((unsigned char)p[-1]) || p[-1] == '_'))
    p--;
  if (e - p <= 0 || e - p >= NAME_MAX_LEN) return 0;
  memcpy(name, p, (size_t)(e - p));
  name[e - p] = '\0';
  return 1;
}

/* Writes OUTDIR/NAME.3 sourcing libswarf.3. */
static int write_alias(const char *dir, const char *name) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s.3", dir, name);
  FILE *f = fopen(path, "w");
  if (f == NULL) return perror(path), 1;
  fputs(".so man3/libswarf.3\n", f);
  return fclose(f) != 0;
}

/* One header: its calls with their comments into `out`. Returns the number
 * of calls, or -1 on failure. */
static int header_pages(FILE *out, const char *dir, const char *path) {
  FILE *in = fopen(path, "r");
  static char comment[TEXT_MAX], decl[TEXT_MAX];
  char line[4096], name[NAME_MAX_LEN];
  int in_comment = 0, n = 0, in_decl = 0;
  if (in == NULL) return perror(path), -1;
  const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
  fprintf(out, ".SH \"<swarf/%s>\"\n", base);
  comment[0] = '\0';
  while (fgets(line, sizeof line, in)) {
    if (in_decl) {
      const char *t = line + strspn(line, " \t");
      if (*t == ';') { /* after compiler notes: end the call's line */
        size_t k = strlen(decl);
        while (k > 0 && isspace((unsigned char)decl[k - 1]))
          decl[--k] = '\0';
        strncat(decl, ";\n", sizeof decl - strlen(decl) - 1);
      } else if (*t != '#' && strncmp(t, "__attribute__", 13)) /* compiler notes: not the call's */
        strncat(decl, line, sizeof decl - strlen(decl) - 1);
      if (strchr(line, ';') == NULL) continue;
      in_decl = 0;
    } else if (in_comment || !strncmp(line, "/*", 2)) {
      if (!in_comment) comment[0] = '\0';
      strncat(comment, line, sizeof comment - strlen(comment) - 1);
      in_comment = strstr(line, "*/") == NULL;
      continue;
    } else if (!strncmp(line, "SWARF_API ", 10)) {
      snprintf(decl, sizeof decl, "%s", line + 10);
      if (strchr(line, ';') == NULL) {
        in_decl = 1;
        continue;
      }
    } else {
      if (line[0] != '\n' && line[0] != '#') comment[0] = '\0'; /* a type: its comment */
      continue;
    }
    char *semi = strrchr(decl, ';');
    if (semi) semi[1] = '\0';
    if (!decl_name(decl, name)) continue;
    comment_clean(comment);
    fputs(".PP\n.nf\n.B ", out);
    roff_put(out, decl);
    fputs("\n.fi\n", out);
    if (comment[0]) {
      fputs(".RS\n.nf\n", out);
      roff_put(out, comment);
      fputs("\n.fi\n.RE\n", out);
    }
    if (write_alias(dir, name)) return fclose(in), -1;
    comment[0] = '\0'; /* the next of a group: the group's comment was shown */
    n++;
  }
  fclose(in);
  return n;
}

int main(int argc, char **argv) {
  char path[4096];
  int total = 0;
  if (argc < 4) {
    fputs("usage: swarf-man3 OUTDIR VERSION HEADER...\n", stderr);
    return 2;
  }
  snprintf(path, sizeof path, "%s/libswarf.3", argv[1]);
  FILE *out = fopen(path, "w");
  if (out == NULL) return perror(path), 1;
  fprintf(out,
          ".\\\" libswarf.3 -- generated by tools/sim/lib/man3.c from the public headers; "
          "do not edit.\n.TH LIBSWARF 3 \"\" \"swarf %s\" \"Library Functions\"\n"
          ".SH NAME\nlibswarf \\- the C API of swarf, the CNC milling simulation engine\n"
          ".SH SYNOPSIS\n.nf\n.B #include <swarf/swarf.h>\n.PP\n"
          "cc prog.c $(pkg\\-config \\-\\-cflags \\-\\-libs swarf)\n.fi\n"
          ".SH DESCRIPTION\nEvery call that can fail returns a\n.B swarf_status\n"
          "and one that makes something fills the caller's\n.B swarf_error\n(status, file, "
          "line, column, word, message; may be NULL); a simulation handle keeps its own "
          "(swarf_sim_error). Handles are opaque: made by *_new, released by *_free "
          "(NULL is fine). The calls by header, each with its header's own words:\n",
          argv[2]);
  for (int i = 3; i < argc; i++) {
    int n = header_pages(out, argv[1], argv[i]);
    if (n < 0) return fclose(out), 1;
    total += n;
  }
  fputs(".SH SEE ALSO\n.BR swarf (1)\n", out);
  if (fclose(out) != 0) return perror(path), 1;
  printf("swarf-man3: %d calls in libswarf.3\n", total);
  return total > 0 ? 0 : 1;
}
