/* shlab/scene.h — triangle meshes (read with assimp), ray casting (Embree 3),
 * procedural scenes with closed-form answers, Green's transfer vectors,
 * environments, reference shading by direct integration, shading error,
 * pictures.
 * Part of the public API: include <shlab.h>, which includes every part.
 * No assimp or Embree type appears here: meshes are copied out of assimp and
 * the import released in the loading function; the scene object owns the
 * Embree device. */
#ifndef SHLAB_SCENE_H
#define SHLAB_SCENE_H

#include "core.h"
#include "io.h"
#include "project.h"
#include "rotate.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ meshes
 * An indexed triangle mesh in double precision.  Every vertex is a "lighting
 * point" (Green): it gets one transfer vector.  Normals are unit vectors and
 * define the front side (transfer integrates over the hemisphere about the
 * normal).  Coordinates are z up: the environment's θ = 0 is +z. */
typedef struct {
    int nvert, ntri;
    double *pos;    /* 3·nvert */
    double *normal; /* 3·nvert, unit */
    int *tri;       /* 3·ntri vertex indices */
} sh_mesh;
void sh_mesh_free(sh_mesh *m);

/* What validation found (sh_mesh_load / sh_mesh_check).  Edges are counted
 * on the mesh welded by exact position (so that a file storing each
 * triangle's corners separately, with flat normals, still has a topology). */
typedef struct {
    int submeshes;          /* meshes in the file, concatenated */
    int skipped_primitives; /* points and lines in the file (ignored) */
    int degenerate_removed; /* triangles with a repeated corner or zero area, dropped */
    int unused_removed;     /* vertices no kept triangle uses, dropped */
    int normals_computed;   /* the file had no normals: computed (see sh_mesh_check) */
    int boundary_edges;     /* welded edges used by one triangle */
    int nonmanifold_edges;  /* welded edges used by more than two triangles */
    int nonmanifold_a, nonmanifold_b; /* the vertices of the first such edge */
    double bbox_min[3], bbox_max[3];
} sh_mesh_report;

/* Flags of sh_mesh_load / sh_mesh_check. */
#define SH_MESH_ALLOW_NONMANIFOLD 1 /* report non-manifold edges instead of refusing */
#define SH_MESH_COMPUTE_NORMALS 2   /* ignore the file's normals, compute them */
#define SH_MESH_Y_UP 4              /* the file is y up: turned +90° about x, (x,y,z) → (x,−z,y) */
/* Largest mesh accepted (vertices or triangles). */
#define SH_MESH_MAX_ELEMS (1 << 26)
/* Largest mesh file read (bytes). */
#define SH_MESH_MAX_BYTES (1LL << 31)
/* Largest |coordinate| of a vertex (in a file or in memory): inside single
 * precision (3.4e38), in which assimp and Embree hold coordinates, so that
 * none becomes infinite there; beyond it a coordinate is "out of range". */
#define SH_MESH_MAX_COORD 1e38

/* Read a triangle mesh (PLY, OBJ and every other format assimp reads) with
 * assimp's C API: triangulated, node transforms applied, submeshes
 * concatenated, then sh_mesh_check.  The file is read once; PLY and OBJ
 * bytes are first checked by our own readers (header, counts against the
 * file's length, indices, coordinates: a bad file is refused before assimp
 * sees it), and assimp runs in a child process with CPU-time, memory and
 * wall-clock limits, so that its abort, hang or runaway allocation is one
 * error (src/scene/mesh_internal.h).  Errors (one line each): missing or
 * unreadable file (SH_EIO); a format no reader knows, a file the guard or
 * assimp rejects, an importer that failed or went past a limit, no
 * triangle, a non-finite or out-of-range coordinate or normal anywhere in
 * the file, non-manifold edges without SH_MESH_ALLOW_NONMANIFOLD, more than
 * SH_MESH_MAX_ELEMS (SH_EFORMAT).  rep may be NULL. */
int sh_mesh_load(const char *path, int flags, sh_mesh *out, sh_mesh_report *rep);
/* The same from bytes in memory: name (never opened) stands for the file's
 * path in messages and picks the format by its extension as a path would
 * ("x.ply", "x.obj", ...); the importer reads no other file (an OBJ's
 * material library is not read). */
int sh_mesh_load_mem(const void *data, size_t size, const char *name, int flags, sh_mesh *out, sh_mesh_report *rep);
/* Validate and clean a mesh in place: non-finite coordinates or normals,
 * coordinates beyond SH_MESH_MAX_COORD and indices out of range are refused; degenerate triangles (a repeated corner,
 * or area ≤ 1e-14·diag² of the bounding box) and then unused vertices are
 * removed; nothing left is an error; edges are counted (above).  Normals:
 * with m->normal == NULL or SH_MESH_COMPUTE_NORMALS they are computed as the
 * area-weighted mean of the face normals (cross products of the triangle's
 * edges, so faces are taken counter-clockwise) over all vertices at the same
 * position, normalised; a zero normal given or computed is an error.
 * Given normals are normalised. */
