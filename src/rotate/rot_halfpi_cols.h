/* rot_halfpi_cols.h — the column blocks of rot_halfpi.c's stages 3 and 5
 * (see "the stages' column blocks" there), included by it three times: with
 * HPC_VB = 64 (a vector is one AVX-512 register), 32 (one AVX2 register) and
 * 16 (SSE2, NEON), each instance's names made by HPC(x).
 *
 * A block row is HP_W columns (256 bytes), CNV vectors of CNL lanes; a
 * row's partial sums of the dot are HP_AL lanes (64 bytes), CA vectors.  The
 * code holds CG = 4 vectors of each kind at a time: the recursion runs over
 * groups of 4 consecutive vectors, and a job's pass over the rows takes the
 * vectors a, a + CA, a + 2CA, a + 3CA (partial-sum vector a) for one row
 * parity.  Every instance thus does the same operations on every element,
 * in the same order: the same bits; each keeps its working set in the
 * registers of its instruction set (64-byte vectors compiled for AVX2 or
 * SSE2 spill on every row: 2 to 6 times slower). */

#define CNL ((int)(HPC_VB / sizeof(sh_real))) /* lanes a vector */
#define CNV (HP_W / CNL)                      /* vectors a block row: 4 or 8 */
#define CA (HP_AL / CNL)                      /* vectors of a row's partial sums: 1 or 2 */
#define CG 4                                  /* vectors held at a time: CNV = CG·CA */
typedef sh_real HPC(v) __attribute__((vector_size(HPC_VB)));
#ifdef SH_REAL_FLOAT
typedef int32_t HPC(vi) __attribute__((vector_size(HPC_VB)));
#else
typedef int64_t HPC(vi) __attribute__((vector_size(HPC_VB)));
#endif
#define CV HPC(v)
#define CVI HPC(vi)

HP_INLINE CV HPC(ld)(const sh_real *p)
{
    CV v;
    memcpy(&v, p, sizeof v);
    return v;
}
HP_INLINE void HPC(st)(sh_real *p, CV v) { memcpy(p, &v, sizeof v); }

/* y ∧ mask, lane by lane (a −1 lane keeps y, a 0 lane gives +0) */
HP_INLINE CV HPC(and)(CV y, CVI mask)
{
    CVI b;
    memcpy(&b, &y, sizeof b);
    b &= mask;
    memcpy(&y, &b, sizeof y);
    return y;
}

HP_INLINE int HPC(any)(CVI c)
{
    int any = 0;
    for (int i = 0; i < CNL; i++) any |= c[i] != 0;
    return any;
}

/* One row for one job, vectors a + CA·g (g < 4): yd into the dot (acc, the
 * partial-sum vector a of the row), ya into the axpy (T) with the factors
 * kp[0] (even columns), kp[1] (odd); kp[0..CNL−1] readable. */
HP_INLINE void HPC(use)(const CV *yd, const CV *ya, const CV *z, CV *T, const sh_real *kp, sh_real *acc)
{
#ifdef __clang__
    CV k; /* clang has no __builtin_shuffle (its own needs literal indices) */
    for (int i = 0; i < CNL; i++) k[i] = kp[i & 1];
#else
    CVI pair = {0};
    for (int i = 0; i < CNL; i++) pair[i] = i & 1;
    const CV k = __builtin_shuffle(HPC(ld)(kp), pair);
#endif
    const CV p = (yd[0] * z[0] + yd[1] * z[1]) + (yd[2] * z[2] + yd[3] * z[3]);
    HPC(st)(acc, HPC(ld)(acc) + p);
#pragma GCC unroll 4
    for (int g = 0; g < CG; g++) T[g] += ya[g] * k;
}

/* The rows of one chunk (rows rhi − first down to rlo of block m0, in buf
 * from row rhi) for one job: by row parity q (each has its own z and T) and
 * partial-sum vector a, a pass holding one set of accumulators in registers
 * (the order of the operations on any accumulator is that of the rows). */
