#version 450
// rot_taylor2.glsl — GENERATED FILE, DO NOT EDIT.
//
// Written by tools/gen_rot_unrolled.c:
//   build/tools/gen_rot_unrolled --shader glsl --method taylor2 --max-order 6 > data/shaders/rot_taylor2.glsl
// (`make regen`; `make check` fails if this file differs from the output).
//
// SH rotation by Křivánek et al.'s Taylor approximation (IRISA PI 1728,
// 2005; shlab's taylor2, src/rotate/rot_taylor.c), NOT exact (error
// O(β²) for taylor1 and taylor1.5, O(β³) for taylor2):
//   R_sh ≈ Z(α) T(β) Z(γ),  T = I + βJ + (β²/2) J²
// with J = dR_Y/dβ at 0 (the closed form of rotation_deriv.c), per band,
// positions j = m + l, s_j = J[m][m−1]:
//   y_j = x_j (1 + (β²/2) J²_jj) + β (s_j x_{j−1} − s_{j+1} x_{j+1})
//         + (β²/2) (s_j s_{j−1} x_{j−2} + s_{j+2} s_{j+1} x_{j+2})
// The per-order functions are those of src/rotate/rot_unrolled_gen.h (the
// same emitter), in float: the same operations in the same order, the
// table values rounded to float as shlab's float kernels round them.
//
// shlab's shader convention (docs/check-your-kernel.md): one invocation
// rotates vector k = gl_GlobalInvocationID.x < count of order² real
// orthonormal SH coefficients (index l(l+1)+m; the rotation acts on
// functions, g(s) = f(R⁻¹s)) by rotation k, given as a 3×3 matrix (row-
// major), a quaternion (w, x, y, z) or ZYZ angles (form 0, 1, 2).  Phase:
// Condon-Shortley (cs), or without it (nocs) when compiled with SHLAB_NOCS.
// Orders 1..6; another order sets status 1 (not handled), an unknown
// form status 2.
// Checked against shlab's golden fixtures by tests/cli/test_shaders_shlab.sh:
//   shlab verify --fixture data/fixtures/rotation/orders_1_10_taylor2.json \
//     --shader data/shaders/rot_taylor2.glsl --abi matrix --orders 1-6 [--define SHLAB_NOCS --convention nocs]
//
// Multiplications per vector (counted " * " in each function): 1:0 2:20 3:65 4:136 5:232 6:352

layout(local_size_x = 64) in;
layout(push_constant) uniform Params { uint order; uint count; uint form; uint pad; } pc;
layout(std430, set = 0, binding = 0) readonly buffer Rotations { float rot[]; };
layout(std430, set = 0, binding = 1) readonly buffer Inputs { float x[]; };
layout(std430, set = 0, binding = 2) writeonly buffer Outputs { float y[]; };
layout(std430, set = 0, binding = 3) buffer Status { uint status[]; };

// taylor2, order 1 (bands 0..0)
void taylor2_1(float par[7], uint b)
{
    y[b + 0u] = x[b + 0u];
}

// taylor2, order 2 (bands 0..1)
void taylor2_2(float par[7], uint b)
{
    const float ca1 = par[0], sa1 = par[1];
    const float cg1 = par[4], sg1 = par[5];
    const float beta = par[6];
    const float bb = 0.5 * beta * beta;
    y[b + 0u] = x[b + 0u];
    { /* band 1 */
        const float x1_n1 = x[b + 1u];
        const float x1_0 = x[b + 2u];
        const float x1_1 = x[b + 3u];
        const float u_0 = x1_0;
        const float u_1 = (cg1 * x1_1 - sg1 * x1_n1);
        const float u_n1 = (sg1 * x1_1 + cg1 * x1_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -0.0);
        const float t_0 = u_0 * (1.0 + bb * -1.0) + beta * -(-1.0 * u_1);
        const float t_1 = u_1 * (1.0 + bb * -1.0) + beta * (-1.0 * u_0);
        y[b + 2u] = t_0;
        y[b + 3u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 1u] = (sa1 * t_1 + ca1 * t_n1);
    }
}

