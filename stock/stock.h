/* stock.h -- the workpiece as an OpenVDB narrow-band level set (plain C API).
 *
 * Role: hold the remaining material as a float level-set grid named "stock"
 * (negative inside material), remove swept volumes from it in place with
 * stock = max(stock, -sweep), and read and write it: .vdb, binary STL mesh,
 * PNG picture from OpenVDB's level-set ray tracer. The C++ behind this header
 * (the .cc files in stock/) is the only code that includes OpenVDB; no exception crosses
 * into C: every function returns a status and fills a message.
 *
 * Units: mm in the workpiece frame; `voxel` is the voxel edge in mm; the
 * narrow band is `half_width` voxels on each side (at least 3).
 *
 * Ownership: a swarf_stock is an opaque handle (new ... free). Output files
 * are written to a temporary name in the same folder and renamed into place,
 * so a failed write never leaves a half-written file.
 *
 * Thread safety: one thread at a time per handle; removal itself runs on
 * TBB's threads internally.
 */
#ifndef SWARF_STOCK_H
#define SWARF_STOCK_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
  SWARF_STOCK_OK = 0,
  SWARF_STOCK_ERR_ARG = 1,    /* invalid argument */
  SWARF_STOCK_ERR_IO = 2,     /* file could not be read or written */
  SWARF_STOCK_ERR_FORMAT = 3, /* file is not a usable level set */
  SWARF_STOCK_ERR_MEMORY = 4,
  SWARF_STOCK_ERR_INTERNAL = 5 /* an exception from OpenVDB, message says which */
} swarf_stock_status;

typedef struct swarf_stock swarf_stock;

/* Signed distance (mm, < 0 inside) of the volume to remove, at world point
 * (x, y, z). Must be 1-Lipschitz (a true or underestimated distance) so that
 * whole blocks can be skipped; must be safe to call from several threads. */
typedef double (*swarf_stock_sdf_fn)(const void *ctx, double x, double y, double z);

/* A box stock [lo, hi] (mm), lo < hi componentwise. `msg` (may be NULL)
 * receives a reason on failure, `msglen` bytes at most. NULL on failure. */
swarf_stock *swarf_stock_new_box(const double lo[3], const double hi[3], double voxel,
                                 int half_width, char *msg, size_t msglen);

/* A cylinder stock about the x, y or z axis (axis 0, 1, 2) through the origin:
 * radius (mm) > 0, from start to end (mm, start < end) along the axis. For
 * rotary work. Exact signed distance near its surface, like the box. */
swarf_stock *swarf_stock_new_cylinder(int axis, double radius, double start, double end,
                                      double voxel, int half_width, char *msg, size_t msglen);

/* Read the grid named "stock" (or the first float level set) of a .vdb file. */
swarf_stock *swarf_stock_read(const char *path, char *msg, size_t msglen);

void swarf_stock_free(swarf_stock *s);

/* Remove the volume {sdf < 0} inside the bounds [lo, hi] (mm, the volume's
 * own bounds; the stock pads them by the narrow band): stock = max(stock, -sdf). */
int swarf_stock_remove(swarf_stock *s, const double lo[3], const double hi[3],
                       swarf_stock_sdf_fn sdf, const void *ctx, char *msg, size_t msglen);

/* Remove a batch of volumes at once (one TBB pass over the union of their
 * bounds); equivalent to calling swarf_stock_remove for each. */
typedef struct {
  double lo[3], hi[3];
  swarf_stock_sdf_fn sdf;
  const void *ctx;
} swarf_stock_cut;
int swarf_stock_remove_batch(swarf_stock *s, const swarf_stock_cut *cuts, size_t ncuts,
                             char *msg, size_t msglen);

/* Whether the volume {sdf < 0} of `cut` overlaps the material by more than
 * `depth` mm: some voxel centre lies deeper than `depth` inside both (stock
 * value < -depth and sdf < -depth; 0 <= depth < the band half-width in mm).
 * Read-only: the stock is not changed. *hit gets 1 or 0; where (may be NULL)
 * the first such voxel centre found (mm). For a rapid move that would cut. */
