/* SPDX-License-Identifier: MPL-2.0 */
/* stock.h -- the workpiece as an OpenVDB narrow-band level set (plain C API).
 *
 * Role: hold the remaining material as a float level-set grid named "stock"
 * (negative inside material), remove swept volumes from it in place with
 * stock = max(stock, -sweep), and read and write it: .vdb, binary STL mesh,
 * PNG picture from OpenVDB's level-set ray tracer. The C++ behind this header
 * (the .cc files in stock/) is the only code that includes OpenVDB; no exception crosses
 * into C: every call that can fail returns a swarf_status and fills a
 * swarf_error (err, may be NULL; its file is the file read or written).
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

#include "swarf_status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct swarf_stock swarf_stock;

/* Signed distance (mm, < 0 inside) of the volume to remove, at world point
 * (x, y, z). Must be 1-Lipschitz (a true or underestimated distance) so that
 * whole blocks can be skipped; must be safe to call from several threads. */
typedef double (*swarf_stock_sdf_fn)(const void *ctx, double x, double y, double z);

/* A box stock [lo, hi] (mm), lo < hi componentwise, into *out.
 * SWARF_ERR_ARG (bad dimensions) or SWARF_ERR_MEMORY with the reason in
 * *err (may be NULL); *out is then NULL. */
SWARF_API swarf_status swarf_stock_new_box(const double lo[3], const double hi[3], double voxel,
                                           int half_width, swarf_stock **out, swarf_error *err);

/* A cylinder stock about the x, y or z axis (axis 0, 1, 2) through the origin:
 * radius (mm) > 0, from start to end (mm, start < end) along the axis. For
 * rotary work. Exact signed distance near its surface, like the box. */
SWARF_API swarf_status swarf_stock_new_cylinder(int axis, double radius, double start, double end,
                                                double voxel, int half_width, swarf_stock **out,
                                                swarf_error *err);

/* The box or cylinder stock above built only in its slab of the index space
 * (stock.h's "Slabs of the stock"), for a process that keeps to that slab:
 * the blocks whose origin lies in the index box [rlo, rhi] (rounded as
 * swarf_stock_set_region does, which is set on the new stock) hold the
 * values, active states and leaves of the whole build; the others hold the
 * outside background, as after swarf_stock_slab_crop; the index box
 * (swarf_stock_index_box) and the index mapping are the whole stock's. A
 * region with no block origin (rlo > rhi on an axis) builds nothing: a
 * shell with the whole stock's index box, voxel and band. Memory: about the
 * slab's share of the whole build's. Errors as the whole builds'; rlo or rhi
 * NULL is SWARF_ERR_ARG. */
SWARF_API swarf_status swarf_stock_new_box_slab(const double lo[3], const double hi[3],
                                                double voxel, int half_width, const int rlo[3],
                                                const int rhi[3], swarf_stock **out,
                                                swarf_error *err);
SWARF_API swarf_status swarf_stock_new_cylinder_slab(int axis, double radius, double start,
                                                     double end, double voxel, int half_width,
                                                     const int rlo[3], const int rhi[3],
                                                     swarf_stock **out, swarf_error *err);

/* Read the grid named "stock" (or the first float level set) of a .vdb file
 * into *out: SWARF_ERR_OPEN when it cannot be opened, SWARF_ERR_FORMAT when
 * it is not a usable level set (err->file is the path). OpenVDB's reader is
 * not hardened, so the program swarf-vdb-read reads the file in a child
 * (stock/isolate.h: where it is looked for; SWARF_VDB_READER) and sends the
 * grid back: a crash, hang or runaway allocation there is an error here. */
SWARF_API swarf_status swarf_stock_read(const char *path, swarf_stock **out, swarf_error *err);

/* A stock from a band file that swarf_stock_write_band wrote: its grid,
 * value for value, parsed here (no child, no OpenVDB parser: the design
 * cache keeps a design's band so). SWARF_ERR_OPEN when it cannot be opened,
 * SWARF_ERR_FORMAT for anything else: another magic or version, a size or
 * checksum that does not match, a node out of range, a grid that
 * swarf_stock_read would refuse. */
SWARF_API swarf_status swarf_stock_read_band(const char *path, swarf_stock **out, swarf_error *err);

/* An embedding program that must not fork (or reads only files it wrote)
 * turns the child off with swarf_stock_set_read_isolation(0), or with the
 * environment variable SWARF_VDB_ISOLATE=0; the file is then read in the
 * calling process. The call wins over the variable; 1 turns the child back
 * on. Process-wide, for the reads that start after it; any thread. */