// taylor2, order 3 (bands 0..2)
void taylor2_3(float par[7], uint b)
{
    const float ca1 = par[0], sa1 = par[1];
    const float cg1 = par[4], sg1 = par[5];
    const float beta = par[6];
    const float bb = 0.5 * beta * beta;
    const float ta = ca1 + ca1;
    const float ca2 = ta * ca1 - 1.0, sa2 = ta * sa1;
    const float tg = cg1 + cg1;
    const float cg2 = tg * cg1 - 1.0, sg2 = tg * sg1;
    y[b + 0u] = x[b + 0u];
    { /* band 1 */
        const float x1_n1 = x[b + 1u];
        const float x1_0 = x[b + 2u];
        const float x1_1 = x[b + 3u];
        const float u_0 = x1_0;
        const float u_1 = (cg1 * x1_1 - sg1 * x1_n1);
        const float u_n1 = (sg1 * x1_1 + cg1 * x1_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -0.0);
        const float t_0 = u_0 * (1.0 + bb * -1.0) + beta * -(-1.0 * u_1);
        const float t_1 = u_1 * (1.0 + bb * -1.0) + beta * (-1.0 * u_0);
        y[b + 2u] = t_0;
        y[b + 3u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 1u] = (sa1 * t_1 + ca1 * t_n1);
    }
    { /* band 2 */
        const float x2_n2 = x[b + 4u];
        const float x2_n1 = x[b + 5u];
        const float x2_0 = x[b + 6u];
        const float x2_1 = x[b + 7u];
        const float x2_2 = x[b + 8u];
        const float u_0 = x2_0;
        const float u_1 = (cg1 * x2_1 - sg1 * x2_n1);
        const float u_n1 = (sg1 * x2_1 + cg1 * x2_n1);
        const float u_2 = (cg2 * x2_2 - sg2 * x2_n2);
        const float u_n2 = (sg2 * x2_2 + cg2 * x2_n2);
        const float t_n2 = u_n2 * (1.0 + bb * -1.0) + beta * -(1.0 * u_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -1.0) + beta * (1.0 * u_n2);
        const float t_0 = u_0 * (1.0 + bb * -3.0) + beta * -(-1.73205078 * u_1) + bb * (1.73205078 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -4.0) + beta * (-1.73205078 * u_0 - -1.0 * u_2);
        const float t_2 = u_2 * (1.0 + bb * -1.0) + beta * (-1.0 * u_1) + bb * (1.73205078 * u_0);
        y[b + 6u] = t_0;
        y[b + 7u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 5u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 8u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 4u] = (sa2 * t_2 + ca2 * t_n2);
    }
}

// taylor2, order 4 (bands 0..3)
void taylor2_4(float par[7], uint b)
{
    const float ca1 = par[0], sa1 = par[1];
    const float cg1 = par[4], sg1 = par[5];
    const float beta = par[6];
    const float bb = 0.5 * beta * beta;
    const float ta = ca1 + ca1;
    const float ca2 = ta * ca1 - 1.0, sa2 = ta * sa1;
    const float ca3 = ta * ca2 - ca1, sa3 = ta * sa2 - sa1;
    const float tg = cg1 + cg1;
    const float cg2 = tg * cg1 - 1.0, sg2 = tg * sg1;
    const float cg3 = tg * cg2 - cg1, sg3 = tg * sg2 - sg1;
    y[b + 0u] = x[b + 0u];
    { /* band 1 */
        const float x1_n1 = x[b + 1u];
        const float x1_0 = x[b + 2u];
        const float x1_1 = x[b + 3u];
        const float u_0 = x1_0;
        const float u_1 = (cg1 * x1_1 - sg1 * x1_n1);
        const float u_n1 = (sg1 * x1_1 + cg1 * x1_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -0.0);
        const float t_0 = u_0 * (1.0 + bb * -1.0) + beta * -(-1.0 * u_1);
        const float t_1 = u_1 * (1.0 + bb * -1.0) + beta * (-1.0 * u_0);
        y[b + 2u] = t_0;
        y[b + 3u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 1u] = (sa1 * t_1 + ca1 * t_n1);
    }
    { /* band 2 */
        const float x2_n2 = x[b + 4u];
        const float x2_n1 = x[b + 5u];
        const float x2_0 = x[b + 6u];
        const float x2_1 = x[b + 7u];
        const float x2_2 = x[b + 8u];
        const float u_0 = x2_0;
        const float u_1 = (cg1 * x2_1 - sg1 * x2_n1);
        const float u_n1 = (sg1 * x2_1 + cg1 * x2_n1);
        const float u_2 = (cg2 * x2_2 - sg2 * x2_n2);
        const float u_n2 = (sg2 * x2_2 + cg2 * x2_n2);
        const float t_n2 = u_n2 * (1.0 + bb * -1.0) + beta * -(1.0 * u_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -1.0) + beta * (1.0 * u_n2);
        const float t_0 = u_0 * (1.0 + bb * -3.0) + beta * -(-1.73205078 * u_1) + bb * (1.73205078 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -4.0) + beta * (-1.73205078 * u_0 - -1.0 * u_2);
        const float t_2 = u_2 * (1.0 + bb * -1.0) + beta * (-1.0 * u_1) + bb * (1.73205078 * u_0);
        y[b + 6u] = t_0;
        y[b + 7u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 5u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 8u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 4u] = (sa2 * t_2 + ca2 * t_n2);
    }
    { /* band 3 */
        const float x3_n3 = x[b + 9u];
        const float x3_n2 = x[b + 10u];
        const float x3_n1 = x[b + 11u];
        const float x3_0 = x[b + 12u];
        const float x3_1 = x[b + 13u];
        const float x3_2 = x[b + 14u];
        const float x3_3 = x[b + 15u];
        const float u_0 = x3_0;
        const float u_1 = (cg1 * x3_1 - sg1 * x3_n1);
        const float u_n1 = (sg1 * x3_1 + cg1 * x3_n1);
        const float u_2 = (cg2 * x3_2 - sg2 * x3_n2);
        const float u_n2 = (sg2 * x3_2 + cg2 * x3_n2);
        const float u_3 = (cg3 * x3_3 - sg3 * x3_n3);
        const float u_n3 = (sg3 * x3_3 + cg3 * x3_n3);
        const float t_n3 = u_n3 * (1.0 + bb * -1.5) + beta * -(1.22474492 * u_n2) + bb * (1.93649173 * u_n1);
        const float t_n2 = u_n2 * (1.0 + bb * -4.0) + beta * (1.22474492 * u_n3 - 1.58113885 * u_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -2.5) + beta * (1.58113885 * u_n2) + bb * (1.93649173 * u_n3);
        const float t_0 = u_0 * (1.0 + bb * -6.0) + beta * -(-2.44948983 * u_1) + bb * (3.87298346 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -8.5) + beta * (-2.44948983 * u_0 - -1.58113885 * u_2) + bb * (1.93649173 * u_3);
        const float t_2 = u_2 * (1.0 + bb * -4.0) + beta * (-1.58113885 * u_1 - -1.22474492 * u_3) + bb * (3.87298346 * u_0);
        const float t_3 = u_3 * (1.0 + bb * -1.5) + beta * (-1.22474492 * u_2) + bb * (1.93649173 * u_1);
        y[b + 12u] = t_0;
        y[b + 13u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 11u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 14u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 10u] = (sa2 * t_2 + ca2 * t_n2);
        y[b + 15u] = (ca3 * t_3 - sa3 * t_n3);
        y[b + 9u] = (sa3 * t_3 + ca3 * t_n3);
    }
}

