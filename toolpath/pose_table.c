/* SPDX-License-Identifier: MPL-2.0 */
/* pose_table.c -- per-thread tables of a motion's poses at evenly spaced
 * times (swarf_motion_pose_table, toolpath.h).
 *
 * The swept-volume sdf of a rotary move evaluates the same N + 1 poses for
 * every voxel it is asked about; the stock asks for the voxels of a block
 * cut after cut, so a thread keeps the tables of its last SLOTS motions,
 * direct-mapped by the motion's address (the moves of a batch sit in one
 * array: consecutive slots) and checked against a byte copy of the motion.
 * SLOTS covers a whole batch of the driver's default 1024 moves (64 slots
 * were refilled 1.05 M times for 5.45 M lookups on the impeller's first 600
 * lines; 1024: 593 fills, one a move): ~350 KB a thread plus the poses,
 * which are kept to BUDGET bytes (over it every other slot is emptied).
 * A caller that numbers its motions (swarf_motion_pose_table_id: a rigid
 * sweep's number, new at each init) is served on the number alone, without
 * the comparison (~110 instructions a lookup; the ball end mill's path looks
 * up once a voxel and move). The poses' rates (swarf_pose_rates) are kept
 * beside a table once asked for (the ball's path), so that the table keeps
 * its size for the callers that read only poses (stamping: a larger pose
 * made it 7 % slower at 0.1 mm). Each thread's cache is freed when the
 * thread ends.
 */
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "toolpath_private.h"

#define SLOTS 1024
#define BUDGET ((size_t)32 << 20) /* bytes of poses a thread keeps at most (plus one table) */

typedef struct {
  swarf_motion key; /* byte copy of the motion the table is for */
  uint64_t id;      /* the caller's id for that motion (swarf_motion_pose_table_id), or 0 */
  int n;            /* the table holds n + 1 poses; 0: empty */
  int cap;          /* poses allocated */
  swarf_pose *poses;
  int rn;                  /* rates holds the n + 1 poses' rates when rn = n (0: none) */
  int rcap;                /* rates allocated */
  swarf_pose_rates *rates; /* swarf_motion_pose_table_rates */
} pose_slot;

typedef struct {
  pose_slot slot[SLOTS];
  size_t bytes; /* poses and rates allocated over all slots */
} pose_cache;

static pthread_key_t cache_key;
static pthread_once_t cache_once = PTHREAD_ONCE_INIT;
static _Thread_local pose_cache *thread_cache;

static void cache_free(void *p) {
  pose_cache *c = p;
  for (int i = 0; i < SLOTS; i++)
    free(c->slot[i].poses), free(c->slot[i].rates);
  free(c);
}

static void cache_key_init(void) {
  pthread_key_create(&cache_key, cache_free);
}

static pose_cache *cache_get(void) {
  if (thread_cache != NULL) return thread_cache;
  pthread_once(&cache_once, cache_key_init);
  thread_cache = calloc(1, sizeof *thread_cache);
  if (thread_cache != NULL) pthread_setspecific(cache_key, thread_cache);
  return thread_cache;
}

/* Empty every slot but keep (over BUDGET: long moves, many of them). */
static void cache_flush(pose_cache *c, const pose_slot *keep) {
  for (int i = 0; i < SLOTS; i++) {
    pose_slot *s = &c->slot[i];
    if (s == keep) continue;
    c->bytes -= sizeof *s->poses * (size_t)s->cap + sizeof *s->rates * (size_t)s->rcap;
    free(s->poses), free(s->rates);
    s->poses = NULL, s->cap = 0, s->n = 0;
    s->rates = NULL, s->rcap = 0, s->rn = 0;
  }
}