SWARF_API void swarf_stock_set_read_isolation(int on);
/* 1 when reads run in a child process (the call's setting, else the variable's). */
SWARF_API int swarf_stock_read_isolation(void);

SWARF_API void swarf_stock_free(swarf_stock *s);

/* Remove the volume {sdf < 0} inside the bounds [lo, hi] (mm, the volume's
 * own bounds; the stock pads them by the narrow band): stock = max(stock, -sdf). */
SWARF_API swarf_status swarf_stock_remove(swarf_stock *s, const double lo[3], const double hi[3],
                                          swarf_stock_sdf_fn sdf, const void *ctx,
                                          swarf_error *err);

/* The sdf at p where only values in (lo, hi) matter (lo < hi): the sdf (to
 * the volume's certified error) if it lies in [lo, hi); below lo any value
 * <= lo that is still >= the sdf; at or above hi any value >= hi. */
typedef double (*swarf_stock_range_fn)(const void *ctx, const double p[3], double lo, double hi);

/* An optional companion of a range function: its value at p for the window
 * (lo, hi) in *d and, when it returns 1 (the value then lies in the window),
 * a plane below the sdf within r of p: sdf(q) >= *pd + g.(q - p) for every q
 * with |q - p| <= r (*pd <= *d). For volumes that are not convex (rotary
 * sweeps) but have such planes near some points. */
typedef int (*swarf_stock_range_plane_fn)(const void *ctx, const double p[3], double lo, double hi,
                                          double r, double *d, double *pd, double g[3]);

/* Remove a batch of volumes at once (one TBB pass over the union of their
 * bounds); equivalent to calling swarf_stock_remove for each. `range` may be
 * NULL (zero-initialise the struct); when set, the removal asks it instead of
 * sdf at the voxels, with hi the value that leaves the voxel as it is and lo
 * the depth that clears it (rotary sweeps prune their search by both).
 * `range_plane` (may be NULL; only with range) replaces range at the centres
 * of 4^3 octants and 2^3 cubes, asked for a plane over their voxels (r their
 * farthest voxel's distance): the removal then evaluates fewer voxels, and
 * the result is the same. */
typedef struct {
  double lo[3], hi[3];
  swarf_stock_sdf_fn sdf;
  const void *ctx;
  swarf_stock_range_fn range;
  swarf_stock_range_plane_fn range_plane;
} swarf_stock_cut;
SWARF_API swarf_status swarf_stock_remove_batch(swarf_stock *s, const swarf_stock_cut *cuts,
                                                size_t ncuts, swarf_error *err);

/* An optional companion of a cut's sdf: the sdf at p = (x, y, z) in *d and,
 * when it returns 1, a unit vector g with sdf(q) >= *d + g.(q - p) for every
 * q (a supporting plane: the volume is convex, so its sdf is, and p may lie
 * inside it or outside). */
typedef int (*swarf_stock_support_fn)(const void *ctx, double x, double y, double z, double *d,
                                      double g[3]);

/* swarf_stock_remove_batch with a companion per cut (support, or support[i],
 * may be NULL: none): the removal bounds each voxel of a 2^3 cube by the
 * plane at the cube's centre instead of by the sdf's 1-Lipschitz bound, so it
 * evaluates the sdf at fewer voxels; the result is the same. */
SWARF_API swarf_status swarf_stock_remove_batch_support(swarf_stock *s, const swarf_stock_cut *cuts,
                                                        const swarf_stock_support_fn *support,
                                                        size_t ncuts, swarf_error *err);

/* Whether the volume {sdf < 0} of `cut` overlaps the material by more than
 * `depth` mm: some voxel centre lies deeper than `depth` inside both (stock
 * value < -depth and sdf < -depth; 0 <= depth < the band half-width in mm).
 * Read-only: the stock is not changed. *hit gets 1 or 0; where (may be NULL)
 * the first such voxel centre found (mm). For a rapid move that would cut. */
SWARF_API swarf_status swarf_stock_overlaps(const swarf_stock *s, const swarf_stock_cut *cut,
                                            double depth, int *hit, double where[3],
                                            swarf_error *err);