// taylor2, order 5 (bands 0..4)
void taylor2_5(float par[7], uint b)
{
    const float ca1 = par[0], sa1 = par[1];
    const float cg1 = par[4], sg1 = par[5];
    const float beta = par[6];
    const float bb = 0.5 * beta * beta;
    const float ta = ca1 + ca1;
    const float ca2 = ta * ca1 - 1.0, sa2 = ta * sa1;
    const float ca3 = ta * ca2 - ca1, sa3 = ta * sa2 - sa1;
    const float ca4 = ta * ca3 - ca2, sa4 = ta * sa3 - sa2;
    const float tg = cg1 + cg1;
    const float cg2 = tg * cg1 - 1.0, sg2 = tg * sg1;
    const float cg3 = tg * cg2 - cg1, sg3 = tg * sg2 - sg1;
    const float cg4 = tg * cg3 - cg2, sg4 = tg * sg3 - sg2;
    y[b + 0u] = x[b + 0u];
    { /* band 1 */
        const float x1_n1 = x[b + 1u];
        const float x1_0 = x[b + 2u];
        const float x1_1 = x[b + 3u];
        const float u_0 = x1_0;
        const float u_1 = (cg1 * x1_1 - sg1 * x1_n1);
        const float u_n1 = (sg1 * x1_1 + cg1 * x1_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -0.0);
        const float t_0 = u_0 * (1.0 + bb * -1.0) + beta * -(-1.0 * u_1);
        const float t_1 = u_1 * (1.0 + bb * -1.0) + beta * (-1.0 * u_0);
        y[b + 2u] = t_0;
        y[b + 3u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 1u] = (sa1 * t_1 + ca1 * t_n1);
    }
    { /* band 2 */
        const float x2_n2 = x[b + 4u];
        const float x2_n1 = x[b + 5u];
        const float x2_0 = x[b + 6u];
        const float x2_1 = x[b + 7u];
        const float x2_2 = x[b + 8u];
        const float u_0 = x2_0;
        const float u_1 = (cg1 * x2_1 - sg1 * x2_n1);
        const float u_n1 = (sg1 * x2_1 + cg1 * x2_n1);
        const float u_2 = (cg2 * x2_2 - sg2 * x2_n2);
        const float u_n2 = (sg2 * x2_2 + cg2 * x2_n2);
        const float t_n2 = u_n2 * (1.0 + bb * -1.0) + beta * -(1.0 * u_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -1.0) + beta * (1.0 * u_n2);
        const float t_0 = u_0 * (1.0 + bb * -3.0) + beta * -(-1.73205078 * u_1) + bb * (1.73205078 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -4.0) + beta * (-1.73205078 * u_0 - -1.0 * u_2);
        const float t_2 = u_2 * (1.0 + bb * -1.0) + beta * (-1.0 * u_1) + bb * (1.73205078 * u_0);
        y[b + 6u] = t_0;
        y[b + 7u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 5u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 8u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 4u] = (sa2 * t_2 + ca2 * t_n2);
    }
    { /* band 3 */
        const float x3_n3 = x[b + 9u];
        const float x3_n2 = x[b + 10u];
        const float x3_n1 = x[b + 11u];
        const float x3_0 = x[b + 12u];
        const float x3_1 = x[b + 13u];
        const float x3_2 = x[b + 14u];
        const float x3_3 = x[b + 15u];
        const float u_0 = x3_0;
        const float u_1 = (cg1 * x3_1 - sg1 * x3_n1);
        const float u_n1 = (sg1 * x3_1 + cg1 * x3_n1);
        const float u_2 = (cg2 * x3_2 - sg2 * x3_n2);
        const float u_n2 = (sg2 * x3_2 + cg2 * x3_n2);
        const float u_3 = (cg3 * x3_3 - sg3 * x3_n3);
        const float u_n3 = (sg3 * x3_3 + cg3 * x3_n3);
        const float t_n3 = u_n3 * (1.0 + bb * -1.5) + beta * -(1.22474492 * u_n2) + bb * (1.93649173 * u_n1);
        const float t_n2 = u_n2 * (1.0 + bb * -4.0) + beta * (1.22474492 * u_n3 - 1.58113885 * u_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -2.5) + beta * (1.58113885 * u_n2) + bb * (1.93649173 * u_n3);
        const float t_0 = u_0 * (1.0 + bb * -6.0) + beta * -(-2.44948983 * u_1) + bb * (3.87298346 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -8.5) + beta * (-2.44948983 * u_0 - -1.58113885 * u_2) + bb * (1.93649173 * u_3);
        const float t_2 = u_2 * (1.0 + bb * -4.0) + beta * (-1.58113885 * u_1 - -1.22474492 * u_3) + bb * (3.87298346 * u_0);
        const float t_3 = u_3 * (1.0 + bb * -1.5) + beta * (-1.22474492 * u_2) + bb * (1.93649173 * u_1);
        y[b + 12u] = t_0;
        y[b + 13u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 11u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 14u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 10u] = (sa2 * t_2 + ca2 * t_n2);
        y[b + 15u] = (ca3 * t_3 - sa3 * t_n3);
        y[b + 9u] = (sa3 * t_3 + ca3 * t_n3);
    }
    { /* band 4 */
        const float x4_n4 = x[b + 16u];
        const float x4_n3 = x[b + 17u];
        const float x4_n2 = x[b + 18u];
        const float x4_n1 = x[b + 19u];
        const float x4_0 = x[b + 20u];
        const float x4_1 = x[b + 21u];
        const float x4_2 = x[b + 22u];
        const float x4_3 = x[b + 23u];
        const float x4_4 = x[b + 24u];
        const float u_0 = x4_0;
        const float u_1 = (cg1 * x4_1 - sg1 * x4_n1);
        const float u_n1 = (sg1 * x4_1 + cg1 * x4_n1);
        const float u_2 = (cg2 * x4_2 - sg2 * x4_n2);
        const float u_n2 = (sg2 * x4_2 + cg2 * x4_n2);
        const float u_3 = (cg3 * x4_3 - sg3 * x4_n3);
        const float u_n3 = (sg3 * x4_3 + cg3 * x4_n3);
        const float u_4 = (cg4 * x4_4 - sg4 * x4_n4);
        const float u_n4 = (sg4 * x4_4 + cg4 * x4_n4);
        const float t_n4 = u_n4 * (1.0 + bb * -2.0) + beta * -(1.41421354 * u_n3) + bb * (2.64575124 * u_n2);
        const float t_n3 = u_n3 * (1.0 + bb * -5.5) + beta * (1.41421354 * u_n4 - 1.87082875 * u_n2) + bb * (3.96862698 * u_n1);
        const float t_n2 = u_n2 * (1.0 + bb * -8.0) + beta * (1.87082875 * u_n3 - 2.12132025 * u_n1) + bb * (2.64575124 * u_n4);
        const float t_n1 = u_n1 * (1.0 + bb * -4.5) + beta * (2.12132025 * u_n2) + bb * (3.96862698 * u_n3);
        const float t_0 = u_0 * (1.0 + bb * -10.0) + beta * -(-3.1622777 * u_1) + bb * (6.70820379 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -14.5) + beta * (-3.1622777 * u_0 - -2.12132025 * u_2) + bb * (3.96862698 * u_3);
        const float t_2 = u_2 * (1.0 + bb * -8.0) + beta * (-2.12132025 * u_1 - -1.87082875 * u_3) + bb * (6.70820379 * u_0 + 2.64575124 * u_4);
        const float t_3 = u_3 * (1.0 + bb * -5.5) + beta * (-1.87082875 * u_2 - -1.41421354 * u_4) + bb * (3.96862698 * u_1);
        const float t_4 = u_4 * (1.0 + bb * -2.0) + beta * (-1.41421354 * u_3) + bb * (2.64575124 * u_2);
        y[b + 20u] = t_0;
        y[b + 21u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 19u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 22u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 18u] = (sa2 * t_2 + ca2 * t_n2);
        y[b + 23u] = (ca3 * t_3 - sa3 * t_n3);
        y[b + 17u] = (sa3 * t_3 + ca3 * t_n3);
        y[b + 24u] = (ca4 * t_4 - sa4 * t_n4);
        y[b + 16u] = (sa4 * t_4 + ca4 * t_n4);
    }
}