int sh_mesh_check(sh_mesh *m, int flags, sh_mesh_report *rep);
/* Deep copy (dst's arrays malloc'd). */
int sh_mesh_copy(const sh_mesh *src, sh_mesh *dst);

/* ------------------------------------------------------- procedural scenes
 * Scenes the project generates, each with answers known in closed form
 * (sh_proc_closed_form).  res is the tessellation (segments per unit of the
 * scene's own parameterisation; larger is finer).
 *   sphere-plane:R,H  sphere of radius R (default 0.5) centred at height H
 *                     (default 1) above the square plane [−2,2]² at z = 0;
 *                     plane normals +z, sphere normals outward.
 *   bowl              interior of the unit hemisphere z ≤ 0 (rim at z = 0),
 *                     normals towards the centre.
 *   box-open:A        interior of the box [−½,½]²×[0,1], normals inward, a
 *                     square hole of half-width A (default 0.25, ≤ ½) in the
 *                     top face.
 *   box-closed        the same box without a hole. */
typedef enum { SH_PROC_SPHERE_PLANE = 0, SH_PROC_BOWL, SH_PROC_BOX_OPEN, SH_PROC_BOX_CLOSED } sh_proc_kind;
typedef struct {
    sh_proc_kind kind;
    double p[2]; /* sphere-plane: R, H; box-open: A */
    int res;     /* 0: the default of the kind */
} sh_proc_scene;
int sh_proc_parse(const char *spec, sh_proc_scene *out);
const char *sh_proc_name(sh_proc_kind k);
int sh_mesh_procedural(const sh_proc_scene *ps, sh_mesh *out);
/* The number of vertices and triangles sh_mesh_procedural makes, without
 * making them (the same builder, counting only; vertices before its mesh
 * check drops unused ones, those inside box-open's hole: an upper bound). */
int sh_proc_size(const sh_proc_scene *ps, long long *nvert, long long *ntri);
/* The shadowed transfer vector (sh_transfer's definition, albedo ρ) of
 * vertex v of the mesh sh_mesh_procedural made, where a closed form exists:
 *   sphere-plane, a plane vertex whose view of the sphere lies wholly above
 *     its horizon: t_i = (ρ/π)[∫_H y_i (n·s) − ∫_cap y_i (n·s)], the cap of
 *     half-angle asin(R/d) about the direction to the centre; the second
 *     integral by the addition theorem (n·s = (4π/3) Σ_m y_1m(n) y_1m(s)),
 *     real Gaunt coefficients and the cap's zonal coefficients, every
 *     coefficient of the order asked;
 *   bowl, every vertex below the rim: the sky is seen through the rim,
 *     whose cosine-weighted view factor from any point of a sphere's inside
 *     is (area of the missing cap)/(4π) = ½ (a sphere's interior view
 *     factors are area fractions), so t_0 = ρ/(2√π): order 1 only;
 *   box-open, a floor vertex off the walls: the view factor of the hole
 *     (parallel rectangle, four corner terms of Howell's catalogue B-3)
 *     gives t_0 = ρ F/√(4π): order 1 only.
 * *known is the number of bands given (order, 1 or 0 when no closed form
 * applies to that vertex).  bound[i] (may be NULL) bounds |t_i − truth| due
 * to the tessellation (the polyhedral sphere lies between its inscribed and
 * circumscribed spheres; the polygonal rim and hole are exact or bounded).
 * lift: the point is p + lift·n, as the rays leave it (sh_scene_ray_origin:
 * ε·diagonal); taken into the sphere-plane and box closed forms. */
int sh_proc_closed_form(const sh_proc_scene *ps, const sh_mesh *m, int v, int order,
                        sh_convention conv, double albedo, double lift, double *t, double *bound, int *known);
/* The same for n vertices at once: vertex verts[k] (every vertex 0..n−1 when
 * verts is NULL) into t + k·order², bound + k·order² (bound may be NULL)
 * and known[k].  The sphere's bound needs the polyhedral sphere's inscribed
 * radius, a pass over every triangle: sh_proc_closed_form makes it per call
 * (when bound is asked), this function once. */
int sh_proc_closed_forms(const sh_proc_scene *ps, const sh_mesh *m, int n, const int *verts, int order,
                         sh_convention conv, double albedo, double lift, double *t, double *bound, int *known);
/* The converged interreflected DC answer under a constant environment of
 * radiance 1 where one exists: bowl ρ/(2−ρ); box-open and sphere-plane with
 * ρ = 1: 1 (the furnace: every ray escapes or meets a surface of radiance
 * 1).  SH_ENOTSUP otherwise. */
int sh_proc_furnace(const sh_proc_scene *ps, double albedo, double *radiance);

/* ------------------------------------------------------------ ray casting */
typedef struct sh_scene sh_scene;
/* Build the Embree scene of a copy of m (validated first with
 * sh_mesh_check's rules for finiteness and indices; the caller keeps m).
 * threads: Embree's build threads and the default for the routines below
 * (0: every online CPU).  The scene owns its device; Embree's errors reach
 * it through the device's error callback and come back as SH_E* with one
 * line.  Robust (watertight) intersection is requested. */
