/* SPDX-License-Identifier: MPL-2.0 */
/* params.c -- numbered, named and computed parameters.
 *
 * Numbered parameters #1..#5601 are plain doubles, except the ranges that
 * mirror the interpreter state, as in LinuxCNC: #5161-#5169 (G28 home),
 * #5181-#5189 (G30 home), #5210-#5219 (G92 on, offsets), #5220 (active
 * system), #5221-#5399 (G54..G59.3 origins, rotation at +9), #5400-#5410
 * (tool, its offsets, diameter), #5420-#5428 (current position, read only).
 * Offsets are shown in the machine's length unit (`length_unit` mm each):
 * inches unless the machine's unit was set, as rs274 without an INI file
 * does (its "user units"); the current position in the active unit.
 *
 * Named parameters live in hash tables owned by the store (lookups in
 * constant time: 200k distinct names parse in linear time): `_`-names are
 * global, others belong to the running sub (main program included). The
 * store owns its tables; swarf_gc_params_clear frees them.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gcode_private.h"

/* One named set: an open-addressing hash table (linear probing, grown at
 * half full), so that n distinct names cost O(n), not O(n^2). */
typedef struct {
  char name[SWARF_GC_NAME_MAX];
  double value;
} named_slot;

struct swarf_gc_named {
  named_slot *slots; /* cap entries, name[0] == '\0': empty */
  size_t n, cap;     /* cap a power of two */
};

static size_t name_hash(const char *name) {
  size_t h = 1469598103934665603u; /* FNV-1a */
  for (; *name != '\0'; name++)
    h = (h ^ (unsigned char)*name) * 1099511628211u;
  return h;
}

/* The slot holding `name`, or the empty slot where it would go. */
static named_slot *named_slot_of(const swarf_gc_named *t, const char *name) {
  size_t i = name_hash(name) & (t->cap - 1);
  while (t->slots[i].name[0] != '\0' && strcmp(t->slots[i].name, name) != 0)
    i = (i + 1) & (t->cap - 1);
  return &t->slots[i];
}

static int named_grow(swarf_gc_named *t) {
  size_t cap = t->cap ? 2 * t->cap : 64;
  swarf_gc_named bigger = {calloc(cap, sizeof(named_slot)), 0, cap};
  if (bigger.slots == NULL) return -1;
  for (size_t i = 0; i < t->cap; i++)
    if (t->slots[i].name[0] != '\0') *named_slot_of(&bigger, t->slots[i].name) = t->slots[i];
  bigger.n = t->n;
  free(t->slots);
  *t = bigger;
  return 0;
}

void swarf_gc_params_init(swarf_gc_params *ps) {
  memset(ps, 0, sizeof *ps);
  ps->length_unit = SWARF_GC_MM_PER_INCH;
}

void swarf_gc_named_free(swarf_gc_named *list) {
  if (list == NULL) return;
  free(list->slots);
  free(list);
}

void swarf_gc_params_clear(swarf_gc_params *ps) {
  swarf_gc_named_free(ps->globals);
  swarf_gc_named_free(ps->locals);
  ps->globals = ps->locals = NULL;
}

swarf_gc_named *swarf_gc_params_swap_locals(swarf_gc_params *ps, swarf_gc_named *locals) {
  swarf_gc_named *old = ps->locals;
  ps->locals = locals;
  return old;
}

/* A mirrored slot: where it lives in the state and how it is scaled. */
typedef struct {
  double *slot; /* NULL: not mirrored */
  double scale; /* parameter = slot / scale */
  int read_only;
} mirror;

static mirror axis_slot(double *axes, int axis, double unit) {
  mirror m = {NULL, 1.0, 0};
  if (axis < 0 || axis > 8) return m;
  if (axis >= SWARF_NAXES) { /* U V W: always zero here */
    m.read_only = 1;
    return m;
  }
  m.slot = &axes[axis];
  m.scale = axis < 3 ? unit : 1.0;
  return m;
}

static mirror mirror_of(const swarf_gc_params *ps, swarf_gc_state *st, int i) {
  mirror none = {NULL, 1.0, 0};
  double u = ps->length_unit;
  if (st == NULL) return none;
  if (i >= 5161 && i <= 5169) return axis_slot(st->g28, i - 5161, u);
  if (i >= 5181 && i <= 5189) return axis_slot(st->g30, i - 5181, u);
  if (i >= 5211 && i <= 5219) return axis_slot(st->g92_saved, i - 5211, u);
  if (i >= 5221 && i <= 5399) {
    int k = (i - 5221) / 20, a = (i - 5221) % 20;
    if (k < SWARF_GC_NSYSTEMS && a == 9) {
      mirror m = {&st->rotations[k], 1.0, 0};
      return m;
    }
    if (k < SWARF_GC_NSYSTEMS && a < 9) return axis_slot(st->systems[k], a, u);
  }
  if (i >= 5401 && i <= 5409) return axis_slot(st->tlo, i - 5401, u);
  return none;
}

/* Machine position of axis `a` in the active unit (degrees for A B C). */
/* The current point (program mm), as LinuxCNC's current_x...: the
 * compensated tool point while cutter compensation moves the path. */