/* Whether the volume {sdf < 0} of `cut` penetrates the material by more than
 * `depth` mm (>= 0): at some voxel centre p the two signed depths add up to
 * more, -v - sdf(p) > depth (v: the stock value). This is max over points of
 * "how deep p lies in the material plus how deep in the body": negative
 * (minus the gap) for bodies apart, the thickness of the overlap where the
 * two surfaces are parallel (a holder's face entering a flat face: the same
 * at every point between them), a lower bound of the depth elsewhere;
 * deeper than the band, v is -band and the sum a lower bound again. Only
 * voxel centres inside the material or at most half a voxel outside it are
 * looked at: outside, a cut stock's values are distances only near faces
 * (beside an edge cut by max(), they are short by up to 30 %), and a layer
 * of half a voxel is what an overlap of half a voxel needs to hold a voxel
 * centre in [-thickness, voxel/2]. `clear` (may be NULL; its bounds are not
 * used) is a volume cut away but not removed from the grid yet: the
 * material is then the stock minus it, its depth min(-v, clear sdf).
 * Read-only; *hit gets 1 or 0, where (may be NULL) the first such voxel
 * centre found. For the non-cutting parts of a tool (tools/sim/assembly/collide.c). */
SWARF_API swarf_status swarf_stock_penetrates(const swarf_stock *s, const swarf_stock_cut *cut,
                                              const swarf_stock_cut *clear, size_t nclear,
                                              double depth, int *hit, double where[3],
                                              swarf_error *err);

/* Threads the stock's passes (removal, the checks of cuts) may use: n >= 1,
 * or 0 for all cores (the default). Per handle; not while a pass runs on it. */
SWARF_API swarf_status swarf_stock_set_threads(swarf_stock *s, int n, swarf_error *err);
SWARF_API int swarf_stock_threads(const swarf_stock *s); /* 0: all cores */

/* At most n threads (n >= 1; 0: no limit, the default) for every stock pass
 * of this process, including those no handle's threads govern (building a
 * box or cylinder, the volume, writing a .vdb, reading a design): a
 * program's --threads N. Process-wide; call it before the work starts. */
SWARF_API void swarf_stock_limit_threads(int n);

/* A long removal pass tells `tick` how far it is (done: 0..1 of its blocks)
 * at least every `every` seconds (0: after every chunk of blocks; chunks
 * aim at every / 5 s), from the calling thread, between chunks (no worker
 * runs then: the stock is a valid level set, partly cut, and may be read).
 * A non-zero answer stops the pass: the call returns SWARF_ERR_ABORTED and
 * the stock stays valid. fn NULL: no ticks (one parallel pass). */
typedef int (*swarf_stock_tick_fn)(void *user, double done);
SWARF_API swarf_status swarf_stock_set_tick(swarf_stock *s, swarf_stock_tick_fn fn, void *user,
                                            double every, swarf_error *err);

/* Facts about the grid. */
SWARF_API double swarf_stock_voxel(const swarf_stock *s);
SWARF_API int swarf_stock_half_width(const swarf_stock *s);
/* Enclosed volume, mm^3: voxel^3 times the sum over all voxels of the inside
 * fraction clamp(1/2 - value/voxel, 0, 1) (exact for faces parallel to voxel
 * faces; about 0.1 % on the removed volume of a 2 mm ball at 0.1 mm voxels).
 * NaN for a NULL stock. */
SWARF_API double swarf_stock_volume(const swarf_stock *s);
SWARF_API unsigned long long swarf_stock_active_voxels(const swarf_stock *s);
/* Clears the sheets of no thickness a cut leaves where its surface passes
 * through the voxel centres of a stock face on the lattice (a slot cut to
 * exactly the bottom face): a voxel on the surface (within 1e-9 voxel of 0)
 * whose two neighbours along one axis are both air a full voxel away becomes
 * air, half a voxel out (sheets.cc). Faces, edges and corners of material
 * and floors thinner than a voxel stay. *cleared (may be NULL): the voxels
 * cleared.
 * swarf_sim_finish calls it on the whole stock before the volumes. */
SWARF_API swarf_status swarf_stock_clear_sheets(swarf_stock *s, long long *cleared,
                                                swarf_error *err);
/* Bounding box of the active voxels, mm. */
SWARF_API void swarf_stock_bounds(const swarf_stock *s, double lo[3], double hi[3]);

/* The stock as a dense array (dense.cc). The index box of the active voxels
 * (lo, dims; dims 0 for an empty stock) and the world point of index 0
 * (origin, mm): voxel centre (i, j, k) lies at origin + voxel (i, j, k). */
SWARF_API void swarf_stock_dense_box(const swarf_stock *s, int lo[3], int dims[3],
                                     double origin[3]);
