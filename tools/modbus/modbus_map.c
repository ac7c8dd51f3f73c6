/* SPDX-License-Identifier: MPL-2.0 */
/* modbus_map.c -- the Modbus register map: what each register of the status
 * block holds, computed from a status snapshot. tools/doc/modbus.md's table is the
 * contract; this file is its only implementation (servers and the push
 * client all call it). Pure functions: the caller owns every buffer.
 */
#include <math.h>
#include <string.h>

#include "modbus_private.h"

static void put32(uint16_t *regs, int at, unsigned long v) {
  if (v > 0xFFFFFFFFul) v = 0xFFFFFFFFul;
  regs[at] = (uint16_t)(v >> 16); /* high word first */
  regs[at + 1] = (uint16_t)(v & 0xFFFF);
}

static unsigned long nonneg(double v) {
  return v > 0 && isfinite(v) ? (unsigned long)llround(v < 4.3e9 ? v : 4.3e9) : 0ul;
}

/* Per-mille: moves done over moves known, 999 at most until finished. */
static uint16_t per_mille(const swarf_job_snapshot *s) {
  long pm;
  if (s->state == SWARF_JOB_FINISHED) return 1000;
  if (s->moves_total <= 0) return 0;
  pm = (long)((double)s->moves_done * 1000.0 / (double)s->moves_total);
  return (uint16_t)(pm < 0 ? 0 : pm > 999 ? 999 : pm);
}

static double elapsed(const swarf_job_snapshot *s, double now) {
  if (s->state == SWARF_JOB_IDLE) return 0.0;
  return (s->end > 0 ? s->end : now) - s->start;
}

/* Seconds left by the mean rate so far; 0xFFFFFFFF while unknown. */
static unsigned long remaining(const swarf_job_snapshot *s, double now) {
  if (s->state == SWARF_JOB_FINISHED) return 0;
  if (s->state != SWARF_JOB_RUNNING || s->moves_total <= 0 || s->moves_done <= 0)
    return 0xFFFFFFFFul;
  if (s->moves_done >= s->moves_total) return 0;
  return nonneg(elapsed(s, now) * (double)(s->moves_total - s->moves_done) / s->moves_done);
}

static uint16_t flags(const swarf_job_snapshot *s) {
  uint8_t b[SWARF_MB_NBITS];
  uint16_t f = 0;
  swarf_mb_map_bits(s, b);
  for (int i = 0; i < SWARF_MB_NBITS; i++)
    f |= (uint16_t)(b[i] << i);
  return f;
}

void swarf_mb_map_registers(const swarf_job_snapshot *s, double now,
                            uint16_t regs[SWARF_MB_NREGS]) {
  memset(regs, 0, sizeof(uint16_t) * SWARF_MB_NREGS);
  regs[SWARF_MB_REG_STATE] = (uint16_t)s->state;
  regs[SWARF_MB_REG_PROGRESS] = per_mille(s);
  put32(regs, SWARF_MB_REG_LINE, s->line > 0 ? (unsigned long)s->line : 0);
  put32(regs, SWARF_MB_REG_MOVES_DONE, s->moves_done > 0 ? (unsigned long)s->moves_done : 0);
  put32(regs, SWARF_MB_REG_MOVES_TOTAL, s->moves_total > 0 ? (unsigned long)s->moves_total : 0);
  put32(regs, SWARF_MB_REG_REMOVED, nonneg(s->removed));
  regs[SWARF_MB_REG_ALARMS] = (uint16_t)(s->alarms > 0xFFFF ? 0xFFFF : s->alarms);
  regs[SWARF_MB_REG_ERROR] = (uint16_t)s->error;
  put32(regs, SWARF_MB_REG_ELAPSED, nonneg(elapsed(s, now)));
  put32(regs, SWARF_MB_REG_REMAINING, remaining(s, now));
  regs[SWARF_MB_REG_TOOL] = (uint16_t)(s->tool > 0 && s->tool < 0xFFFF ? s->tool : 0);
  regs[SWARF_MB_REG_HEARTBEAT] = (uint16_t)(s->heartbeat & 0xFFFF);
  regs[SWARF_MB_REG_FLAGS] = flags(s);
  regs[SWARF_MB_REG_VERSION] = SWARF_MB_MAP_VERSION;
  regs[SWARF_MB_REG_COLLISIONS] = (uint16_t)(s->collisions > 0xFFFF ? 0xFFFF
                                             : s->collisions > 0    ? s->collisions
                                                                    : 0);
  for (int i = 0; i < SWARF_JOB_NAME_LEN; i += 2) {
    unsigned char hi = (unsigned char)s->program[i], lo = (unsigned char)s->program[i + 1];
    regs[SWARF_MB_NAME_REG + i / 2] = (uint16_t)(hi << 8 | (hi ? lo : 0));
  }
}

void swarf_mb_map_bits(const swarf_job_snapshot *s, uint8_t bits[SWARF_MB_NBITS]) {
  bits[0] = s->state == SWARF_JOB_RUNNING;
  bits[1] = s->state == SWARF_JOB_FINISHED;
  bits[2] = s->state == SWARF_JOB_FAILED;
  bits[3] = s->alarms > 0;
  bits[4] = s->paused != 0;
  bits[5] = s->moves_total > 0;
  bits[6] = s->commands != 0;
}