int sh_scene_create(const sh_mesh *m, int threads, sh_scene **out);
void sh_scene_free(sh_scene *s);
const sh_mesh *sh_scene_mesh(const sh_scene *s);
int sh_scene_threads(const sh_scene *s);
/* Diagonal of the bounding box. */
double sh_scene_diag(const sh_scene *s);
typedef struct {
    int hit;        /* 0: the ray left the scene */
    int tri;        /* triangle index */
    double t, u, v; /* distance (dir normalised), barycentrics of corners 1 and 2 */
    int front;      /* the ray met the triangle's front: the side its vertex normals face */
} sh_hit;
/* One ray, from org along dir (normalised here), over (tnear, tfar).  Safe
 * to call from many threads at once. */
int sh_scene_occluded(const sh_scene *s, const double org[3], const double dir[3], double tnear,
                      double tfar, int *occluded);
int sh_scene_intersect(const sh_scene *s, const double org[3], const double dir[3], double tnear,
                       double tfar, sh_hit *hit);
/* The origin of rays leaving vertex v: p + ε·diag·n (Green's offset along
 * the normal; ε = 0 → 1e-4). */
void sh_scene_ray_origin(const sh_scene *s, int v, double eps, double org[3]);

/* ------------------------------------------------------- Green's transfer
 * Transfer vector of vertex x (Green 2003, "Diffuse Unshadowed/Shadowed/
 * Interreflected Transfer"): exit radiance B(x) = Σ_i L_i t_i(x) for a
 * lighting with SH coefficients L_i, where
 *   unshadowed      t_i = (ρ/π) ∫ y_i(s) max(0, n·s) ds,
 *   shadowed        t_i = (ρ/π) ∫ y_i(s) V(x,s) max(0, n·s) ds,
 *   interreflected  the shadowed vector plus bounces: bounce k+1 at x is
 *                   ρ·mean over the rays that meet a front face of the
 *                   bounce-k vectors interpolated at the hit.
 * Estimator: the directions are a jittered s×s grid (s² = rays) mapped to
 * the hemisphere with density cos θ/π (Malley), the same set for every
 * vertex in its tangent frame (Green uses one set for all vertices; his
 * uniform sphere samples with the lower half discarded are replaced by
 * cosine-weighted ones, so the estimator is ρ·mean of y_i V — exact for a
 * constant, which makes the furnace test exact).  The vector is formed in
 * the frame (t, b, n) and rotated to the world by the SH rotation of the
 * frame (sh_scene_rotate_coeffs).  Unshadowed in closed form instead:
 * t_lm = (ρ/π) √(4π/(2l+1)) z_l y_lm(n), z_l the zonal coefficients of
 * max(0, cosθ) (sh_lobe_zonal, e = 1; addition theorem).
 * Interreflection stops when a bounce adds Σ_x‖Δt(x)‖₂ ≤ bounce_tol·Σ_x‖t(x)‖₂
 * or after max_bounces. */
typedef enum { SH_TRANSFER_UNSHADOWED = 0, SH_TRANSFER_SHADOWED, SH_TRANSFER_INTERREFLECTED } sh_transfer_kind;
const char *sh_transfer_kind_name(sh_transfer_kind k);
int sh_transfer_kind_parse(const char *s, sh_transfer_kind *out);
typedef struct {
    sh_transfer_kind kind;
    int order;
    sh_convention conv;
    long rays;            /* per vertex, rounded to a square (0: 1024) */
    unsigned long seed;
    double albedo;        /* ρ in (0, 1] (0: 1) */
    int closed_form;      /* unshadowed: the closed form instead of rays */
    int max_bounces;      /* interreflected (0: 100) */
    double bounce_tol;    /* interreflected (0: 1e-6) */
    double ray_eps;       /* ray origin offset, fraction of the diagonal (0: 1e-4) */
    int threads;          /* 0: the scene's */
    sh_progress_fn progress; /* optional: vertices done, then bounces */
    void *progress_ctx;
    const int *verts;     /* optional (not for interreflected): only these */
    int nverts;           /*   nverts vertices, T row k for vertex verts[k] */
} sh_transfer_opts;
#define SH_TRANSFER_MAX_BOUNCES 1000
typedef struct {
    long long rays;       /* rays cast (all passes) */
    double seconds;       /* wall time of the ray passes */
    double rays_per_s;
    int threads;
    int rays_per_vertex;  /* s² actually used */
    int bounces;          /* interreflected: bounces done */
    double last_bounce_rel; /* the stopping measure of the last bounce */
    int converged;        /* interreflected: stopped by bounce_tol */
    long long escaped;    /* rays of the first pass that left the scene */
    long long backface;   /* rays of the first pass that met a back face */
} sh_transfer_stats;
/* T receives nvert·order² doubles (vertex-major; nverts·order² with
 * verts).  stats may be NULL. */
int sh_transfer(const sh_scene *s, const sh_transfer_opts *o, double *T, sh_transfer_stats *stats);
/* Closed-form unshadowed transfer of one normal (ρ = albedo). */
int sh_transfer_unshadowed(int order, sh_convention conv, double albedo, const double n[3], double *t);