HP_INLINE void HPC(chunk_job)(const HPJOB *J, const sh_real *buf, int m0, int rhi, int first, int rlo,
                              int st5)
{
    const sh_real *kp = J->kp;
    const int rd = m0 + HP_W - 1; /* rows ≤ rd meet the diagonal */
    for (int q = 0; q < 2; q++)
        for (int a = 0; a < CA; a++) {
            CV z[CG], T[CG];
#pragma GCC unroll 4
            for (int g = 0; g < CG; g++) {
                const int o = m0 + (a + CA * g) * CNL;
                z[g] = HPC(ld)(J->z[q] + o), T[g] = HPC(ld)(J->T[q] + o);
            }
            sh_real *acc = J->acc + a * CNL;
            int r = rhi - first;
            if ((r & 1) != q) r--;
            for (; r >= rlo && r > rd; r -= 2) {
                const sh_real *b = buf + (size_t)(rhi - r) * HP_W + a * CNL;
                CV y[CG];
#pragma GCC unroll 4
                for (int g = 0; g < CG; g++) y[g] = HPC(ld)(b + CA * g * CNL);
                HPC(use)(y, y, z, T, kp + 2 * (size_t)r, acc + (size_t)HP_AL * r);
            }
            CVI idx[CG]; /* the columns */
            for (int g = 0; g < CG; g++)
                for (int i = 0; i < CNL; i++) idx[g][i] = m0 + (a + CA * g) * CNL + i;
            for (; r >= rlo; r -= 2) { /* the diagonal's rows: columns c ≤ r to the dot, c < r to the axpy (stage 3) */
                const sh_real *b = buf + (size_t)(rhi - r) * HP_W + a * CNL;
                CV yd[CG], ya[CG];
#pragma GCC unroll 4
                for (int g = 0; g < CG; g++) {
                    const CV y = HPC(ld)(b + CA * g * CNL);
                    const CVI lt = idx[g] < r, le = idx[g] <= r;
                    yd[g] = HPC(and)(y, st5 ? lt : le);
                    ya[g] = HPC(and)(y, st5 ? le : lt);
                }
                HPC(use)(yd, ya, z, T, kp + 2 * (size_t)r, acc + (size_t)HP_AL * r);
            }
#pragma GCC unroll 4
            for (int g = 0; g < CG; g++) HPC(st)(J->T[q] + m0 + (a + CA * g) * CNL, T[g]);
        }
}

/* A column block's recursion between chunks: rows r+1 (x1) and r+2 (x2) of
 * the block's columns (mantissas), 2m, and for a scaled block the columns'
 * scales 2^−kexp (0: flushed). */
typedef struct {
    CV x1[CNV], x2[CNV], tm[CNV], sc[CNV];
    int kexp[HP_W];
} HPC(blk);

/* Rows rhi..rlo of the block's vectors v0..v0+3 (b: the state at row rhi+1)
 * into buf, row rhi first; *first: the first row (from rhi) with an entry of
 * these vectors ≥ HP_TINY·P_r, if none so far (*active).  The recursion's
 * rows stay in registers (lanes are touched only through b, on the rare
 * rescaling paths). */
HP_INLINE void HPC(gen)(const HPGEN *g, HPC(blk) *b, int scaled, int v0, int rhi, int rlo, sh_real *buf,
                        int *active, int *first)
{
    const int l = g->l;
    CV x1[CG], x2[CG], tm[CG], sc[CG];
#pragma GCC unroll 4
    for (int u = 0; u < CG; u++)
        x1[u] = b->x1[v0 + u], x2[u] = b->x2[v0 + u], tm[u] = b->tm[v0 + u], sc[u] = b->sc[v0 + u];
    int unk = 0; /* the first row (from rhi) not found below HP_TINY */
    for (int r = rhi; r >= rlo; r--) {
        if (r < l) {
            if (g->resc[r]) { /* rows r+1, r+2 / 2^HP_ROW_EXP */
                const sh_real down = (sh_real)ldexp(1.0, -HP_ROW_EXP);
                if (!scaled) {
#pragma GCC unroll 4
                    for (int u = 0; u < CG; u++) x1[u] *= down, x2[u] *= down;
                } else { /* the exponents only */
#pragma GCC unroll 4
                    for (int u = 0; u < CG; u++) b->sc[v0 + u] = sc[u];
                    for (int q = v0 * CNL; q < (v0 + CG) * CNL; q++) {
                        b->kexp[q] += HP_ROW_EXP;
                        b->sc[q / CNL][q % CNL] = b->kexp[q] > HP_FLUSH_K ? 0 : b->sc[q / CNL][q % CNL] * down;
                    }
#pragma GCC unroll 4
                    for (int u = 0; u < CG; u++) sc[u] = b->sc[v0 + u];
                }
            }
            const sh_real c = g->C[r + 2];
#pragma GCC unroll 4
            for (int u = 0; u < CG; u++) {
                const CV x = tm[u] * x1[u] - c * x2[u];
                x2[u] = x1[u];
                x1[u] = x;
            }
            if (scaled && !(r & HP_CHECK_MASK)) {
                /* lanes of row r above 2^HP_RESCALE_EXP: rows r, r+1 scaled down */
                const sh_real lim = (sh_real)ldexp(1.0, HP_RESCALE_EXP);
                CVI big = (x1[0] > lim) | (x1[0] < -lim);
#pragma GCC unroll 4
                for (int u = 1; u < CG; u++) big |= (x1[u] > lim) | (x1[u] < -lim);
                if (HPC(any)(big)) {
                    const sh_real down = (sh_real)ldexp(1.0, -HP_RESCALE_EXP);
#pragma GCC unroll 4
                    for (int u = 0; u < CG; u++) b->x1[v0 + u] = x1[u], b->x2[v0 + u] = x2[u], b->sc[v0 + u] = sc[u];
                    for (int q = v0 * CNL; q < (v0 + CG) * CNL; q++) {
                        const sh_real x = b->x1[q / CNL][q % CNL];
                        if (SH_FABS(x) > lim) {
                            b->x1[q / CNL][q % CNL] = x * down, b->x2[q / CNL][q % CNL] *= down;
                            b->kexp[q] -= HP_RESCALE_EXP;
                            b->sc[q / CNL][q % CNL] = b->kexp[q] > HP_FLUSH_K ? 0 : (sh_real)ldexp(1.0, -b->kexp[q]);
                        }
                    }
#pragma GCC unroll 4
                    for (int u = 0; u < CG; u++) x1[u] = b->x1[v0 + u], x2[u] = b->x2[v0 + u], sc[u] = b->sc[v0 + u];
                }
            }
        }
        sh_real *row = buf + (size_t)(rhi - r) * HP_W + v0 * CNL;
        CV w[CG];
#pragma GCC unroll 4
        for (int u = 0; u < CG; u++) {
            w[u] = scaled ? x1[u] * sc[u] : x1[u];
            HPC(st)(row + u * CNL, w[u]);
        }
        if (!*active && (!(r & 7) || r == rlo)) {
            /* any |w| ≥ HP_TINY·P_r, checked every 8 rows (and at the chunk's
             * end): the stage starts after the last row found below, up to 7
             * rows early (entries below HP_TINY); compared as integers (|w| ≥ 0) */
            CVI mask, tau, x, big;
            CV t;
            for (int i = 0; i < CNL; i++) mask[i] = HP_ABSMASK, t[i] = g->tau[r];
            memcpy(&tau, &t, sizeof tau);
            memcpy(&x, &w[0], sizeof x);
            big = (x & mask) >= tau;
#pragma GCC unroll 4
            for (int u = 1; u < CG; u++) memcpy(&x, &w[u], sizeof x), big |= (x & mask) >= tau;
            if (HPC(any)(big)) *active = 1, *first = unk;
            else unk = rhi - r + 1;
        }
    }
#pragma GCC unroll 4
    for (int u = 0; u < CG; u++) b->x1[v0 + u] = x1[u], b->x2[v0 + u] = x2[u], b->sc[v0 + u] = sc[u];
}

