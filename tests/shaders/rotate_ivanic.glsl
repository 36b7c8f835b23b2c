#version 450
// rotate_ivanic.glsl — an example shader kernel under shlab's convention
// (docs/check-your-kernel.md, "Shaders"): each invocation rotates one vector
// of real SH coefficients (index l(l+1)+m, Condon-Shortley phase) by one
// rotation, given as a matrix, a quaternion or ZYZ angles (push constant
// `form`).  The rotation is Ivanic and Ruedenberg's recurrence (J. Phys.
// Chem. 100, 6342 (1996); corrections J. Phys. Chem. A 102, 9099 (1998)),
// written here independently of shlab's C code, in the basis without the
// phase (band 1 ∝ y, z, x); the cs sign (-1)^m is applied on the way in
// and out.  Orders above MAXO are declined (status 1).
//
// Deliberate mistakes for the tests (verify --shader F --define NAME):
// MISTAKE_INVERSE (transposed matrix), MISTAKE_CONVENTION (no cs sign),
// MISTAKE_SWAP (α and γ swapped; euler form), MISTAKE_DEG2RAD (angles taken
// as degrees; euler form), MISTAKE_MDESC (m descending within each band);
// and misbehaviour: HANG_ORDER_3 (never finishes at order 3), BROKEN (does
// not compile).
layout(local_size_x = 64) in;
layout(push_constant) uniform Params { uint order; uint count; uint form; uint pad; } pc;
layout(std430, set = 0, binding = 0) readonly buffer Rotations { float rot[]; };
layout(std430, set = 0, binding = 1) readonly buffer Inputs { float x[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Outputs { float y[]; };
layout(std430, set = 0, binding = 3) buffer Status { uint status[]; };

#define MAXO 10
#define MAXW (2 * MAXO - 1)

float R1[3][3];          // band 1 (m = -1, 0, 1)
float B0[MAXW * MAXW];   // band l-1
float B1[MAXW * MAXW];   // band l

float prev(int L, int a, int b) { return B0[(a + L) * (2 * L + 1) + (b + L)]; }

// The paper's P function from R^1 and R^{l-1}.
float P(int i, int l, int a, int b)
{
    const float r1 = R1[i + 1][2], rm1 = R1[i + 1][0], r0 = R1[i + 1][1];
    const int L = l - 1;
    if (b == l) return r1 * prev(L, a, L) - rm1 * prev(L, a, -L);
    if (b == -l) return r1 * prev(L, a, -L) + rm1 * prev(L, a, L);
    return r0 * prev(L, a, b);
}

// index of coefficient (l, m) in a vector, with the mistake of m order
uint at(uint base, int l, int m)
{
#ifdef MISTAKE_MDESC
    return base + uint(l * l + l - m);
#else
    return base + uint(l * l + l + m);
#endif
}

// the cs sign (-1)^m (none for a kernel with the other convention)
float cs(int m)
{
#ifdef MISTAKE_CONVENTION
    return 1.0;
#else
    return (m & 1) != 0 ? -1.0 : 1.0;
#endif
}

void rotation_matrix(uint k, out float R[9])
{
    if (pc.form == 0u) {
        for (int i = 0; i < 9; i++) R[i] = rot[9u * k + uint(i)];
    } else if (pc.form == 1u) {
        const float w = rot[4u * k], qx = rot[4u * k + 1u], qy = rot[4u * k + 2u], qz = rot[4u * k + 3u];
        R[0] = 1.0 - 2.0 * (qy * qy + qz * qz); R[1] = 2.0 * (qx * qy - w * qz);       R[2] = 2.0 * (qx * qz + w * qy);
        R[3] = 2.0 * (qx * qy + w * qz);       R[4] = 1.0 - 2.0 * (qx * qx + qz * qz); R[5] = 2.0 * (qy * qz - w * qx);
        R[6] = 2.0 * (qx * qz - w * qy);       R[7] = 2.0 * (qy * qz + w * qx);       R[8] = 1.0 - 2.0 * (qx * qx + qy * qy);
    } else {
        float a = rot[3u * k], b = rot[3u * k + 1u], g = rot[3u * k + 2u];
#ifdef MISTAKE_SWAP
        const float t = a; a = g; g = t;
#endif
#ifdef MISTAKE_DEG2RAD
        a *= 3.14159265358979 / 180.0; b *= 3.14159265358979 / 180.0; g *= 3.14159265358979 / 180.0;
#endif
        // R = Rz(a) Ry(b) Rz(g)
        const float ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cg = cos(g), sg = sin(g);
        R[0] = ca * cb * cg - sa * sg; R[1] = -ca * cb * sg - sa * cg; R[2] = ca * sb;
        R[3] = sa * cb * cg + ca * sg; R[4] = -sa * cb * sg + ca * cg; R[5] = sa * sb;
        R[6] = -sb * cg;               R[7] = sb * sg;                 R[8] = cb;
    }
#ifdef MISTAKE_INVERSE
    float T[9] = float[9](R[0], R[3], R[6], R[1], R[4], R[7], R[2], R[5], R[8]);
    R = T;
#endif
}

void main()
{
    const uint k = gl_GlobalInvocationID.x;
    if (k >= pc.count) return;
    const int order = int(pc.order);
    if (order < 1 || order > MAXO) { status[k] = 1u; return; }
#ifdef HANG_ORDER_3
    // lavapipe ends every loop of an invocation after 65535 turns in all, so
    // a hang is work: 10³ dependent sines a turn, about 6.6·10⁷ in all
#define X10(s) s s s s s s s s s s
    float h = float(k);
    for (int i = 0; i < 65535 && order == 3; i++) { X10(X10(X10(h = sin(h) + 1.0;))) }
    if (h == 12345.0) status[k] = 2u; // keeps h alive
#endif
#ifdef BROKEN
    this is not GLSL;
#endif
    const uint base = k * uint(order * order);
    y[base] = x[base];
    if (order == 1) return;
    float R[9];
    rotation_matrix(k, R);
    // band 1: m = -1, 0, 1 ↔ y, z, x, so R^1 = P R Pᵀ with that permutation
    const int ax[3] = int[3](1, 2, 0);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) { R1[i][j] = R[ax[i] * 3 + ax[j]]; B0[i * 3 + j] = R1[i][j]; }
    for (int l = 1; l < order; l++) {
        const int w = 2 * l + 1;
        if (l >= 2) {
            for (int m = -l; m <= l; m++)
                for (int mp = -l; mp <= l; mp++) {
                    const int am = abs(m);
                    const float d0 = m == 0 ? 1.0 : 0.0;
                    const float den = abs(mp) < l ? float((l + mp) * (l - mp)) : float(2 * l * (2 * l - 1));
                    const float u = sqrt(float((l + m) * (l - m)) / den);
                    const float v = 0.5 * sqrt((1.0 + d0) * float((l + am - 1) * (l + am)) / den) * (1.0 - 2.0 * d0);
                    const float wc = -0.5 * sqrt(float((l - am - 1) * (l - am)) / den) * (1.0 - d0);
                    const float U = am < l ? P(0, l, m, mp) : 0.0;
                    float V, W = 0.0;
                    if (m == 0) {
                        V = P(1, l, 1, mp) + P(-1, l, -1, mp);
                    } else if (m > 0) {
                        V = P(1, l, m - 1, mp) * (m == 1 ? sqrt(2.0) : 1.0) - (m == 1 ? 0.0 : P(-1, l, -m + 1, mp));
                        if (am + 1 <= l - 1) W = P(1, l, m + 1, mp) + P(-1, l, -m - 1, mp);
                    } else {
                        V = (m == -1 ? 0.0 : P(1, l, m + 1, mp)) + P(-1, l, -m - 1, mp) * (m == -1 ? sqrt(2.0) : 1.0);
                        if (am + 1 <= l - 1) W = P(1, l, m - 1, mp) - P(-1, l, -m + 1, mp);
                    }
                    B1[(m + l) * w + (mp + l)] = u * U + v * V + wc * W;
                }
            for (int i = 0; i < w * w; i++) B0[i] = B1[i];
        }
        // out_m = cs(m) Σ_m' B[m][m'] cs(m') in_m'
        for (int m = -l; m <= l; m++) {
            float s = 0.0;
            for (int mp = -l; mp <= l; mp++) s += B0[(m + l) * w + (mp + l)] * cs(mp) * x[at(base, l, mp)];
            y[at(base, l, m)] = cs(m) * s;
        }
    }
}