/* Rotate SH coefficients (nchan vectors of order²) by rot with a rotation
 * method, in place allowed: the one place the scenes rotate (lighting,
 * frames), through the rotation plan API. */
int sh_scene_rotate_coeffs(int order, sh_convention conv, sh_rot_method method,
                           const sh_rotation *rot, int nchan, const double *in, double *out);

/* ------------------------------------------------------------ environments
 * Distant lighting L(s): a lat-long image (its pixels as a piecewise
 * constant function, Rec. 709 luminance and the colour channels) or an
 * analytic light.  Optionally rotated: L'(s) = L(Rᵀs). */
typedef struct sh_env sh_env;
int sh_env_from_image(const sh_image *img, sh_env **out); /* lat-long; copied */
int sh_env_from_light(const sh_light *L, sh_env **out);
void sh_env_free(sh_env *e);
/* Luminance at dir (unit), and the colour in rgb (may be NULL; an analytic
 * light is grey). */
double sh_env_eval(const sh_env *e, const double dir[3], double rgb[3]);
/* SH coefficients, 4 channels (Y, R, G, B) of order² each: the image by
 * sh_project_image, a light by its closed form or 2·order+8 Gauss-Legendre
 * nodes (sh_project, QUAD). */
int sh_env_project(const sh_env *e, int order, sh_convention conv, double *coeffs);

/* ------------------------------------------------------------------ shading */
/* B[v] = Σ_{i < order²} L_i T[v·tord² + i] for v < nvert (order ≤ tord). */
int sh_shade(int nvert, int tord, const double *T, int order, const double *L, double *B);
/* Reference exit radiance (luminance) of the shadowed direct lighting,
 *   B(x) = (ρ/π) ∫_H L(Rᵀs) V(x,s) max(0, n·s) ds,
 * by direct integration of the environment itself with ray-cast
 * visibility, at the vertices listed (NULL: all), in `replications`
 * independent replications whose mean is B and whose standard error is se.
 *   An image: the pixels are taken as a piecewise constant function, and
 *   the sum over pixels Σ_p L_p ∫_p V cos is grouped into blocks of b×b
 *   pixels; each block contributes W·V(s)·cos(s)/c_p with one ray per
 *   replication, the pixel p drawn with probability ∝ |L_p| Ω_p c_p
 *   (c_p = max(0, n·centre of p), W = Σ_block |L_p| Ω_p c_p) and s uniform
 *   in p.  Light is thus integrated exactly up to visibility, which alone is
 *   sampled (a sun costs no variance unless it is partly hidden).  Pixels
 *   whose centre lies below the horizon are left out (their part above it
 *   has cos ≤ half a pixel's angle).  b is chosen so that about `samples`
 *   blocks cover the sphere.
 *   An analytic light: `samples` cosine-weighted stratified rays (as
 *   sh_transfer), estimator (ρ/N) Σ V L.
 * rot may be NULL (identity).
 *   Replication r of vertex v draws from a stream seeded by (seed, v, r)
 * alone, so the replications first_replication .. first_replication +
 * replications − 1 of one call and those of another call with the next
 * first_replication are the replications 0 .. k+m−1 of a single call:
 * pooling them (sh_study_refine) is drawing more, not starting again. */
typedef struct {
    long samples;     /* per replication (0: 8192) */
    int replications; /* ≥ 2 (0: 4) */
    unsigned long seed;
    double albedo;    /* (0: 1) */
    double ray_eps;   /* (0: 1e-4) */
    int threads;      /* 0: the scene's */
    sh_progress_fn progress;
    void *progress_ctx;
    int first_replication; /* the index of the first replication drawn (0..1000) */
} sh_reference_opts;
int sh_shade_reference(const sh_scene *s, const sh_env *env, const sh_rotation *rot, const int *verts,
                       int nv, const sh_reference_opts *o, double *B, double *se,
                       sh_transfer_stats *stats);
/* Shading error of B against a reference ref (n values):
 *   rel_l2  = √(Σ (B − ref)²) / √(Σ ref²)          (relative L2 over vertices)
 *   rel_max = max |B − ref| / √(Σ ref² / n)         (worst vertex, in units of
 *             the RMS reference radiance)
 *   ref_l2  = √(Σ se²) / √(Σ ref²)                  (the reference's own
 *             standard error in the rel_l2 measure; se may be NULL → 0). */
typedef struct { double rel_l2, rel_max, ref_l2; } sh_shade_err;
int sh_shade_error(int n, const double *B, const double *ref, const double *se, sh_shade_err *e);

/* ----------------------------------------------------------- shading study
 * What a viewer sees of each approximation, on a scene lit by an
 * environment: shadowed transfer of order max_order at a seeded subset of
 * the vertices, the environment's luminance projected to max_order, and the
 * reference of sh_shade_reference at the same vertices.  The SH shading of
 * order n ≤ max_order uses the first n² coefficients of both (rotation is
 * block diagonal, so rotating at max_order and truncating is rotating at n).
 * Not thread-safe; its routines use threads inside. */