// taylor2, order 6 (bands 0..5)
void taylor2_6(float par[7], uint b)
{
    const float ca1 = par[0], sa1 = par[1];
    const float cg1 = par[4], sg1 = par[5];
    const float beta = par[6];
    const float bb = 0.5 * beta * beta;
    const float ta = ca1 + ca1;
    const float ca2 = ta * ca1 - 1.0, sa2 = ta * sa1;
    const float ca3 = ta * ca2 - ca1, sa3 = ta * sa2 - sa1;
    const float ca4 = ta * ca3 - ca2, sa4 = ta * sa3 - sa2;
    const float ca5 = ta * ca4 - ca3, sa5 = ta * sa4 - sa3;
    const float tg = cg1 + cg1;
    const float cg2 = tg * cg1 - 1.0, sg2 = tg * sg1;
    const float cg3 = tg * cg2 - cg1, sg3 = tg * sg2 - sg1;
    const float cg4 = tg * cg3 - cg2, sg4 = tg * sg3 - sg2;
    const float cg5 = tg * cg4 - cg3, sg5 = tg * sg4 - sg3;
    y[b + 0u] = x[b + 0u];
    { /* band 1 */
        const float x1_n1 = x[b + 1u];
        const float x1_0 = x[b + 2u];
        const float x1_1 = x[b + 3u];
        const float u_0 = x1_0;
        const float u_1 = (cg1 * x1_1 - sg1 * x1_n1);
        const float u_n1 = (sg1 * x1_1 + cg1 * x1_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -0.0);
        const float t_0 = u_0 * (1.0 + bb * -1.0) + beta * -(-1.0 * u_1);
        const float t_1 = u_1 * (1.0 + bb * -1.0) + beta * (-1.0 * u_0);
        y[b + 2u] = t_0;
        y[b + 3u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 1u] = (sa1 * t_1 + ca1 * t_n1);
    }
    { /* band 2 */
        const float x2_n2 = x[b + 4u];
        const float x2_n1 = x[b + 5u];
        const float x2_0 = x[b + 6u];
        const float x2_1 = x[b + 7u];
        const float x2_2 = x[b + 8u];
        const float u_0 = x2_0;
        const float u_1 = (cg1 * x2_1 - sg1 * x2_n1);
        const float u_n1 = (sg1 * x2_1 + cg1 * x2_n1);
        const float u_2 = (cg2 * x2_2 - sg2 * x2_n2);
        const float u_n2 = (sg2 * x2_2 + cg2 * x2_n2);
        const float t_n2 = u_n2 * (1.0 + bb * -1.0) + beta * -(1.0 * u_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -1.0) + beta * (1.0 * u_n2);
        const float t_0 = u_0 * (1.0 + bb * -3.0) + beta * -(-1.73205078 * u_1) + bb * (1.73205078 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -4.0) + beta * (-1.73205078 * u_0 - -1.0 * u_2);
        const float t_2 = u_2 * (1.0 + bb * -1.0) + beta * (-1.0 * u_1) + bb * (1.73205078 * u_0);
        y[b + 6u] = t_0;
        y[b + 7u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 5u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 8u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 4u] = (sa2 * t_2 + ca2 * t_n2);
    }
    { /* band 3 */
        const float x3_n3 = x[b + 9u];
        const float x3_n2 = x[b + 10u];
        const float x3_n1 = x[b + 11u];
        const float x3_0 = x[b + 12u];
        const float x3_1 = x[b + 13u];
        const float x3_2 = x[b + 14u];
        const float x3_3 = x[b + 15u];
        const float u_0 = x3_0;
        const float u_1 = (cg1 * x3_1 - sg1 * x3_n1);
        const float u_n1 = (sg1 * x3_1 + cg1 * x3_n1);
        const float u_2 = (cg2 * x3_2 - sg2 * x3_n2);
        const float u_n2 = (sg2 * x3_2 + cg2 * x3_n2);
        const float u_3 = (cg3 * x3_3 - sg3 * x3_n3);
        const float u_n3 = (sg3 * x3_3 + cg3 * x3_n3);
        const float t_n3 = u_n3 * (1.0 + bb * -1.5) + beta * -(1.22474492 * u_n2) + bb * (1.93649173 * u_n1);
        const float t_n2 = u_n2 * (1.0 + bb * -4.0) + beta * (1.22474492 * u_n3 - 1.58113885 * u_n1);
        const float t_n1 = u_n1 * (1.0 + bb * -2.5) + beta * (1.58113885 * u_n2) + bb * (1.93649173 * u_n3);
        const float t_0 = u_0 * (1.0 + bb * -6.0) + beta * -(-2.44948983 * u_1) + bb * (3.87298346 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -8.5) + beta * (-2.44948983 * u_0 - -1.58113885 * u_2) + bb * (1.93649173 * u_3);
        const float t_2 = u_2 * (1.0 + bb * -4.0) + beta * (-1.58113885 * u_1 - -1.22474492 * u_3) + bb * (3.87298346 * u_0);
        const float t_3 = u_3 * (1.0 + bb * -1.5) + beta * (-1.22474492 * u_2) + bb * (1.93649173 * u_1);
        y[b + 12u] = t_0;
        y[b + 13u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 11u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 14u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 10u] = (sa2 * t_2 + ca2 * t_n2);
        y[b + 15u] = (ca3 * t_3 - sa3 * t_n3);
        y[b + 9u] = (sa3 * t_3 + ca3 * t_n3);
    }
    { /* band 4 */
        const float x4_n4 = x[b + 16u];
        const float x4_n3 = x[b + 17u];
        const float x4_n2 = x[b + 18u];
        const float x4_n1 = x[b + 19u];
        const float x4_0 = x[b + 20u];
        const float x4_1 = x[b + 21u];
        const float x4_2 = x[b + 22u];
        const float x4_3 = x[b + 23u];
        const float x4_4 = x[b + 24u];
        const float u_0 = x4_0;
        const float u_1 = (cg1 * x4_1 - sg1 * x4_n1);
        const float u_n1 = (sg1 * x4_1 + cg1 * x4_n1);
        const float u_2 = (cg2 * x4_2 - sg2 * x4_n2);
        const float u_n2 = (sg2 * x4_2 + cg2 * x4_n2);
        const float u_3 = (cg3 * x4_3 - sg3 * x4_n3);
        const float u_n3 = (sg3 * x4_3 + cg3 * x4_n3);
        const float u_4 = (cg4 * x4_4 - sg4 * x4_n4);
        const float u_n4 = (sg4 * x4_4 + cg4 * x4_n4);
        const float t_n4 = u_n4 * (1.0 + bb * -2.0) + beta * -(1.41421354 * u_n3) + bb * (2.64575124 * u_n2);
        const float t_n3 = u_n3 * (1.0 + bb * -5.5) + beta * (1.41421354 * u_n4 - 1.87082875 * u_n2) + bb * (3.96862698 * u_n1);
        const float t_n2 = u_n2 * (1.0 + bb * -8.0) + beta * (1.87082875 * u_n3 - 2.12132025 * u_n1) + bb * (2.64575124 * u_n4);
        const float t_n1 = u_n1 * (1.0 + bb * -4.5) + beta * (2.12132025 * u_n2) + bb * (3.96862698 * u_n3);
        const float t_0 = u_0 * (1.0 + bb * -10.0) + beta * -(-3.1622777 * u_1) + bb * (6.70820379 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -14.5) + beta * (-3.1622777 * u_0 - -2.12132025 * u_2) + bb * (3.96862698 * u_3);
        const float t_2 = u_2 * (1.0 + bb * -8.0) + beta * (-2.12132025 * u_1 - -1.87082875 * u_3) + bb * (6.70820379 * u_0 + 2.64575124 * u_4);
        const float t_3 = u_3 * (1.0 + bb * -5.5) + beta * (-1.87082875 * u_2 - -1.41421354 * u_4) + bb * (3.96862698 * u_1);
        const float t_4 = u_4 * (1.0 + bb * -2.0) + beta * (-1.41421354 * u_3) + bb * (2.64575124 * u_2);
        y[b + 20u] = t_0;
        y[b + 21u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 19u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 22u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 18u] = (sa2 * t_2 + ca2 * t_n2);
        y[b + 23u] = (ca3 * t_3 - sa3 * t_n3);
        y[b + 17u] = (sa3 * t_3 + ca3 * t_n3);
        y[b + 24u] = (ca4 * t_4 - sa4 * t_n4);
        y[b + 16u] = (sa4 * t_4 + ca4 * t_n4);
    }
    { /* band 5 */
        const float x5_n5 = x[b + 25u];
        const float x5_n4 = x[b + 26u];
        const float x5_n3 = x[b + 27u];
        const float x5_n2 = x[b + 28u];
        const float x5_n1 = x[b + 29u];
        const float x5_0 = x[b + 30u];
        const float x5_1 = x[b + 31u];
        const float x5_2 = x[b + 32u];
        const float x5_3 = x[b + 33u];
        const float x5_4 = x[b + 34u];
        const float x5_5 = x[b + 35u];
        const float u_0 = x5_0;
        const float u_1 = (cg1 * x5_1 - sg1 * x5_n1);
        const float u_n1 = (sg1 * x5_1 + cg1 * x5_n1);
        const float u_2 = (cg2 * x5_2 - sg2 * x5_n2);
        const float u_n2 = (sg2 * x5_2 + cg2 * x5_n2);
        const float u_3 = (cg3 * x5_3 - sg3 * x5_n3);
        const float u_n3 = (sg3 * x5_3 + cg3 * x5_n3);
        const float u_4 = (cg4 * x5_4 - sg4 * x5_n4);
        const float u_n4 = (sg4 * x5_4 + cg4 * x5_n4);
        const float u_5 = (cg5 * x5_5 - sg5 * x5_n5);
        const float u_n5 = (sg5 * x5_5 + cg5 * x5_n5);
        const float t_n5 = u_n5 * (1.0 + bb * -2.5) + beta * -(1.58113885 * u_n4) + bb * (3.3541019 * u_n3);
        const float t_n4 = u_n4 * (1.0 + bb * -7.0) + beta * (1.58113885 * u_n5 - 2.12132025 * u_n3) + bb * (5.19615221 * u_n2);
        const float t_n3 = u_n3 * (1.0 + bb * -10.5) + beta * (2.12132025 * u_n4 - 2.44948983 * u_n2) + bb * (3.3541019 * u_n5 + 6.48074055 * u_n1);
        const float t_n2 = u_n2 * (1.0 + bb * -13.0) + beta * (2.44948983 * u_n3 - 2.64575124 * u_n1) + bb * (5.19615221 * u_n4);
        const float t_n1 = u_n1 * (1.0 + bb * -7.0) + beta * (2.64575124 * u_n2) + bb * (6.48074055 * u_n3);
        const float t_0 = u_0 * (1.0 + bb * -15.0) + beta * -(-3.87298346 * u_1) + bb * (10.2469511 * u_2);
        const float t_1 = u_1 * (1.0 + bb * -22.0) + beta * (-3.87298346 * u_0 - -2.64575124 * u_2) + bb * (6.48074055 * u_3);
        const float t_2 = u_2 * (1.0 + bb * -13.0) + beta * (-2.64575124 * u_1 - -2.44948983 * u_3) + bb * (10.2469511 * u_0 + 5.19615221 * u_4);
        const float t_3 = u_3 * (1.0 + bb * -10.5) + beta * (-2.44948983 * u_2 - -2.12132025 * u_4) + bb * (6.48074055 * u_1 + 3.3541019 * u_5);
        const float t_4 = u_4 * (1.0 + bb * -7.0) + beta * (-2.12132025 * u_3 - -1.58113885 * u_5) + bb * (5.19615221 * u_2);
        const float t_5 = u_5 * (1.0 + bb * -2.5) + beta * (-1.58113885 * u_4) + bb * (3.3541019 * u_3);
        y[b + 30u] = t_0;
        y[b + 31u] = (ca1 * t_1 - sa1 * t_n1);
        y[b + 29u] = (sa1 * t_1 + ca1 * t_n1);
        y[b + 32u] = (ca2 * t_2 - sa2 * t_n2);
        y[b + 28u] = (sa2 * t_2 + ca2 * t_n2);
        y[b + 33u] = (ca3 * t_3 - sa3 * t_n3);
        y[b + 27u] = (sa3 * t_3 + ca3 * t_n3);
        y[b + 34u] = (ca4 * t_4 - sa4 * t_n4);
        y[b + 26u] = (sa4 * t_4 + ca4 * t_n4);
        y[b + 35u] = (ca5 * t_5 - sa5 * t_n5);
        y[b + 25u] = (sa5 * t_5 + ca5 * t_n5);
    }
}