static void current(const swarf_gc_state *st, double p[SWARF_NAXES]) {
  memcpy(p, st->pos, SWARF_NAXES * sizeof *p);
  if (swarf_gc_comp_active(st)) memcpy(p, st->comp_pos, 3 * sizeof *p);
}

static double current_axis(const swarf_gc_state *st, int a) {
  double p[SWARF_NAXES];
  current(st, p);
  return a < 3 ? p[a] / swarf_gc_scale(st) : p[a];
}

static double machine_axis(const swarf_gc_state *st, int a) {
  double m[SWARF_NAXES];
  current(st, m);
  swarf_gc_to_machine(st, m, m);
  return a < 3 ? m[a] / swarf_gc_scale(st) : m[a];
}

static double computed(const swarf_gc_state *st, int i, int *found) {
  *found = 1;
  if (i >= 5021 && i <= 5026) return machine_axis(st, i - 5021);
  if (i >= 5027 && i <= 5029) return 0;
  if (i == 5210) return st->g92_on;
  if (i == 5220) return swarf_gc_system_index(st) + 1;
  if (i == 5400) return st->tool;
  if (i >= 5420 && i <= 5425) return current_axis(st, i - 5420);
  if (i >= 5426 && i <= 5428) return 0;
  *found = 0;
  return 0;
}

double swarf_gc_param_get(const swarf_gc_params *ps, int i) {
  int found;
  double v;
  if (i <= 0 || i >= SWARF_GC_NPARAMS) return 0;
  if (ps->state != NULL) {
    mirror m = mirror_of(ps, (swarf_gc_state *)ps->state, i);
    if (m.slot != NULL) return *m.slot / m.scale;
    v = computed(ps->state, i, &found);
    if (found) return v;
  }
  return ps->num[i];
}

void swarf_gc_param_set(swarf_gc_params *ps, swarf_gc_state *st, int i, double v) {
  mirror m;
  if (i <= 0 || i >= SWARF_GC_NPARAMS) return;
  m = mirror_of(ps, st, i);
  if (m.slot != NULL && !m.read_only) *m.slot = v * m.scale;
  ps->num[i] = v;
}

static named_slot *find(const swarf_gc_named *t, const char *name) {
  named_slot *s;
  if (t == NULL || t->cap == 0) return NULL;
  s = named_slot_of(t, name);
  return s->name[0] != '\0' ? s : NULL;
}

/* Read-only names computed from the state (a few of LinuxCNC's). */
static int predefined(const swarf_gc_params *ps, const char *name, double *v) {
  const swarf_gc_state *st = ps->state;
  if (strcmp(name, "_value") == 0) return *v = ps->value, 0;
  if (strcmp(name, "_value_returned") == 0) return *v = ps->value_returned, 0;
  if (st == NULL) return -1;
  if (strcmp(name, "_metric") == 0) return *v = st->modal.units == 210, 0;
  if (strcmp(name, "_imperial") == 0) return *v = st->modal.units == 200, 0;
  if (strcmp(name, "_absolute") == 0) return *v = st->modal.distance == 900, 0;
  if (strcmp(name, "_incremental") == 0) return *v = st->modal.distance == 910, 0;
  if (strcmp(name, "_current_tool") == 0) return *v = st->tool, 0;
  if (strcmp(name, "_selected_tool") == 0) return *v = st->selected_tool, 0;
  if (strcmp(name, "_feed") == 0) return *v = st->feed / swarf_gc_scale(st), 0;
  if (strcmp(name, "_rpm") == 0) return *v = st->speed, 0;
  if (strncmp(name, "_abs_", 5) == 0 && name[5] != '\0' && name[6] == '\0') {
    const char *at = strchr("xyzabc", name[5]);
    if (at != NULL) return *v = machine_axis(st, (int)(at - "xyzabc")), 0;
  }
  if (name[0] == '_' && name[1] != '\0' && name[2] == '\0') {
    const char *axes = "xyzabc", *at = strchr(axes, name[1]);
    if (at != NULL) {
      *v = current_axis(st, (int)(at - axes));
      return 0;
    }
  }
  return -1;
}

int swarf_gc_param_named(const swarf_gc_params *ps, const char *name, double *v) {
  const named_slot *n = find(name[0] == '_' ? ps->globals : ps->locals, name);
  if (n != NULL) {
    *v = n->value;
    return 0;
  }
  return name[0] == '_' ? predefined(ps, name, v) : -1;
}

int swarf_gc_param_set_named(swarf_gc_params *ps, const char *name, double v) {
  swarf_gc_named **t = name[0] == '_' ? &ps->globals : &ps->locals;
  named_slot *n;
  if (name[0] == '\0') return -1;
  if (*t == NULL && (*t = calloc(1, sizeof **t)) == NULL) return -1;
  n = find(*t, name);
  if (n == NULL) {
    if (2 * ((*t)->n + 1) > (*t)->cap && named_grow(*t) != 0) return -1;
    n = named_slot_of(*t, name);
    strncpy(n->name, name, sizeof n->name - 1);
    n->name[sizeof n->name - 1] = '\0';
    (*t)->n++;
  }
  n->value = v;
  return 0;
}