/* The values (mm, < 0 inside, +-the band's half-width beyond it) at the
 * voxel centres of the index box [lo, lo + dims), into out (dims[0] dims[1]
 * dims[2] floats, the last index fastest: C order, as NumPy's (x, y, z)).
 * At most 2^31 values (SWARF_ERR_LIMIT). */
SWARF_API swarf_status swarf_stock_to_dense(const swarf_stock *s, const int lo[3],
                                            const int dims[3], float *out, swarf_error *err);
/* A stock from such an array of signed distances (mm, < 0 inside), value
 * (i, j, k) at origin + voxel (i, j, k): the voxels within the band
 * (|value| < half_width voxel) are its narrow band, and the signs beyond are
 * filled from them, so the array must hold the whole surface with air
 * around it. A value that is not finite is SWARF_ERR_ARG (naming its index);
 * voxel 0.001 to 1000 mm, half_width 3 to 64. */
SWARF_API swarf_status swarf_stock_from_dense(const double origin[3], double voxel,
                                              const int dims[3], const float *values,
                                              int half_width, swarf_stock **out, swarf_error *err);

/* Interpolated value of the level set at a world point (mm). */
SWARF_API double swarf_stock_sample(const swarf_stock *s, double x, double y, double z);
/* Value stored at the voxel nearest to a world point, and its centre. */
SWARF_API double swarf_stock_voxel_value(const swarf_stock *s, double x, double y, double z,
                                         double centre[3]);

/* Visit every active voxel: fn(ctx, centre, value). */
typedef void (*swarf_stock_visit_fn)(void *ctx, const double centre[3], float value);
SWARF_API void swarf_stock_visit_active(const swarf_stock *s, swarf_stock_visit_fn fn, void *ctx);

/* OpenVDB's checkLevelSet: SWARF_OK if the grid is a valid narrow-band level
 * set, else SWARF_ERR_FORMAT with the diagnosis in err->message. Runs checks 1
 * to 8 (type, class, uniform voxels, background, no active tiles, finite
 * values, active values within the band, inactive values at +-band); check 9
 * (Eikonal |grad| near 1 at zero crossings) is left out: it fails at every
 * sharp edge of an exact distance field, OpenVDB's own createLevelSetBox
 * included. */
SWARF_API swarf_status swarf_stock_check(const swarf_stock *s, swarf_error *err);

/* Outputs, each written atomically (temporary name, then rename);
 * SWARF_ERR_IO when the file cannot be written (err->file is the path). */
SWARF_API swarf_status swarf_stock_write_vdb(const swarf_stock *s, const char *path,
                                             swarf_error *err);
/* swarf's own file of the stock's grid (its transform, band and every
 * value; native byte order, for a cache on this machine): for
 * swarf_stock_read_band. */
SWARF_API swarf_status swarf_stock_write_band(const swarf_stock *s, const char *path,
                                              swarf_error *err);
/* Binary STL of the zero isosurface; *ntri (may be NULL) gets the triangle count. */
SWARF_API swarf_status swarf_stock_write_stl(const swarf_stock *s, const char *path, size_t *ntri,
                                             swarf_error *err);
/* Shaded picture (PNG, width x height) of the stock seen from above at an
 * angle, ray traced with OpenVDB's LevelSetRayTracer. */
SWARF_API swarf_status swarf_stock_write_png(const swarf_stock *s, const char *path, int width,
                                             int height, swarf_error *err);

/* ==== Slabs of the stock (several processes on one stock) ===================
 * Removal is pointwise and works per leaf-aligned block of 8^3 voxels, so
 * copies of one stock, each removing the same volumes in its own region of
 * the index space, hold between them the grid one stock would: load the
 * other copies' slabs into one of them and it is that grid, voxel for voxel
 * (same values, active states and tree nodes). Index space: voxel ijk has
 * its centre at origin + voxel * ijk (mm). */

/* The index box (voxels, both ends inclusive) holding all the material and
 * band, as built or read; lo > hi when empty. It never grows. */
SWARF_API void swarf_stock_index_box(const swarf_stock *s, int lo[3], int hi[3]);
/* The index of the voxel whose centre is nearest to world point p (mm). */
SWARF_API void swarf_stock_index_of(const swarf_stock *s, const double p[3], int ijk[3]);

/* Restrict removal (all kinds) and the queries swarf_stock_overlaps,
 * swarf_stock_penetrates and swarf_stock_gouge to the blocks whose origin
 * (a multiple of 8 on each axis) lies in the index box [lo, hi]: the other
 * blocks keep their values and are not looked at (a query then answers for
 * the region only; a measured removal's volumes and gouges are the
 * region's). lo and hi NULL: the whole stock again. SWARF_ERR_ARG if lo > hi. */