typedef struct sh_study sh_study;
typedef struct {
    int max_order;      /* 0: 12 */
    long rays;          /* transfer rays per vertex (0: 1024) */
    int nverts;         /* vertices studied: a seeded random subset (0: all) */
    unsigned long seed;
    double albedo;      /* 0: 1 */
    sh_reference_opts ref;
    int threads;        /* 0: the scene's */
    sh_progress_fn progress;
    void *progress_ctx;
    int refine;         /* the most sh_study_refine may multiply the reference's
                           replications by (0: 16; 1: never): the cap on its work,
                           min(refine × ref.replications, 1000) replications */
} sh_study_opts;
typedef struct {
    int nverts, max_order;
    sh_transfer_stats transfer, reference; /* the reference at the current rotation
                                              (its refinements summed in) */
    double ref_l2;      /* the reference's own standard error, rel_l2 measure */
    int replications;   /* the reference's replications now (refinements included) */
    int max_replications; /* the cap of sh_study_refine */
} sh_study_info;
int sh_study_create(const sh_scene *s, const sh_env *env, const sh_study_opts *o, sh_study **out);
void sh_study_free(sh_study *st);
/* Rotate the environment (NULL: identity): the reference is recomputed with
 * rays for L(Rᵀs), and the lighting coefficients are rotated by each
 * method on demand. */
int sh_study_set_rotation(sh_study *st, const sh_rotation *rot);
/* Shading error at order n with the lighting rotated by `method` (any
 * method at the identity). */
int sh_study_error(sh_study *st, sh_rot_method method, int order, sh_shade_err *err);
int sh_study_info_get(const sh_study *st, sh_study_info *info);
/* The vertices studied (st keeps them). */
const int *sh_study_vertices(const sh_study *st, int *n);
/* Refine the reference at the current rotation to `replications` in all, by
 * drawing the missing ones and pooling them with those drawn (the result is
 * the reference sh_study_set_rotation would compute with that many; at least
 * 2 are drawn).  Refused above the cap (sh_study_info.max_replications); a
 * count not above the current one changes nothing.  A new rotation starts
 * again from ref.replications. */
int sh_study_refine(sh_study *st, int replications);

/* ------------------------------------------------- trustworthy decisions
 * Every decision of the study rests on comparisons "is the shading error e
 * within the budget E?", e measured against the reference.  The reference's
 * own error r (ref_l2) enters the measured error in quadrature,
 * e_measured² ≈ e² + r², so it biases every comparison, and near E a noisy
 * reference decides instead of the SH error.  The rule (SH_STUDY_MARGIN):
 *   a comparison is trusted when r ≤ min(E, e) / 10,
 * the reference at least ten times below both numbers compared: below E, a
 * failing comparison (e > E) cannot be an artefact of the reference, and a
 * passing one is decided to within r²/(2E) ≤ E/200; below e, the printed
 * error is the SH error's, to within r²/(2e) ≤ e/200 (0.5 %), not the
 * reference's noise.  A decision is trusted when every comparison it rests on
 * is; otherwise it is undecided: no answer, never a guess.
 *   sh_study_decide_* refine the reference first (sh_study_refine), to the
 * replications the 1/√R law of a mean of R replications says brings r to what
 * the rule needs (× 1.25), the largest that some untrusted decision asks for
 * within the cap, at most SH_STUDY_ROUNDS times; a decision whose need lies
 * beyond the cap is not refined for.  All is deterministic given the seed. */
#define SH_STUDY_MARGIN 10.0
#define SH_STUDY_ROUNDS 3
/* What the rule asks of the reference for a comparison of e with E:
 * min(E, e) / SH_STUDY_MARGIN. */
double sh_study_ref_needed(double budget, double err);
/* The replications the 1/√R law says bring ref_l2 (measured with R
 * replications) down to `needed`: ⌈R (ref_l2/needed)²⌉ (R when already met;
 * INT_MAX when needed ≤ 0 or the count would overflow). */
int sh_study_replications_for(double ref_l2, int replications, double needed);

/* The order for a budget: the smallest n ≤ max_order with err(n) ≤ budget,
 * against one reference (error ref_l2).  It rests on the comparisons at
 * orders 1..n (n = max_order when none qualifies): trusted when
 * ref_l2 ≤ min(budget, err(n)) / 10, i.e. below the budget (the failing
 * orders) and below the error at the order decided. */
typedef struct {
    int undecided;     /* 1: the rule fails; order is then 0 and means nothing */
    int order;         /* decided: the order, 0 when none ≤ max_order qualifies */
    double rel_l2;     /* decided: err at the order (at max_order when none) */
    double ref_l2;     /* the reference's error the decision was judged with */
    double ref_needed; /* what the rule asks of it */
} sh_order_decision;
/* err[n − 1] is the error at order n. */
int sh_decide_order(int max_order, const double *err, double ref_l2, double budget, sh_order_decision *d);