/* Stage 3 (st5 = 0) or 5 over every job (J: nj jobs), the wedge generated
 * once more (hp_start): block by block, HP_R rows at a time, the groups of
 * vectors of the recursion one after the other. */
HP_INLINE uint64_t HPC(cols)(HPGEN *g, int nj, const HPJOB *J, int st5)
{
    const int l = g->l;
    sh_real *buf = g->buf;
    uint64_t count = 0;
    for (int m0 = 0; m0 <= l; m0 += HP_W) {
        HPC(blk) b;
        const int scaled = m0 + HP_W > g->ms; /* any column ≥ ms: all by mantissa and kexp */
        for (int q = 0; q < HP_W; q++) {
            const int m = m0 + q, v = q / CNL, i = q % CNL;
            b.tm[v][i] = (sh_real)(2 * m);
            b.x2[v][i] = 0;
            if (m > l) b.x1[v][i] = 0, b.sc[v][i] = 0, b.kexp[q] = 0;
            else if (m < g->ms) b.x1[v][i] = g->sw[m], b.sc[v][i] = 1, b.kexp[q] = 0;
            else b.x1[v][i] = g->sx[m], b.sc[v][i] = g->ssc[m], b.kexp[q] = g->skexp[m];
        }
        int active = 0;
        for (int rhi = l; rhi >= m0; rhi -= HP_R) {
            const int rlo = rhi - HP_R + 1 > m0 ? rhi - HP_R + 1 : m0;
            const int none = rhi - rlo + 1;
            int first = active ? 0 : none; /* the chunk's first row for the stage */
            for (int v0 = 0; v0 < CNV; v0 += CG) {
                int act = active, f = none;
                if (scaled) HPC(gen)(g, &b, 1, v0, rhi, rlo, buf, &act, &f);
                else HPC(gen)(g, &b, 0, v0, rhi, rlo, buf, &act, &f);
                if (f < first) first = f;
            }
            if (first < none) active = 1;
            count += (uint64_t)(rhi - rlo + 1) * (scaled ? 3 : 2) * HP_W;
            if (first == none) continue;
            for (int j = 0; j < nj; j++) HPC(chunk_job)(J + j, buf, m0, rhi, first, rlo, st5);
            count += (uint64_t)nj * (uint64_t)(rhi - first - rlo + 1) * 2 * HP_W;
        }
    }
    return count;
}

#undef CNL
#undef CNV
#undef CA
#undef CG
#undef CV
#undef CVI
