/* rotation_kernels.c — which code runs a rotation (sh_rot_kernel, rotate.h).  The unrolled kernels
 * (rot_fast.c, generated straight-line code for zxzxz and the Taylor methods
 * up to order SH_UNROLLED_MAX_ORDER) exist as one object per variant: the
 * plain one (default flags, one lane) and, on x86-64, one per ISA — `avx2`
 * and `avx512` (one lane, AVX2 + FMA, or AVX-512's 32 registers) and the
 * SIMD-lane objects `sse2v`, `avx2v`, `avx512v` used for batches
 * (rot_simd.h).  A variant is used only if it is
 * compiled in and the CPU runs it (CPUID, and XGETBV for the OS saving the
 * YMM/ZMM registers); the choice is made in plan create and kept in the
 * plan, so no global state is written after start-up. */
#include "rotate/rot_internal.h"

#include <pthread.h>
#include <string.h>

extern const sh__rot_fast_d sh__rot_fast_base_d;
extern const sh__rot_fast_f sh__rot_fast_base_f;
#if defined(__x86_64__)
#define SH_FAST_X86 1
#include <cpuid.h>
extern const sh__rot_fast_d sh__rot_fast_avx2_d, sh__rot_fast_avx512_d, sh__rot_fast_sse2v_d,
    sh__rot_fast_avx2v_d, sh__rot_fast_avx512v_d;
extern const sh__rot_fast_f sh__rot_fast_avx2_f, sh__rot_fast_avx512_f, sh__rot_fast_sse2v_f,
    sh__rot_fast_avx2v_f, sh__rot_fast_avx512v_f;

static unsigned long long xcr0(void)
{
    unsigned a, d;
    __asm__ volatile("xgetbv" : "=a"(a), "=d"(d) : "c"(0));
    return ((unsigned long long)d << 32) | a;
}
#endif

static const char *const kernel_names[SH_KERNEL_N] = {
    [SH_KERNEL_AUTO] = "auto",  [SH_KERNEL_SCALAR] = "scalar", [SH_KERNEL_UNROLLED] = "unrolled",
    [SH_KERNEL_SSE2] = "sse2",  [SH_KERNEL_AVX2] = "avx2",     [SH_KERNEL_AVX512] = "avx512",
};

const char *sh_rot_kernel_name(sh_rot_kernel k)
{
    return (k >= 0 && k < SH_KERNEL_N) ? kernel_names[k] : "?";
}

int sh_rot_kernel_parse(const char *s, sh_rot_kernel *out)
{
    for (int k = 0; k < SH_KERNEL_N; k++)
        if (s && !strcmp(s, kernel_names[k])) {
            *out = (sh_rot_kernel)k;
            return SH_OK;
        }
    return sh_error(SH_EINVAL, "unknown kernel '%s' (auto, scalar, unrolled, sse2, avx2, avx512)",
                    s ? s : "");
}

/* What CPUID and XGETBV say, read once per process (pthread_once: no data
 * race however many threads create rotators at once); inside a virtual
 * machine each CPUID can cost microseconds. */
static int cpu_avx2, cpu_avx512;
static pthread_once_t cpu_once = PTHREAD_ONCE_INIT;
static void read_cpu(void);

int sh_rot_kernel_available(sh_rot_kernel k)
{
    switch (k) {
    case SH_KERNEL_AUTO:
    case SH_KERNEL_SCALAR:
    case SH_KERNEL_UNROLLED: return 1;
#ifdef SH_FAST_X86
    case SH_KERNEL_SSE2: return 1; /* x86-64 baseline */
    case SH_KERNEL_AVX2: pthread_once(&cpu_once, read_cpu); return cpu_avx2;
    case SH_KERNEL_AVX512: pthread_once(&cpu_once, read_cpu); return cpu_avx512;
#endif
    default: return 0;
    }
}