SWARF_API swarf_status swarf_stock_set_region(swarf_stock *s, const int lo[3], const int hi[3],
                                              swarf_error *err);

/* Count, per block, the volumes removal visits it for (evaluates them at its
 * voxels: the work): counts[(i n[1] + j) n[2] + k] += that number for the
 * block whose origin is lo + 8 (i, j, k) (lo rounded down to multiples of
 * 8; blocks outside the n[0] x n[1] x n[2] box are not counted). The array
 * is the caller's and must outlive the removals; NULL: off. */
SWARF_API void swarf_stock_set_tally(swarf_stock *s, const int lo[3], const int n[3],
                                     unsigned long long *counts);

/* Free the leaves outside the region (they become outside tiles): a copy
 * that keeps to its region then holds its slab only. The values outside
 * the region are meaningless afterwards, until slabs are loaded there (a
 * slab holds every leaf of its region, so the stock gathering the slabs
 * may be cropped too). Without a region: nothing. */
SWARF_API swarf_status swarf_stock_slab_crop(swarf_stock *s, swarf_error *err);

/* The slab of the stock in its region (the whole stock without one): its
 * blocks below the tree's level-1 nodes, which are the only ones removal
 * changes, into a new buffer *buf (free() it) of *len bytes, for a stock of
 * the same voxel and band on a machine of the same byte order. */
SWARF_API swarf_status swarf_stock_slab_save(const swarf_stock *s, void **buf, size_t *len,
                                             swarf_error *err);
/* Put a saved slab into s: its blocks replace s's (SWARF_ERR_ARG for another
 * voxel or band, SWARF_ERR_FORMAT for a damaged buffer; s may then hold some
 * of its blocks). */
SWARF_API swarf_status swarf_stock_slab_load(swarf_stock *s, const void *buf, size_t len,
                                             swarf_error *err);

/* ==== Stock from files, placement for a setup ====================
 * The functions below return a swarf_status and fill `err` (may be NULL):
 * SWARF_ERR_OPEN (the file cannot be opened), SWARF_ERR_FORMAT (it is not a
 * usable mesh or grid: the message says what and, for meshes, where),
 * SWARF_ERR_ARG (a bad argument), SWARF_ERR_IO (an output cannot be
 * written), SWARF_ERR_MEMORY, SWARF_ERR_INTERNAL. err->file is the input
 * file when there is one. On failure *out is NULL and nothing is written. */

/* Where a stock is placed for the next setup: x' = R x + t with
 * R = Rz(r[2]) Ry(r[1]) Rx(r[0]): rotations about the fixed machine axes
 * through the origin, X first, then Y, then Z (right-hand rule), then the
 * translation. t in mm, r in degrees. All zero: identity. */
typedef struct {
  double t[3]; /* tx, ty, tz, mm */
  double r[3]; /* rx, ry, rz, degrees */
} swarf_stock_placement;

/* Parse "tx=..,ty=..,tz=..,rx=..,ry=..,rz=.." (any subset, any order, each at
 * most once; missing ones are 0). SWARF_ERR_ARG with the bad key or number. */
SWARF_API swarf_status swarf_stock_placement_parse(const char *spec, swarf_stock_placement *out,
                                                   swarf_error *err);

/* A stock from a triangle mesh in an STL file (binary or ASCII, mm), placed
 * by `place` (NULL: as it is), as a level set of `voxel` mm with a band of
 * `half_width` voxels (OpenVDB's meshToLevelSet). The mesh must be closed
 * (every edge shared by exactly two triangles), manifold and consistently
 * oriented, with finite coordinates; an empty mesh, an open one, a
 * non-manifold or an inconsistently oriented one is refused with
 * SWARF_ERR_FORMAT naming the first bad edge's end points. */
SWARF_API swarf_status swarf_stock_read_stl(const char *path, const swarf_stock_placement *place,
                                            double voxel, int half_width, swarf_stock **out,
                                            swarf_error *err);

/* A stock from a .vdb file (the float level set named "stock", or the first
 * float level set): its own voxel size if `voxel` is 0 or equal to the
 * file's (to 1e-9 relative; the grid is then used as it is, values clamped
 * into its band, NaN as outside), else resampled at `voxel` as
 * swarf_stock_resample does (half_width voxels of band; 0: the file's, at
 * least 3). Placed by `place` (NULL: as it is). A file without a float level
 * set, or one without material, is SWARF_ERR_FORMAT. */
