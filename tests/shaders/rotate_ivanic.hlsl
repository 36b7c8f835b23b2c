// rotate_ivanic.hlsl — the HLSL twin of rotate_ivanic.glsl (the same
// Ivanic-Ruedenberg recurrence, written independently of shlab's C code),
// under shlab's shader convention (docs/check-your-kernel.md, "Shaders"):
// one invocation rotates one vector of real SH coefficients (index
// l(l+1)+m, Condon-Shortley phase); orders above MAXO are declined.
struct Params { uint order; uint count; uint form; uint pad; };
[[vk::push_constant]] Params pc;
[[vk::binding(0, 0)]] StructuredBuffer<float> rot;
[[vk::binding(1, 0)]] StructuredBuffer<float> x;
[[vk::binding(2, 0)]] RWStructuredBuffer<float> y;
[[vk::binding(3, 0)]] RWStructuredBuffer<uint> status;

#define MAXO 10
#define MAXW (2 * MAXO - 1)

static float R1[3][3];        // band 1 (m = -1, 0, 1)
static float B0[MAXW * MAXW]; // band l-1
static float B1[MAXW * MAXW]; // band l

float prev(int L, int a, int b) { return B0[(a + L) * (2 * L + 1) + (b + L)]; }

// The paper's P function from R^1 and R^{l-1}.
float P(int i, int l, int a, int b)
{
    float r1 = R1[i + 1][2], rm1 = R1[i + 1][0], r0 = R1[i + 1][1];
    int L = l - 1;
    if (b == l) return r1 * prev(L, a, L) - rm1 * prev(L, a, -L);
    if (b == -l) return r1 * prev(L, a, -L) + rm1 * prev(L, a, L);
    return r0 * prev(L, a, b);
}

float cs(int m) { return (m & 1) != 0 ? -1.0 : 1.0; }

void rotation_matrix(uint k, out float R[9])
{
    if (pc.form == 0u) {
        for (int i = 0; i < 9; i++) R[i] = rot[9u * k + uint(i)];
    } else if (pc.form == 1u) {
        float w = rot[4u * k], qx = rot[4u * k + 1u], qy = rot[4u * k + 2u], qz = rot[4u * k + 3u];
        R[0] = 1.0 - 2.0 * (qy * qy + qz * qz); R[1] = 2.0 * (qx * qy - w * qz);       R[2] = 2.0 * (qx * qz + w * qy);
        R[3] = 2.0 * (qx * qy + w * qz);       R[4] = 1.0 - 2.0 * (qx * qx + qz * qz); R[5] = 2.0 * (qy * qz - w * qx);
        R[6] = 2.0 * (qx * qz - w * qy);       R[7] = 2.0 * (qy * qz + w * qx);       R[8] = 1.0 - 2.0 * (qx * qx + qy * qy);
    } else {
        // R = Rz(a) Ry(b) Rz(g)
        float a = rot[3u * k], b = rot[3u * k + 1u], g = rot[3u * k + 2u];
        float ca = cos(a), sa = sin(a), cb = cos(b), sb = sin(b), cg = cos(g), sg = sin(g);
        R[0] = ca * cb * cg - sa * sg; R[1] = -ca * cb * sg - sa * cg; R[2] = ca * sb;
        R[3] = sa * cb * cg + ca * sg; R[4] = -sa * cb * sg + ca * cg; R[5] = sa * sb;
        R[6] = -sb * cg;               R[7] = sb * sg;                 R[8] = cb;
    }
}

[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID)
{
    uint k = id.x;
    if (k >= pc.count) return;
    int order = int(pc.order);
    if (order < 1 || order > MAXO) { status[k] = 1u; return; }
    uint base = k * uint(order * order);
    y[base] = x[base];
    if (order == 1) return;
    float R[9];
    rotation_matrix(k, R);
    // band 1: m = -1, 0, 1 ↔ y, z, x, so R^1 = P R Pᵀ with that permutation
    int ax[3] = { 1, 2, 0 };
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) { R1[i][j] = R[ax[i] * 3 + ax[j]]; B0[i * 3 + j] = R1[i][j]; }
    for (int l = 1; l < order; l++) {
        int w = 2 * l + 1;
        if (l >= 2) {
            for (int m = -l; m <= l; m++)
                for (int mp = -l; mp <= l; mp++) {
                    int am = abs(m);
                    float d0 = m == 0 ? 1.0 : 0.0;
                    float den = abs(mp) < l ? float((l + mp) * (l - mp)) : float(2 * l * (2 * l - 1));
                    float u = sqrt(float((l + m) * (l - m)) / den);
                    float v = 0.5 * sqrt((1.0 + d0) * float((l + am - 1) * (l + am)) / den) * (1.0 - 2.0 * d0);
                    float wc = -0.5 * sqrt(float((l - am - 1) * (l - am)) / den) * (1.0 - d0);
                    float U = am < l ? P(0, l, m, mp) : 0.0;
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
            for (int mp = -l; mp <= l; mp++) s += B0[(m + l) * w + (mp + l)] * cs(mp) * x[base + uint(l * l + l + mp)];
            y[base + uint(l * l + l + m)] = cs(m) * s;
        }
    }
}