// β = atan2(s, c) ∈ [0, π] for s ≥ 0, as rot_fast.c's shk_beta: Abramowitz &
// Stegun 4.4.49 (Hastings), atan x = x(1 + a₂x² + … + a₁₆x¹⁶) + ε with
// |ε| ≤ 2·10⁻⁸ on [0, 1], on x = min(s, |c|)/max(s, |c|), then atan x,
// π/2 − atan x, or π minus those for c < 0.  The device's atan is not
// used: Vulkan allows it 4096 ulp, and lavapipe's was measured several
// ulp off, which the Taylor kernels (output error ~ l·δβ) turned into
// errors past the fixtures' float32 tolerance.
float beta_of(float s, float c)
{
    const float ac = abs(c);
    const bool swap = s > ac;
    const float num = swap ? ac : s, den = swap ? s : ac;
    const float xr = den > 0.0 ? num / den : 0.0, x2 = xr * xr;
    const float a = ((((((((0.0028662257 * x2 - 0.0161657367) * x2 + 0.0429096138) * x2 - 0.0752896400) * x2 +
                          0.1065626393) * x2 - 0.1420889944) * x2 + 0.1999355085) * x2 - 0.3333314528) * x2 + 1.0) * xr;
    const float t = swap ? 1.57079633 - a : a;
    return c >= 0.0 ? t : 3.14159265 - t;
}