/* The largest β of a grid β_0 < β_1 < ... within a budget: the comparisons
 * err_j ≤ budget from j = 0 on, until the first that fails (each β with its
 * own reference, ref_l2[j]).  Trusted when each of these comparisons is
 * (the rule with err_j); otherwise undecided at the first that is not. */
typedef struct {
    int undecided;
    int last;          /* decided: the index of the largest β within the budget
                          (−1: β_0 fails; nbeta − 1: none fails on the grid);
                          undecided: at − 1 (the trusted passes before `at`) */
    int at;            /* the comparison judged: undecided, the first that fails
                          the rule; decided, the one nearest to failing it (the
                          largest ref_l2[j] / needed) */
    double ref_l2;     /* its reference's error */
    double ref_needed; /* what the rule asks of it */
} sh_beta_decision;
int sh_decide_beta(int nbeta, const double *err, const double *ref_l2, double budget, sh_beta_decision *d);

/* The order decision of each of nb budgets at the study's current rotation,
 * the lighting rotated by `method`, the reference refined as above.  err
 * (may be NULL) receives the errors at orders 1..max_order against the final
 * reference. */
int sh_study_decide_orders(sh_study *st, sh_rot_method method, int max_order, int nb, const double *budgets,
                           sh_order_decision *d, sh_shade_err *err);
/* Comparisons at the study's current rotation: err[k] = rel_l2 of
 * (method[k], order[k]) against the reference, refined as above until
 * each comparison with budget[k] is trusted or the cap stops it.  What the
 * walks of sh_decide_beta measure at each β. */
int sh_study_compare(sh_study *st, int n, const sh_rot_method *method, const int *order, const double *budget,
                     double *err);

/* ------------------------------------------------------------------ pictures */
typedef struct {
    double eye[3], target[3], up[3];
    double fov_deg; /* vertical field of view */
    int width, height;
} sh_camera;
/* A camera looking at the centre of m's bounding box from direction
 * view_dir (from the target towards the eye), far enough to see the whole
 * bounding sphere; z up (y up when view_dir is vertical). */
int sh_camera_frame(const sh_mesh *m, const double view_dir[3], double fov_deg, int width, int height,
                    sh_camera *cam);
/* Render: a camera ray through each pixel centre; where it meets a
 * triangle, the per-vertex values vcol (nvert·nchan, vertex-major)
 * interpolated barycentrically; elsewhere the environment seen (bg, may be
 * NULL → 0; its colour when nchan = 3, its luminance when 1).  out gets a
 * planar float image of nchan (1 or 3) channels; free with sh_image_free. */
int sh_render(const sh_scene *s, const sh_camera *cam, int nchan, const double *vcol, const sh_env *bg,
              int threads, sh_image *out);
/* A false-colour map of a 1-channel image: 0 → black, vmax → white through
 * blue, red, yellow (values clamped to [0, vmax]); out has 3 channels. */
int sh_image_colormap(const sh_image *in, double vmax, sh_image *out);
/* Write an 8-bit sRGB PNG (libpng) of a 1- or 3-channel linear image
 * multiplied by exposure (clamped to [0,1], sRGB transfer curve), through a
 * temporary file renamed into place. */
int sh_png_write(const char *path, const sh_image *img, double exposure);

/* ----------------------------------------------------------- radiance cache
 * Křivánek et al. 2005 (Sec. 4.2, after Křivánek, Gautron, Pattanaik &
 * Bouatouch's radiance caching, itself after Ward's irradiance caching):
 * the incident radiance is computed in SH at sparse records, each in its
 * own tangent frame (sh__tangent_frame of the vertex normal), and reused at
 * nearby vertices: a vertex p takes the records i with
 *   1/w_i(p) = ‖p − p_i‖/R_i + √(1 − n·n_i) < a
 * (R_i the harmonic mean distance of the rays leaving p_i, a the allowed
 * error) and interpolates them after rotating each into its own frame,
 *   Λ(p) = Σ_S w_i (R_sh(M_pᵀ M_i) Λ_i) / Σ_S w_i        (their Eq. 1),
 * without translation gradients (as their Table 1).  The β of that
 * rotation is the angle between n and n_i, small by construction, which is
 * where the Taylor rotation was meant to pay off.
 *
 * Incident radiance at a vertex (sh_incident_radiance), R, G, B, in its
 * frame (t, b, n): Λ_c,i = ∫_H L_c(s) V(s) y_i(Mᵀs) ds (plus, with bounce,
 * the light reflected once by the scene), estimated as
 *   environment image: blocks of b×b pixels (about env_samples of them on
 *     the sphere), one sample per block: a pixel drawn ∝ Ω_p·(|R|+|G|+|B|),
 *     s uniform in it, contribution W_block·L_c,p/(|R|+|G|+|B|)_p·V(s)·y(s)
 *     where s is above the horizon (unbiased; light exact up to
 *     visibility, as sh_shade_reference);
 *   analytic light: env_samples stratified uniform hemisphere directions,
 *     (2π/N) Σ L V y;
 *   bounce: `rays` stratified uniform hemisphere directions; a ray meeting
 *     a front face adds (2π/N)·B_d(hit) y, B_d the direct exit radiance
 *     (shadowed transfer of order min(order, 8) with `rays` rays dotted with
 *     the environment's projection, clamped at 0) interpolated
 *     barycentrically at the hit.
 * R_i: the harmonic mean of the hit distances of 64 stratified uniform
 * hemisphere rays per vertex (escaping rays count 1/t = 0), clamped to
 * [rmin, rmax]·diagonal.  Every vertex's random streams depend on (seed,
 * vertex) only, so a record equals the direct computation at its vertex.
 *
 * Record placement (Ward's lazy criterion): the vertices are visited in a
 * seeded random order; a vertex no existing record covers (1/w < a)
 * becomes a record.  Every vertex is then covered by ≥ 1 record.
 *
 * Shading from the local Λ: diffuse B_c = Σ_i t_i Λ_c,i with
 * t = sh_transfer_unshadowed(ẑ) (ρ/π times the clamped cosine); Phong
 * (exponent E, Křivánek's glossy use) B_c = ρ (E+1)/(2π) ∫ Λ_c(s)
 * max(0, r·s)^E ds, r the mirror direction of the direction to `eye`,
 * i.e. Σ_lm Λ_c,lm ρ (E+1)/(2π) √(4π/(2l+1)) z_l y_lm(r), z_l the zonal
 * coefficients of max(0, cosθ)^E (sh_lobe_zonal). */
