/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_spec.c -- endpoint strings of the --modbus options:
 *
 *   tcp:[HOST:]PORT[,unit=N]    (server; HOST defaults to 127.0.0.1; push adds address=A)
 *   rtu:DEVICE,BAUD,PARITY,DATABITS,STOPBITS[,unit=N]
 *
 * Push endpoints also take address=A (required) and interval=SECONDS. HOST
 * may be [IPv6]. Everything is checked here, before anything is opened; the
 * caller owns the endpoint filled in.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modbus_private.h"

static swarf_status bad(swarf_error *err, const char *spec, const char *what) {
  return swarf_error_set(err, SWARF_ERR_ARG, "\"%s\": %s", spec, what);
}

static int read_long(const char *text, long lo, long hi, long *out) {
  char *end;
  errno = 0;
  *out = strtol(text, &end, 10);
  return end == text || *end != '\0' || errno || *out < lo || *out > hi ? -1 : 0;
}

/* "[HOST:]PORT" (HOST may be [v6], default 127.0.0.1); port 0 asks for a
 * free one. */
static int parse_hostport(char *field, swarf_mb_endpoint *e) {
  char *colon = strrchr(field, ':'), *portp = colon ? colon + 1 : field;
  long port;
  if (read_long(portp, 0, 65535, &port)) return -1;
  if (colon) *colon = '\0';
  if (colon && colon > field && field[0] == '[' && colon[-1] == ']') {
    colon[-1] = '\0';
    field++;
  }
  if (colon == NULL || field[0] == '\0') field = "127.0.0.1";
  if (strlen(field) >= sizeof e->host) return -1;
  strcpy(e->host, field);
  snprintf(e->port, sizeof e->port, "%ld", port);
  return 0;
}

/* DEVICE,BAUD,PARITY,DATABITS,STOPBITS: the first five comma fields. */
static int parse_serial(char **fields, int n, swarf_mb_endpoint *e) {
  long baud, data, stop;
  if (n < 5 || strlen(fields[0]) >= sizeof e->device || fields[0][0] == '\0') return -1;
  if (read_long(fields[1], 50, 4000000, &baud) || read_long(fields[3], 5, 8, &data) ||
      read_long(fields[4], 1, 2, &stop) || strlen(fields[2]) != 1 ||
      !strchr("NEOneo", fields[2][0]))
    return -1;
  strcpy(e->device, fields[0]);
  e->baud = (int)baud;
  e->parity = (char)(fields[2][0] & ~0x20);
  e->data_bits = (int)data;
  e->stop_bits = (int)stop;
  return 0;
}

/* key=value extras. */
static int parse_extra(const char *kv, int push, swarf_mb_endpoint *e) {
  long v;
  char *end;
  if (!strncmp(kv, "unit=", 5)) return read_long(kv + 5, 1, 247, &v) ? -1 : (e->unit = (int)v, 0);
  if (push && !strncmp(kv, "address=", 8))
    return read_long(kv + 8, 0, 65536 - SWARF_MB_NREGS, &v) ? -1 : (e->address = (int)v, 0);
  if (push && !strncmp(kv, "interval=", 9)) {
    errno = 0;
    e->interval = strtod(kv + 9, &end);
    return *end || end == kv + 9 || errno || !(e->interval >= 0.05 && e->interval <= 3600) ? -1 : 0;
  }
  return -1;
}

swarf_status swarf_mb_endpoint_parse(const char *spec, int push, swarf_mb_endpoint *e,
                                     swarf_error *err) {
  char copy[600], *fields[12], *save = NULL;
  int n = 0, first_extra;
  if (spec == NULL || e == NULL || strlen(spec) >= sizeof copy)
    return bad(err, spec ? spec : "", "too long");
  memset(e, 0, sizeof *e);
  e->unit = 1;
  e->address = -1;
  e->interval = 1.0;
  strcpy(copy, spec);
  for (char *f = strtok_r(copy, ",", &save); f && n < 12; f = strtok_r(NULL, ",", &save))
    fields[n++] = f;
  if (n > 0 && !strncmp(fields[0], "tcp:", 4)) {
    e->kind = SWARF_MB_TCP;
    if (parse_hostport(fields[0] + 4, e)) return bad(err, spec, "give tcp:HOST:PORT");
    first_extra = 1;
  } else if (n > 0 && !strncmp(fields[0], "rtu:", 4) && !push) {
    e->kind = SWARF_MB_RTU;
    fields[0] += 4;
    if (parse_serial(fields, n, e))
      return bad(err, spec, "give rtu:DEVICE,BAUD,PARITY(N/E/O),DATABITS(5-8),STOPBITS(1-2)");
    first_extra = 5;
  } else {
    return bad(err, spec,
               push ? "give tcp:HOST:PORT,unit=N,address=A"
                    : "give tcp:HOST:PORT or rtu:DEVICE,BAUD,PARITY,DATA,STOP");
  }
  for (int i = first_extra; i < n; i++)
    if (parse_extra(fields[i], push, e))
      return bad(err, spec,
                 push ? "options are unit=1..247, address=0..65472, interval=0.05..3600 (s)"
                      : "the only option is unit=1..247");
  if (push && e->address < 0) return bad(err, spec, "push needs address=A");
  if (push && !strcmp(e->port, "0")) return bad(err, spec, "push needs a real port");
  return SWARF_OK;
}
