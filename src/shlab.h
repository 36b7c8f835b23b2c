/* shlab.h — the public header of libshlab: includes every part, src/shlab/NAME.h.
 *
 * shlab is a numerical verification and analysis workbench for real spherical
 * harmonics (SH).  Conventions (basis, phase, index, rotation direction, image
 * layouts) are pinned in docs/CONVENTIONS.md and summarised in docs/tour.md:
 *   - direction s = (sinθ cosφ, sinθ sinφ, cosθ), z up;
 *   - real SH y_l^m, default convention SH_CS (Condon-Shortley phase inside P,
 *     as Green's P()/SH() code), alternative SH_NOCS (odd m negated);
 *   - flat index i = l(l+1)+m; "order n" = bands 0..n-1 = n² coefficients.
 *
 * Error handling follows GSL's style: every routine that can fail returns an
 * int status (SH_OK = 0); a one-line human-readable reason is kept in a
 * thread-local buffer (sh_last_error()).  No routine calls exit().
 * Numerical kernels never allocate; routines that need scratch space say so.
 */
#ifndef SHLAB_H
#define SHLAB_H

#define SHLAB_VERSION "0.1.0"

#include "shlab/core.h"
#include "shlab/basis.h"
#include "shlab/convention.h"
#include "shlab/io.h"
#include "shlab/project.h"
#include "shlab/rotate.h"
#include "shlab/taylor.h"
#include "shlab/scale.h"
#include "shlab/measure.h"
#include "shlab/verify.h"
#include "shlab/scene.h"

#endif /* SHLAB_H */