typedef struct {
    int phong;        /* 0: diffuse; 1: Phong lobe about the mirror direction */
    double exponent;  /* Phong exponent E > 0 */
    double eye[3];    /* Phong: the viewer's position */
} sh_cache_brdf;
typedef struct {
    int order;           /* bands (0: 6) */
    long env_samples;    /* environment samples per record (0: 4096) */
    long rays;           /* bounce rays per record, rounded to a square (0: 1024) */
    int bounce;          /* add one bounce of the direct light */
    double albedo;       /* ρ in (0, 1] (0: 1) */
    double a;            /* allowed error a > 0 (0: 0.2) */
    double rmin, rmax;   /* clamp of R_i, fractions of the diagonal (0: 0.01, 0.25) */
    sh_cache_brdf brdf;
    unsigned long seed;
    double ray_eps;      /* ray origin offset (0: 1e-4 of the diagonal) */
    int threads;         /* 0: the scene's */
    sh_progress_fn progress;
    void *progress_ctx;
} sh_cache_opts;
/* The incident radiance Λ at the listed vertices (NULL: all; nv·3·order²
 * doubles, vertex-major, then R, G, B), by the estimator above. */
int sh_incident_radiance(const sh_scene *s, const sh_env *env, const sh_cache_opts *o, const int *verts, int nv,
                         double *L, sh_transfer_stats *stats);
/* How a record is rotated into a vertex's frame. */
typedef struct {
    sh_rot_method method; /* any method (exact or Taylor) */
    int ignore;           /* 1: not rotated at all (Křivánek's "Ignore" row) */
    double beta_lim;      /* Taylor methods: zxzxz instead where β > beta_lim (≤ 0: never) */
} sh_cache_rot;
typedef struct sh_cache sh_cache;
typedef struct {
    int nverts, records;
    long long uses;          /* (vertex, record) pairs interpolated: one rotation each (3 channels) */
    double mean_uses;        /* per vertex */
    double beta_max, beta_mean, beta_p50, beta_p90, beta_p99; /* angle between n and n_i, radians */
    double harm_clamped_lo, harm_clamped_hi; /* fractions of vertices whose R was clamped */
    double seconds_placement; /* R at every vertex, placement, neighbour lists (wall) */
    double seconds_records;  /* the records' incident radiance (wall) */
    long long rays;          /* rays of the records (and R) */
    int threads;
} sh_cache_info;
/* Compute R at every vertex, place the records, compute them, list each
 * vertex's records with weights and rotations, set up the BRDF. */
int sh_cache_create(const sh_scene *s, const sh_env *env, const sh_cache_opts *o, sh_cache **out);
void sh_cache_free(sh_cache *c);
int sh_cache_info_get(const sh_cache *c, sh_cache_info *info);
/* The vertices that hold records (c keeps them). */
const int *sh_cache_records(const sh_cache *c, int *n);
/* The records vertex v uses: up to max of them, their vertices and 1/w
 * (0: the record sits at v's position with v's normal, and is used alone);
 * returns the number (all of them, even beyond max), or −1 on bad
 * arguments.  sh_cache_radius: R(v), the clamped harmonic mean distance. */
int sh_cache_uses(const sh_cache *c, int v, int max, int *rec_vertex, double *inv_weight);
double sh_cache_radius(const sh_cache *c, int v);
/* The interpolated Λ(v) (3·order²) in v's frame. */
int sh_cache_incident(sh_cache *c, const sh_cache_rot *rot, int v, double *L);
/* Shade every vertex from the cache: B (3·nvert, vertex-major R, G, B).
 * threads 1 for timing.  seconds: wall time of the interpolation and
 * shading loop alone (plans made before); cpu_seconds: the calling
 * thread's CPU time of that loop when threads = 1 (else 0), which time
 * slices lost to other processes do not inflate; fallbacks: Taylor
 * rotations replaced by zxzxz (β > beta_lim). */