static int cpu_runs(sh_rot_kernel k)
{
    switch (k) {
    case SH_KERNEL_AUTO:
    case SH_KERNEL_SCALAR:
    case SH_KERNEL_UNROLLED: return 1;
#ifdef SH_FAST_X86
    case SH_KERNEL_SSE2: return 1; /* x86-64 baseline */
    case SH_KERNEL_AVX2:
    case SH_KERNEL_AVX512: {
        unsigned a, b, c, d;
        if (!__get_cpuid(1, &a, &b, &c, &d)) return 0;
        const int fma = (c & bit_FMA) != 0, osxsave = (c & bit_OSXSAVE) != 0, avx = (c & bit_AVX) != 0;
        if (!fma || !osxsave || !avx || __get_cpuid_max(0, NULL) < 7) return 0;
        const unsigned long long x = xcr0();
        __cpuid_count(7, 0, a, b, c, d);
        if (k == SH_KERNEL_AVX2) return (x & 6) == 6 && (b & bit_AVX2) != 0; /* XMM, YMM saved */
        return (x & 0xe6) == 0xe6 && (b & bit_AVX2) && (b & bit_AVX512F) && (b & bit_AVX512VL); /* + opmask, ZMM */
    }
#endif
    default: return 0;
    }
}

static void read_cpu(void)
{
    cpu_avx2 = cpu_runs(SH_KERNEL_AVX2);
    cpu_avx512 = cpu_runs(SH_KERNEL_AVX512);
}

/* AUTO: the widest the CPU runs — AVX-512 (for one rotation its 32
 * registers, for batches 16 float lanes: both measured fastest, docs/rotation.md
 * "Rotation speed"), else AVX2, else SSE2, else the plain unrolled code. */
sh_rot_kernel sh__rot_kernel_auto(void)
{
    if (sh_rot_kernel_available(SH_KERNEL_AVX512)) return SH_KERNEL_AVX512;
    if (sh_rot_kernel_available(SH_KERNEL_AVX2)) return SH_KERNEL_AVX2;
    if (sh_rot_kernel_available(SH_KERNEL_SSE2)) return SH_KERNEL_SSE2;
    return SH_KERNEL_UNROLLED;
}

/* the unrolled tables of kernel k: one lane (single vectors) and SIMD lanes
 * (batches) */
void sh__rot_kernel_tables(sh_rot_kernel k, const sh__rot_fast_d **d1, const sh__rot_fast_d **dv,
                          const sh__rot_fast_f **f1, const sh__rot_fast_f **fv)
{
    *d1 = *dv = &sh__rot_fast_base_d;
    *f1 = *fv = &sh__rot_fast_base_f;
#ifdef SH_FAST_X86
    switch (k) {
    case SH_KERNEL_SSE2: *dv = &sh__rot_fast_sse2v_d, *fv = &sh__rot_fast_sse2v_f; break;
    case SH_KERNEL_AVX2:
        *d1 = &sh__rot_fast_avx2_d, *f1 = &sh__rot_fast_avx2_f;
        *dv = &sh__rot_fast_avx2v_d, *fv = &sh__rot_fast_avx2v_f;
        break;
    case SH_KERNEL_AVX512:
        *d1 = &sh__rot_fast_avx512_d, *f1 = &sh__rot_fast_avx512_f;
        *dv = &sh__rot_fast_avx512v_d, *fv = &sh__rot_fast_avx512v_f;
        break;
    default: break;
    }
#else
    (void)k;
#endif
}

int sh__rot_fast_method(sh_rot_method m)
{
    switch (m) {
    case SH_ROT_ZXZXZ: return SH__FAST_ZXZXZ;
    case SH_ROT_TAYLOR1: return SH__FAST_TAYLOR1;
    case SH_ROT_TAYLOR15: return SH__FAST_TAYLOR15;
    case SH_ROT_TAYLOR2: return SH__FAST_TAYLOR2;
    case SH_ROT_IVANIC: return SH__FAST_IVANIC;
    default: return -1;
    }
}