SWARF_API swarf_status swarf_stock_read_vdb(const char *path, const swarf_stock_placement *place,
                                            double voxel, int half_width, swarf_stock **out,
                                            swarf_error *err);

/* A new stock: `s` moved by `p`, same voxel and band. Rotations by
 * multiples of 90 degrees with translations by whole voxels permute the
 * voxels exactly; other placements resample the level set (trilinear, errs
 * below ~0.05 voxel on faces, more at sharp edges). */
SWARF_API swarf_status swarf_stock_place(const swarf_stock *s, const swarf_stock_placement *p,
                                         swarf_stock **out, swarf_error *err);

/* A new stock: `s` sampled at `voxel` mm (trilinear) with a band of
 * `half_width` voxels (1 to 64); where that band is wider than the source's,
 * the part beyond the source's reads as outside the band. */
SWARF_API swarf_status swarf_stock_resample(const swarf_stock *s, double voxel, int half_width,
                                            swarf_stock **out, swarf_error *err);

/* ==== Comparison with a design (the part as designed) ========================
 * A design is a swarf_stock too: a level set of the part, negative inside.
 * Deviations are measured up to its band (its "reach", mm, = half_width *
 * voxel): beyond it a deviation reads as the reach (the *_clamped flags say
 * so). SWARF_STOCK_DESIGN_BAND is the band the readers below give a design. */
#define SWARF_STOCK_DESIGN_BAND 2 /* voxels */

/* A design from FILE.stl (a closed mesh, as swarf_stock_read_stl, with
 * SWARF_STOCK_DESIGN_BAND voxels of band) or FILE.vdb (as swarf_stock_read_vdb:
 * its own band, so its reach is that band's), by the file name's extension
 * (case-insensitive); at `voxel` mm (a .vdb: 0 keeps its own). */
SWARF_API swarf_status swarf_stock_read_design(const char *path, double voxel, swarf_stock **out,
                                               swarf_error *err);

/* swarf_stock_read_design with `half_width` voxels of band (1 to 64) for a
 * .stl (a .vdb keeps its own): swarf_stock_design_band's. */
SWARF_API swarf_status swarf_stock_read_design_band(const char *path, double voxel, int half_width,
                                                    swarf_stock **out, swarf_error *err);

/* Gives `design` (read from a .vdb that swarf_stock_read_design_band made
 * from the STL at `path`, as the design cache keeps it) that STL's
 * triangles, which the reader keeps for exact distances beyond the band:
 * then it is the design that reader gives, value for value. The triangles
 * are read at the first such distance asked for, if one is: the STL must
 * not change until then (if it does, that query fails with SWARF_ERR_IO). */
SWARF_API swarf_status swarf_stock_design_surface(swarf_stock *design, const char *path,
                                                  swarf_error *err);

/* Writes the triangles of `design` (read from an STL: swarf_stock_read_design
 * or swarf_stock_design_surface) to `path`, atomically, in the order its exact
 * distances search them (sorting them now if no distance beyond the band was
 * asked for yet), for swarf_stock_design_surface_cached: the design cache
 * keeps them beside the band. SWARF_ERR_ARG for a design without triangles. */
SWARF_API swarf_status swarf_stock_design_surface_save(const swarf_stock *design, const char *path,
                                                       swarf_error *err);

/* swarf_stock_design_surface, the triangles read from `cached` (what
 * swarf_stock_design_surface_save wrote for that STL and voxel: no parsing,
 * welding or sorting), at the first distance asked for. If `cached` cannot be
 * read or is not such a file, it is removed and the STL is read instead. */
SWARF_API swarf_status swarf_stock_design_surface_cached(swarf_stock *design, const char *cached,
                                                         const char *stl, swarf_error *err);

/* The band (voxels) a design read from a mesh at `voxel` mm needs to give
 * the same results as with SWARF_STOCK_DESIGN_BAND, used with `stock` (NULL:
 * one made here at `voxel`) and `tolerance` (mm; <= 0: half the stock's
 * voxel). A mesh's design measures deviations beyond its band on its
 * triangles, so on the stock's lattice (same voxel, origins whole voxels
 * apart) it needs exact values only up to the tolerance and half a voxel
 * (the volumes' inside fractions; depths beyond are measured), and at least
 * one voxel (the removal passes over blocks where the design is a voxel
 * away): max(1, ceil(tolerance / voxel + 1/2)), which makes the read ~1.7x
 * cheaper at the default tolerance (bear, 0.2 mm). Elsewhere (another lattice: the
 * design sampled trilinearly), SWARF_STOCK_DESIGN_BAND. With `views` nonzero
 * (pictures and .ply colours sample the band) the band reaches the colours'
 * default range, 4 tolerances, and one voxel more (at least
 * SWARF_STOCK_DESIGN_BAND, at most 64), so that the colours saturate where
 * the legend says, not at the band. */