int swarf_stock_overlaps(const swarf_stock *s, const swarf_stock_cut *cut, double depth, int *hit,
                         double where[3], char *msg, size_t msglen);

/* Whether the volume {sdf < 0} of `cut` penetrates the material by more than
 * `depth` mm (>= 0): at some voxel centre p the two signed depths add up to
 * more, -v - sdf(p) > depth (v: the stock value; voxels outside the band, at
 * +band, are not looked at). This is max over points of "how deep p lies in
 * the material plus how deep in the body": negative (minus the gap) for
 * bodies apart, the thickness of the overlap where the two surfaces are
 * parallel (a holder's face entering a flat face: the same at every point
 * between them, so no voxel centre needs to fall inside a thin overlap), a
 * lower bound of the depth elsewhere; deeper than the band, v is -band and
 * the sum a lower bound again. Read-only; *hit gets 1 or 0, where (may be
 * NULL) the first such voxel centre found. For the non-cutting parts of a
 * tool (tools/sim/collide.c). */
int swarf_stock_penetrates(const swarf_stock *s, const swarf_stock_cut *cut, double depth,
                           int *hit, double where[3], char *msg, size_t msglen);

/* Facts about the grid. */
double swarf_stock_voxel(const swarf_stock *s);
int swarf_stock_half_width(const swarf_stock *s);
/* Enclosed volume, mm^3: voxel^3 times the sum over all voxels of the inside
 * fraction clamp(1/2 - value/voxel, 0, 1) (exact for faces parallel to voxel
 * faces; about 0.1 % on the removed volume of a 2 mm ball at 0.1 mm voxels).
 * NaN for a NULL stock. */
double swarf_stock_volume(const swarf_stock *s);
unsigned long long swarf_stock_active_voxels(const swarf_stock *s);
void swarf_stock_bounds(const swarf_stock *s, double lo[3], double hi[3]); /* active bbox, mm */

/* Interpolated value of the level set at a world point (mm). */
double swarf_stock_sample(const swarf_stock *s, double x, double y, double z);
/* Value stored at the voxel nearest to a world point, and its centre. */
double swarf_stock_voxel_value(const swarf_stock *s, double x, double y, double z,
                               double centre[3]);

/* Visit every active voxel: fn(ctx, centre, value). */
typedef void (*swarf_stock_visit_fn)(void *ctx, const double centre[3], float value);
void swarf_stock_visit_active(const swarf_stock *s, swarf_stock_visit_fn fn, void *ctx);

/* OpenVDB's checkLevelSet: 0 if the grid is a valid narrow-band level set,
 * else -1 with the diagnosis in msg. Runs checks 1 to 8 (type, class, uniform
 * voxels, background, no active tiles, finite values, active values within the
 * band, inactive values at +-band); check 9 (Eikonal |grad| near 1 at zero
 * crossings) is left out: it fails at every sharp edge of an exact distance
 * field, OpenVDB's own createLevelSetBox included. */
int swarf_stock_check(const swarf_stock *s, char *msg, size_t msglen);

/* Outputs, each written atomically (temporary name, then rename). */
int swarf_stock_write_vdb(const swarf_stock *s, const char *path, char *msg, size_t msglen);
/* Binary STL of the zero isosurface; *ntri (may be NULL) gets the triangle count. */
int swarf_stock_write_stl(const swarf_stock *s, const char *path, size_t *ntri, char *msg,
                          size_t msglen);
/* Shaded picture (PNG, width x height) of the stock seen from above at an
 * angle, ray traced with OpenVDB's LevelSetRayTracer. */
int swarf_stock_write_png(const swarf_stock *s, const char *path, int width, int height,
                          char *msg, size_t msglen);

#ifdef __cplusplus
}
#endif
#endif