/* Fill slot s of c with the n + 1 poses of m. Returns 0, or -1 out of memory. */
static int slot_fill(pose_cache *c, pose_slot *s, const swarf_motion *m, int n) {
  if (s->cap < n + 1) {
    size_t grow = sizeof *s->poses * (size_t)(n + 1 - s->cap);
    swarf_pose *p;
    if (c->bytes + grow > BUDGET) cache_flush(c, s);
    p = realloc(s->poses, sizeof *p * (size_t)(n + 1));
    if (p == NULL) return -1;
    s->poses = p, s->cap = n + 1, c->bytes += grow;
  }
  for (int i = 0; i <= n; i++)
    swarf_motion_pose(m, (double)i / n, &s->poses[i]);
  memcpy(&s->key, m, sizeof *m);
  s->n = n, s->rn = 0;
  return 0;
}

/* The rates of slot s's poses (filled). Returns 0, or -1 out of memory. */
static int slot_rates(pose_cache *c, pose_slot *s) {
  if (s->rn == s->n) return 0;
  if (s->rcap < s->n + 1) {
    size_t grow = sizeof *s->rates * (size_t)(s->n + 1 - s->rcap);
    swarf_pose_rates *r;
    if (c->bytes + grow > BUDGET) cache_flush(c, s);
    r = realloc(s->rates, sizeof *r * (size_t)(s->n + 1));
    if (r == NULL) return -1;
    s->rates = r, s->rcap = s->n + 1, c->bytes += grow;
  }
  for (int i = 0; i <= s->n; i++)
    swarf_pose_rates_of(&s->poses[i], &s->rates[i]);
  s->rn = s->n;
  return 0;
}

/* The table of m's n + 1 poses: slot s's if it holds them (by id when id is
 * not 0, else by a comparison of the contents), else s refilled. */
static swarf_status lookup(pose_cache *c, pose_slot *s, const swarf_motion *m, int n, uint64_t id,
                           const swarf_pose **out) {
  if (s->n == n && ((id != 0 && s->id == id) || memcmp(&s->key, m, sizeof *m) == 0)) {
    if (id != 0) s->id = id;
    *out = s->poses;
    return SWARF_OK;
  }
  s->n = 0, s->id = 0, s->rn = 0;
  if (slot_fill(c, s, m, n) != 0) return SWARF_ERR_MEMORY;
  s->id = id;
  *out = s->poses;
  return SWARF_OK;
}

swarf_status swarf_motion_pose_table_id(const swarf_motion *m, int n, uint64_t id,
                                        const swarf_pose **out) {
  pose_cache *c;
  if (out == NULL) return SWARF_ERR_ARG;
  *out = NULL;
  if (m == NULL || n < 1) return SWARF_ERR_ARG;
  if ((c = cache_get()) == NULL) return SWARF_ERR_MEMORY;
  return lookup(c, &c->slot[((uintptr_t)m / sizeof *m) % SLOTS], m, n, id, out);
}

swarf_status swarf_motion_pose_table_rates(const swarf_motion *m, int n, uint64_t id,
                                           const swarf_pose **poses,
                                           const swarf_pose_rates **rates) {
  pose_cache *c;
  pose_slot *s;
  swarf_status st;
  if (poses == NULL || rates == NULL) return SWARF_ERR_ARG;
  *poses = NULL, *rates = NULL;
  if (m == NULL || n < 1) return SWARF_ERR_ARG;
  if ((c = cache_get()) == NULL) return SWARF_ERR_MEMORY;
  s = &c->slot[((uintptr_t)m / sizeof *m) % SLOTS];
  if (id != 0 && s->id == id && s->n == n && s->rn == n) { /* the usual case, at once */
    *poses = s->poses, *rates = s->rates;
    return SWARF_OK;
  }
  if ((st = lookup(c, s, m, n, id, poses)) != SWARF_OK) return st;
  if (slot_rates(c, s) != 0) {
    *poses = NULL;
    return SWARF_ERR_MEMORY;
  }
  *rates = s->rates;
  return SWARF_OK;
}

swarf_status swarf_motion_pose_table(const swarf_motion *m, int n, const swarf_pose **out) {
  return swarf_motion_pose_table_id(m, n, 0, out);
}