typedef struct { double seconds, cpu_seconds; long long rotations, fallbacks; } sh_cache_timing;
int sh_cache_shade(sh_cache *c, const sh_cache_rot *rot, int threads, double *B, sh_cache_timing *t);
/* Time the shading loop of each of n rotation specs in the calling thread:
 * `rounds` rounds, every spec once per round in an order rotated by one
 * each round; a measurement repeats the loop until it has taken
 * min_cpu_seconds of this thread's CPU time (at least once) and gives the
 * CPU seconds per loop in sec[r·n + k].  Loads from other processes lengthen
 * wall time, not this thread's CPU time; ratios of specs within a round
 * are the trustworthy output. */
int sh_cache_bench(sh_cache *c, const sh_cache_rot *rots, int n, int rounds, double min_cpu_seconds, double *sec);
/* Every vertex computed directly (sh_incident_radiance at each) and
 * shaded: B as sh_cache_shade; stats->seconds the wall time.  With the
 * cache's own seed a record's vertex gets exactly the record; another seed
 * gives an independent estimate (the direct computation's noise). */
int sh_cache_shade_direct(sh_cache *c, unsigned long seed, int threads, double *B, sh_transfer_stats *stats);
/* Luminance of 3-channel values: Y[v] = 0.2126 R + 0.7152 G + 0.0722 B. */
void sh_rgb_luminance(int n, const double *rgb, double *Y);

/* ------------------------------------------------------------ shadow fields
 * Wang et al. 2006, Sec. 3.1 (object occlusion fields after Zhou et al.
 * 2005): the occlusion of an occluder is sampled at one distance d0 and
 * scaled to the distance d of each receiver with an SH scaling matrix
 * M(k), k = d/d0 (scale.h), instead of being sampled at many radii.
 * Here the occluder is a sphere (radius R, centre C), whose occlusion from
 * distance d is exactly the cap of half-angle asin(R/d) about the
 * direction to C; its field at d0 is that cap's zonal projection.
 *   exact   the cap projected at d itself (no scaling: what a fully
 *           sampled field gives);
 *   cone    Wang's cone family, k = d/d0, half-angle cone_angle (0: π/4);
 *   sphere  the sphere's own τ: the cap at d (half-angle w_d) linearly
 *           onto the cap at d0 (w0) and the rest of the sphere onto the
 *           rest — exact geometry, so only the truncation of the sampled
 *           field remains.  (The linear family τ = min(k'θ, π) with
 *           k' = w0/w_d is exact geometry too, but spreads the truncated
 *           field's value at θ = π over every θ > π/k'.)
 * With samples ≥ 2, M is tabulated at that many k geometric in [kmin,
 * kmax] (both 0: the receivers' range) and interpolated linearly in k
 * (Wang Sec. 2.2: "40 values of k in an exponential distribution"); k
 * outside the table takes its end.  The field is placed on the direction
 * to C (addition theorem) and the receiver's transfer is the product of
 * shadow fields truncated to the order:
 *   t = P_n(V·c⁺),  V = 1 − O,  c⁺ = sh_transfer_unshadowed(n) (ρ/π times
 * the clamped cosine), by real Gaunt coefficients — so B = Σ L_i t_i is
 * the triple product of lighting, visibility and cosine. */
typedef enum { SH_SF_EXACT = 0, SH_SF_CONE, SH_SF_SPHERE } sh_sf_scaling;
const char *sh_sf_scaling_name(sh_sf_scaling s);
int sh_sf_scaling_parse(const char *s, sh_sf_scaling *out);
#define SH_SF_MAX_ORDER 16
typedef struct {
    int order;             /* ≤ SH_SF_MAX_ORDER */
    sh_sf_scaling scaling;
    double cone_angle;     /* cone: θ0 (0: π/4) */
    double d0;             /* the distance the field is sampled at (> R) */
    int samples;           /* 0: M(k) at every receiver; ≥ 2: a table over k */
    double kmin, kmax;     /* the table's range (both 0: the receivers') */
    double albedo;         /* ρ (0: 1) */
    sh_progress_fn progress; /* receivers done (may be NULL) */
    void *progress_ctx;
} sh_sf_opts;
typedef struct {
    double kmin, kmax;     /* the receivers' k = d/d0 */
    int matrices;          /* scaling matrices computed */
    double seconds;
} sh_sf_stats;
/* The field at distance d (order² coefficients, zonal about +z), M(d/d0)
 * computed directly (samples ignored). */
int sh_sf_field(const sh_sf_opts *o, double radius, double d, double *O);
/* Transfer vectors T (n·order²) at n receivers (positions and unit
 * normals, 3 each) shadowed by the sphere (centre, radius). */
int sh_shadow_field_transfer(const sh_sf_opts *o, const double centre[3], double radius, int n, const double *pos,
                             const double *normal, double *T, sh_sf_stats *stats);

#ifdef __cplusplus
}
#endif
#endif /* SHLAB_SCENE_H */
