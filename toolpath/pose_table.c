/* pose_table.c -- per-thread tables of a motion's poses at evenly spaced
 * times (swarf_motion_pose_table, toolpath.h).
 *
 * The swept-volume sdf of a rotary move evaluates the same N + 1 poses for
 * every voxel it is asked about; the stock asks for the voxels of a block
 * cut after cut, so a thread keeps the tables of its last SLOTS motions,
 * direct-mapped by the motion's address (the moves of a batch sit in one
 * array: consecutive slots) and checked against a byte copy of the motion.
 * Each thread's cache is freed when the thread ends.
 */
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "toolpath_private.h"

#define SLOTS 64

typedef struct {
  swarf_motion key; /* byte copy of the motion the table is for */
  int n;            /* the table holds n + 1 poses; 0: empty */
  int cap;          /* poses allocated */
  swarf_pose *poses;
} pose_slot;

typedef struct {
  pose_slot slot[SLOTS];
} pose_cache;

static pthread_key_t cache_key;
static pthread_once_t cache_once = PTHREAD_ONCE_INIT;
static _Thread_local pose_cache *thread_cache;

static void cache_free(void *p) {
  pose_cache *c = p;
  for (int i = 0; i < SLOTS; i++)
    free(c->slot[i].poses);
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

/* Fill slot s with the n + 1 poses of m. Returns 0, or -1 out of memory. */
static int slot_fill(pose_slot *s, const swarf_motion *m, int n) {
  if (s->cap < n + 1) {
    swarf_pose *p = realloc(s->poses, sizeof *p * (size_t)(n + 1));
    if (p == NULL) return -1;
    s->poses = p, s->cap = n + 1;
  }
  for (int i = 0; i <= n; i++)
    swarf_motion_pose(m, (double)i / n, &s->poses[i]);
  memcpy(&s->key, m, sizeof *m);
  s->n = n;
  return 0;
}

swarf_status swarf_motion_pose_table(const swarf_motion *m, int n, const swarf_pose **out) {
  pose_cache *c;
  pose_slot *s;
  if (out == NULL) return SWARF_ERR_ARG;
  *out = NULL;
  if (m == NULL || n < 1) return SWARF_ERR_ARG;
  if ((c = cache_get()) == NULL) return SWARF_ERR_MEMORY;
  s = &c->slot[((uintptr_t)m / sizeof *m) % SLOTS];
  if (s->n == n && memcmp(&s->key, m, sizeof *m) == 0) {
    *out = s->poses;
    return SWARF_OK;
  }
  s->n = 0;
  if (slot_fill(s, m, n) != 0) return SWARF_ERR_MEMORY;
  *out = s->poses;
  return SWARF_OK;
}