SWARF_API int swarf_stock_design_band(const swarf_stock *stock, double voxel, double tolerance,
                                      int views);

/* SWARF_ERR_ARG unless the design's interior and the stock's material
 * overlap (their bounding boxes meet): a design in another frame or
 * another place. Cheap: call it before a run. */
SWARF_API swarf_status swarf_stock_check_design(const swarf_stock *s, const swarf_stock *design,
                                                swarf_error *err);

/* The deviation of a stock from a design. With tolerance t (mm):
 *  gouge  = no material where the design is deeper than t inside it
 *           (material removed from the part); with `initial` (the stock
 *           before the run, may be NULL) only where `initial` had material,
 *           the rest being `missing`;
 *  excess = material farther than t outside the design (left to remove).
 * Volumes are voxel estimates like swarf_stock_volume's: per voxel, the
 * inside fraction in one grid minus that in the other (shifted by t), when
 * positive: exact for faces parallel to voxel faces, and nothing where the
 * two surfaces coincide. Depths: the deepest point of the gouge below the
 * design's surface, the farthest point of the excess above it, each found at
 * a voxel centre p as the distance in the design plus the radius of the ball
 * around p that the region is known to hold (|stock value|, at most one
 * voxel): exact for flat floors and walls, within a voxel always. */
typedef struct {
  double tolerance;      /* mm, as used */
  double reach;          /* mm: deviations beyond it read as it (the design's band) */
  double stock_volume;   /* mm^3 of material */
  double design_volume;  /* mm^3 of the design */
  double gouge_volume;   /* mm^3 */
  double gouge_depth;    /* mm, deepest gouge below the design's surface; 0 if none */
  double gouge_at[3];    /* mm, where (NaN if none) */
  int gouge_clamped;     /* 1: gouge_depth reached the reach: the gouge is deeper */
  double excess_volume;  /* mm^3 */
  double excess_height;  /* mm, largest excess above the design's surface; 0 if none */
  double excess_at[3];   /* mm, where (NaN if none) */
  int excess_clamped;    /* 1: excess_height reached the reach: the excess is larger */
  double missing_volume; /* mm^3 of design deeper than t where `initial` had no
                          * material (0 without `initial`) */
} swarf_stock_deviation;

/* Tolerance <= 0: half the stock's voxel. The grids may have different
 * voxels and origins (the design is sampled trilinearly at the stock's
 * voxel centres). SWARF_ERR_ARG if they do not overlap (as
 * swarf_stock_check_design). */
SWARF_API swarf_status swarf_stock_compare(const swarf_stock *s, const swarf_stock *design,
                                           const swarf_stock *initial, double tolerance,
                                           swarf_stock_deviation *out, swarf_error *err);

/* Per move, before it is removed: how deep the volume {sdf < 0} of `cut`
 * reaches into the design where material is still there. *depth gets the
 * deepest point of cut AND material AND design below the design's surface
 * (mm; estimated as in swarf_stock_compare from the voxel centres inside
 * both the cut and the material), or 0 when it is not deeper than
 * `tolerance` (>= 0); where (may be NULL) its place (NaN when 0).
 * Read-only. The cost is that of swarf_stock_overlaps over the cut's blocks
 * holding material; swarf_stock_remove_batch_measured gives the same per
 * cut of a batch, in order, in one pass. */
SWARF_API swarf_status swarf_stock_gouge(const swarf_stock *s, const swarf_stock *design,
                                         const swarf_stock_cut *cut, double tolerance,
                                         double *depth, double where[3], swarf_error *err);

/* What one cut of a batch did (swarf_stock_remove_batch_measured). */
typedef struct {
  double removed;        /* mm^3 it removed from the stock as it stood: removed_voxels * voxel^3 */
  double removed_voxels; /* the same in voxel volumes, summed per block in whole multiples
                          * of 2^-16 (each block's rounded), so that the sums of parts
                          * of a stock (swarf_stock_set_region) add up to the same bits */
  double gouge_depth;    /* mm, as swarf_stock_gouge against the stock as it stood
                          * (0: none deeper than the tolerance, or no design) */
  double gouge_at[3];    /* mm, where (NaN when gouge_depth is 0) */
} swarf_stock_cut_effect;