// par = (cos α, sin α, cos β, sin β, cos γ, sin γ, β) of R = Rz(α) Ry(β) Rz(γ)
// (ZYZ, active; docs/CONVENTIONS.md), what the kernels above read, from
// the rotation in any of the convention's forms (pc.form).  The formulas
// are those of shlab's C kernels (src/rotate/rot_fast.c), in float:
//  matrix (form 0), no trigonometric call: cβ = R22 and
//    sβ e^{iα} = R02 + i R12,
//    (1 + cβ) e^{i(α+γ)} = (R00 + R11) + i (R10 − R01)   (taken when cβ ≥ 0),
//    (1 − cβ) e^{i(α−γ)} = (R11 − R00) − i (R10 + R01)   (taken when cβ < 0),
//    γ relative to the same α, so near β = 0 or π, where α alone is
//    ill-conditioned, its error cancels in R; at sβ = 0 exactly α = 0.
//  quaternion (w, x, y, z) (form 1): A = w + iz = cos(β/2) e^{i(α+γ)/2},
//    B = y − ix = sin(β/2) e^{i(α−γ)/2}: cβ = (|A|² − |B|²)/|q|²,
//    sβ = 2|A||B|/|q|², e^{iα} = AB/(|A||B|), e^{iγ} = AB̄/(|A||B|);
//    |B| = 0: α = 0, e^{iγ} = A²/|A|²; |A| = 0: α = 0, e^{iγ} = B̄²/|B|².
//  ZYZ angles α, β, γ in radians (form 2): cos and sin of each.
// β itself (read by the Taylor kernels only): the given angle, or
// beta_of(sβ, cβ) = atan2(sβ, cβ) ∈ [0, π] from a matrix or a quaternion.
// Taylor kernels, matrix with cβ < 0: e^{iγ} = (−R20 + i R21)/|(R20, R21)|
//    (R20 = −sβ cγ, R21 = sβ sγ) instead of (c).  Z(α) T(β) Z(γ) is not a
//    function of R alone: away from β = 0 α and γ each matter (near
//    β = 0, T ≈ I and only α + γ does, which (b) gives well), and the third
//    column and row give each to the relative accuracy of those entries.
//    Through (c), γ = α − (α−γ) carried 1-2 float ulps more, which T(β)
//    amplifies near β = π (by ~l·|T|) past the Taylor fixtures' float32
//    tolerance (measured on lavapipe: 3.4e-6 against 3.2e-6 at
//    β = π − 1e-9).  (c) stays the fallback when R20 = R21 = 0.
// SHLAB_NOCS (no Condon-Shortley phase): R_nocs = S R_cs S with
// S = diag((−1)^m) = R_sh(Rz(π)), and Rz(π) Ry(β) Rz(π) = Ry(−β): the
// same kernels with sβ and β negated.
// Returns false for a form it does not know.
bool rot_par(uint k, out float par[7])
{
    if (pc.form == 0u) {
        const uint o = 9u * k;
        const float r00 = rot[o], r01 = rot[o + 1u], r02 = rot[o + 2u];
        const float r10 = rot[o + 3u], r11 = rot[o + 4u], r12 = rot[o + 5u], r22 = rot[o + 8u];
        const float s2 = r02 * r02 + r12 * r12, sb = sqrt(s2);
        const bool has = s2 > 0.0;
        const float inv = has ? 1.0 / sb : 0.0;
        const float ca = has ? r02 * inv : 1.0, sa = r12 * inv;
        const bool up = r22 >= 0.0;
        const float p = up ? r00 + r11 : r11 - r00, q = up ? r10 - r01 : -(r10 + r01);
        const float nrm = 1.0 / sqrt(p * p + q * q);
        const float cs = p * nrm, ss = q * nrm; // e^{i(α+γ)} or e^{i(α−γ)}
        const float t = ss * ca - cs * sa;
        par[0] = ca; par[1] = sa; par[2] = r22; par[3] = sb;
        par[4] = cs * ca + ss * sa; par[5] = up ? t : -t;
        const float r20 = rot[o + 6u], r21 = rot[o + 7u], h2 = r20 * r20 + r21 * r21;
        if (!up && h2 > 0.0) {
            const float ih = 1.0 / sqrt(h2);
            par[4] = -r20 * ih;
            par[5] = r21 * ih;
        }
        par[6] = beta_of(sb, r22);
    } else if (pc.form == 1u) {
        const uint o = 4u * k;
        const float qw = rot[o], qx = rot[o + 1u], qy = rot[o + 2u], qz = rot[o + 3u];
        const float ww = qw * qw, zz = qz * qz, xx = qx * qx, yy = qy * qy;
        const float a2 = ww + zz, b2 = xx + yy, in2 = 1.0 / (a2 + b2);
        const float ab = sqrt(a2 * b2);
        const bool has = ab > 0.0;
        const float iab = has ? 1.0 / ab : 0.0;
        const float wy = qw * qy, zx = qz * qx, zy = qz * qy, wx = qw * qx;
        const bool up = a2 >= b2;
        const float dn = 1.0 / (up ? a2 : b2);
        const float dc = (up ? ww - zz : yy - xx) * dn;
        const float ds = (up ? qw : qx) * (up ? qz : qy) * (dn + dn);
        par[0] = has ? (wy + zx) * iab : 1.0;
        par[1] = (zy - wx) * iab;
        par[2] = (a2 - b2) * in2;
        par[3] = (ab + ab) * in2;
        par[4] = has ? (wy - zx) * iab : dc;
        par[5] = has ? (wx + zy) * iab : ds;
        par[6] = beta_of(par[3], par[2]);
    } else if (pc.form == 2u) {
        const uint o = 3u * k;
        const float al = rot[o], be = rot[o + 1u], ga = rot[o + 2u];
        par[0] = cos(al); par[1] = sin(al);
        par[2] = cos(be); par[3] = sin(be);
        par[4] = cos(ga); par[5] = sin(ga);
        par[6] = be;
    } else {
        return false;
    }
#ifdef SHLAB_NOCS
    par[3] = -par[3];
    par[6] = -par[6];
#endif
    return true;
}

void main()
{
    const uint k = gl_GlobalInvocationID.x;
    if (k >= pc.count) return;
    if (pc.order < 1u || pc.order > 6u) {
        status[k] = 1u;
        return;
    }
    float par[7];
    if (!rot_par(k, par)) {
        status[k] = 2u;
        return;
    }
    const uint b = k * pc.order * pc.order;
    switch (pc.order) {
    case 1u: taylor2_1(par, b); break;
    case 2u: taylor2_2(par, b); break;
    case 3u: taylor2_3(par, b); break;
    case 4u: taylor2_4(par, b); break;
    case 5u: taylor2_5(par, b); break;
    case 6u: taylor2_6(par, b); break;
    default: break;
    }
}