/* swarf_stock_remove_batch, measuring each cut in order: cut i acts on the
 * stock left by cuts 0..i-1, and each voxel's change of inside fraction
 * (swarf_stock_volume's estimate) is attributed to the cuts that made it,
 * so the `removed` of all cuts add up to the volume before minus the volume
 * after (to rounding: 2^-17 voxel a block and cut at most). design (may be NULL) and tolerance
 * as in swarf_stock_gouge. effects[ncuts] is filled. The grid ends
 * bit-identical to swarf_stock_remove_batch's. */
SWARF_API swarf_status swarf_stock_remove_batch_measured(
    swarf_stock *s, const swarf_stock_cut *cuts, size_t ncuts, const swarf_stock *design,
    double tolerance, swarf_stock_cut_effect *effects, swarf_error *err);

/* swarf_stock_remove_batch_measured with a companion per cut (support may be
 * NULL, as in swarf_stock_remove_batch_support): fewer sdf evaluations, the
 * same grid and the same effects. */
SWARF_API swarf_status swarf_stock_remove_batch_measured_support(
    swarf_stock *s, const swarf_stock_cut *cuts, const swarf_stock_support_fn *support,
    size_t ncuts, const swarf_stock *design, double tolerance, swarf_stock_cut_effect *effects,
    swarf_error *err);

/* swarf_stock_remove_batch_measured_support for the gouges alone: the same
 * grid and the same gouge_depth and gouge_at per cut, bit for bit, but
 * removed and removed_voxels are 0. It replays only the voxels a design can
 * be gouged at (a design NULL: the plain removal), so a run with a design
 * and without per-line volumes costs little more than a plain one where the
 * program stays off the design. */
SWARF_API swarf_status swarf_stock_remove_batch_gouges_support(
    swarf_stock *s, const swarf_stock_cut *cuts, const swarf_stock_support_fn *support,
    size_t ncuts, const swarf_stock *design, double tolerance, swarf_stock_cut_effect *effects,
    swarf_error *err);

/* ==== Outputs with views and deviation colours ================================ */

typedef enum {
  SWARF_VIEW_ISO = 0, /* from (-1, -1.3, 1.6): above, front left (perspective) */
  SWARF_VIEW_TOP,     /* looking down -Z, X to the right (orthographic, as the next five) */
  SWARF_VIEW_FRONT,   /* looking along +Y (from the operator's side), Z up */
  SWARF_VIEW_BACK,    /* looking along -Y */
  SWARF_VIEW_LEFT,    /* looking along +X */
  SWARF_VIEW_RIGHT,   /* looking along -X */
  SWARF_VIEW_BOTTOM   /* looking up +Z */
} swarf_stock_view;

/* "iso", "top", "front", "back", "left", "right", "bottom". SWARF_ERR_ARG
 * (with the names) otherwise. */
SWARF_API swarf_status swarf_stock_view_parse(const char *name, swarf_stock_view *out,
                                              swarf_error *err);

/* Options of a picture or a mesh. Zero values: 1024 x 768, iso, no design. */
typedef struct {
  int width, height; /* pixels (pictures only) */
  swarf_stock_view view;
  const swarf_stock *design; /* non-NULL: colour by signed deviation from it */
  double tolerance;          /* mm, within +-tolerance is green; <= 0: half a voxel */
  double range;              /* mm, full blue (gouge) / red (excess) at -+range;
                              * <= 0: 4 tolerances */
} swarf_stock_output;

/* A PNG ray traced with OpenVDB's LevelSetRayTracer from opt->view. With a
 * design, the surface is coloured by its signed distance to the design
 * (blue inside = gouge, green within tolerance, red outside = excess) and a
 * legend with the scale in mm is drawn in the picture. */
SWARF_API swarf_status swarf_stock_write_image(const swarf_stock *s, const char *path,
                                               const swarf_stock_output *opt, swarf_error *err);

/* The zero isosurface as a mesh, format by the file name's extension
 * (case-insensitive): .stl (binary), .obj, .ply (binary little-endian; with
 * a design each vertex gets its deviation colour, red green blue, and its
 * signed deviation in mm, property "deviation"). Another extension is
 * SWARF_ERR_ARG. *ntri (may be NULL) gets the triangle count. */
SWARF_API swarf_status swarf_stock_write_mesh(const swarf_stock *s, const char *path,
                                              const swarf_stock_output *opt, size_t *ntri,
                                              swarf_error *err);

#ifdef __cplusplus
}
#endif
#endif
