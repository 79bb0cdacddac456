/* The inputs and cases of the portable-tier test, shared by the C program
 * (tests/c/portable.c), the OpenCL kernel (tests/c/portable_opencl.c) and,
 * written again in Rust, tests/c_abi/portable.rs: case c at index k writes
 * up to four floats to o (the rest 0). Index k < 2^24 - 16 gives
 * u = k 2^-24; the last 16 indices give the special values below. */
#ifndef PORTABLE_CASES_H
#define PORTABLE_CASES_H

#include "scatterkit_portable.h"

#define PC_N 16777216u
#define PC_CASES 35
#define PC_MAJ_N 60u /* the majorant grid of case 26: 5 x 3 x 4 cells */

SKP_FN float pc_u(skp_u32 k) {
    if (k >= PC_N - 16u) {
        switch (k - (PC_N - 16u)) {
        case 0: return 1.0f;
        case 1: return 1.0000001f;
        case 2: return -0.0f;
        case 3: return -1e-30f;
        case 4: return 2.0f;
        case 5: return skp_from_bits(0x7fc00000u);
        case 6: return skp_from_bits(0x7f800000u);
        case 7: return -skp_from_bits(0x7f800000u);
        case 8: return 0.99999994f;
        case 9: return 5.9604645e-08f;
        case 10: return 1e-45f;
        case 11: return 0.5f;
        case 12: return 0.25f;
        case 13: return 0.75f;
        case 14: return 0.49999997f;
        default: return 0.50000006f;
        }
    }
    return (float)k * 5.9604645e-08f;
}

/* A second uniform, scrambled from k. */
SKP_FN float pc_u2(skp_u32 k) {
    skp_u32 h = k * 2654435761u;
    return (float)(h >> 8) * 5.9604645e-08f;
}

/* One of eight (nearly) unit vectors. */
SKP_FN skp_vec3 pc_dir(skp_u32 k) {
    skp_vec3 v;
    switch (k & 7u) {
    case 0: v.x = 0.0f; v.y = 0.0f; v.z = 1.0f; break;
    case 1: v.x = 0.0f; v.y = 0.0f; v.z = -1.0f; break;
    case 2: v.x = 1.0f; v.y = 0.0f; v.z = 0.0f; break;
    case 3: v.x = 0.0f; v.y = -1.0f; v.z = 0.0f; break;
    case 4: v.x = 0.6f; v.y = 0.0f; v.z = 0.8f; break;
    case 5: v.x = 0.0f; v.y = 0.8f; v.z = -0.6f; break;
    case 6: v.x = 0.48f; v.y = 0.6f; v.z = 0.64f; break;
    default: v.x = -0.36f; v.y = 0.48f; v.z = -0.8f; break;
    }
    return v;
}

/* The asymmetries of cases 2 to 7. */
SKP_FN float pc_g(int c) {
    switch (c) {
    case 2: return 0.0f;
    case 3: return 0.3f;
    case 4: return -0.7f;
    case 5: return 0.9f;
    case 6: return 0.999f;
    default: return -0.999999f;
    }
}

/* A direction sample to o: the direction, then its density; its cos theta
   goes to nothing here (case 34 writes those). */
SKP_FN void pc_dir_out(skp_dir_sample r, float *o) {
    o[0] = r.dir.x;
    o[1] = r.dir.y;
    o[2] = r.dir.z;
    o[3] = r.pdf;
}

/* Majorant i of case 26's grid: 0 to 3 in steps of 0.75, one cell 40. */
SKP_FN float pc_maj(skp_u32 i) {
    return i == 17u ? 40.0f : (float)((i * 7u) % 5u) * 0.75f;
}

/* Case 26: a walk through the 5 x 3 x 4 grid maj over [-1, 1.5] x
   [-0.5, 0.5] x [0, 2], three steps: (begin + 1) + 3 (step + 1) + ... as a
   code plus 100 times the cell at the end, and the three t; one input in
   128 bad. */
SKP_FN void pc_walk(skp_u32 k, float u, float u2, float u3, const SKP_GLOBAL float *maj, float *o) {
    SKP_BEGIN
    skp_vec3 d = pc_dir(k), org, lo, hi;
    skp_walk w;
    float sig, tmin, tmax, back = (k & 64u) ? 0.0f : 3.0f;
    skp_u32 nx = 5u;
    int b, s1, s2, s3;
    org.x = 0.25f - SKP_MUL(back, d.x) + SKP_MUL(u2 - 0.5f, 2.5f);
    org.y = 0.0f - SKP_MUL(back, d.y) + SKP_MUL(u3 - 0.5f, 1.0f);
    org.z = 1.0f - SKP_MUL(back, d.z) + SKP_MUL(u - 0.5f, 2.0f);
    lo.x = -1.0f; lo.y = -0.5f; lo.z = 0.0f;
    hi.x = 1.5f; hi.y = 0.5f; hi.z = 2.0f;
    tmin = (k & 16u) ? 0.5f : 0.0f;
    tmax = (k & 32u) ? 4.0f : skp_from_bits(0x7f800000u);
    if ((k & 127u) == 127u) { /* one input in 128 is bad, eight ways */
        switch ((k >> 7) & 7u) {
        case 0: nx = 0u; break;
        case 1: org.x = skp_from_bits(0x7fc00000u); break;
        case 2: tmin = -1.0f; break;
        case 3: tmax = -1.0f; break;
        case 4: d.x = 0.0f; d.y = 0.0f; d.z = 0.0f; break;
        case 5: hi.x = lo.x; break;
        case 6: org.y = skp_from_bits(0x7f800000u); break;
        default: nx = 16777216u; break;
        }
    }
    b = skp_walk_begin(&w, org, d, lo, hi, nx, 3u, 4u, tmin, tmax);
    if (b != 1) {
        o[0] = (float)(b + 1);
        return;
    }
    s1 = skp_walk_step(&w, maj, u, &o[1], &sig);
    s2 = skp_walk_step(&w, maj, u2, &o[2], &sig);
    s3 = skp_walk_step(&w, maj, u3, &o[3], &sig);
    o[0] = (float)(2 + 3 * (s1 + 1) + 9 * (s2 + 1) + 27 * (s3 + 1)) + (float)(100u * skp_walk_cell(&w));
}

SKP_FN void pc_case(int c, skp_u32 k, const SKP_GLOBAL float *maj, float *o) {
    SKP_BEGIN /* the inputs below must not contract either (0.5 + 1e4 u2) */
    float u = pc_u(k), u2 = pc_u2(k), s, pdf, sig[3];
    skp_vec3 v;
    skp_schlick sch;
    skp_hg hg;
    skp_draine dr;
    skp_two_lobe tl;
    skp_fog fog;
    o[0] = 0.0f;
    o[1] = 0.0f;
    o[2] = 0.0f;
    o[3] = 0.0f;
    switch (c) {
    case 0:
        skp_sin_cos_2pi(u, &o[0], &o[1]);
        break;
    case 1:
        pc_dir_out(skp_isotropic_sample_dir(u, u2), o);
        break;
    case 2: case 3: case 4: case 5: case 6: case 7:
        skp_hg_new(pc_g(c), &hg);
        o[0] = skp_hg_sample_cos(hg, u);
        o[1] = skp_hg_sample_cos_sin(hg, u, &s, &pdf);
        o[2] = s;
        o[3] = pdf;
        break;
    case 8: case 9:
        skp_hg_new(c == 8 ? 0.7f : -0.2f, &hg);
        pc_dir_out(skp_hg_sample_dir(hg, pc_dir(k), u, u2), o);
        break;
    case 10:
        skp_hg_new(0.9f, &hg);
        o[0] = skp_hg_pdf(hg, SKP_MUL(2.0f, u) - 1.0f);
        skp_hg_new(-0.5f, &hg);
        o[1] = skp_hg_pdf(hg, SKP_MUL(2.0f, u) - 1.0f);
        break;
    case 11:
        o[0] = skp_rayleigh_sample_cos(u);
        o[1] = skp_rayleigh_pdf(o[0]);
        break;
    case 12:
        pc_dir_out(skp_rayleigh_sample_dir(pc_dir(k), u, u2), o);
        break;
    case 13:
        o[0] = skp_ln(skp_from_bits(k << 7));
        o[1] = skp_ln(u);
        break;
    case 14:
        o[0] = skp_free_path(2.5f, u);
        o[1] = skp_free_path(1e-3f, u);
        break;
    case 16: case 17:
        skp_hg_new(SKP_MUL(2.0f, u) - 1.0f, &hg);
        o[0] = c == 16 ? hg.c1 : hg.kd;
        o[1] = c == 16 ? hg.c2 : hg.k2;
        o[2] = c == 16 ? hg.c3 : hg.kp;
        o[3] = c == 16 ? hg.c4 : hg.omg;
        break;
    case 18: case 19:
        skp_draine_new(c == 18 ? 0.5f : -0.3f, c == 18 ? 1.0f : 250.0f, &dr);
        o[0] = skp_draine_sample_cos(dr, u);
        o[1] = skp_draine_pdf(dr, o[0]);
        skp_draine_new(c == 18 ? 0.9f : 0.01f, c == 18 ? 10.0f : 1000.0f, &dr);
        o[2] = skp_draine_sample_cos(dr, u);
        o[3] = skp_draine_pdf(dr, o[2]);
        break;
    case 20:
        skp_draine_new(SKP_MUL(2.0f, u) - 1.0f, 0.5f + SKP_MUL(1e4f, u2), &dr); /* alpha < 1: refused */
        o[0] = dr.lower.d;
        o[1] = dr.lower.r;
        o[2] = dr.upper.d;
        o[3] = dr.kp;
        break;
    case 21:
        skp_two_lobe_new(0.8f, -0.3f, 0.9f, &tl);
        o[0] = skp_two_lobe_sample_cos(tl, u);
        o[1] = skp_two_lobe_pdf(tl, o[0]);
        skp_two_lobe_new(0.5f, 0.99f, u2, &tl);
        o[2] = skp_two_lobe_sample_cos(tl, u);
        o[3] = skp_two_lobe_pdf(tl, o[2]);
        break;
    case 22:
        skp_two_lobe_new(0.8f, -0.3f, k & 8u ? 1.0f : 0.9f, &tl);
        pc_dir_out(skp_two_lobe_sample_dir(tl, pc_dir(k), u, u2), o);
        break;
    case 23:
        skp_fog_new(0.85f, 0.45f, 250.0f, 0.3f, &fog);
        o[0] = skp_fog_sample_cos(fog, u);
        o[1] = skp_fog_pdf(fog, o[0]);
        skp_fog_new(0.9f, 0.6f, 20.0f, u2, &fog);
        o[2] = skp_fog_sample_cos(fog, u);
        o[3] = skp_fog_pdf(fog, o[2]);
        break;
    case 24:
        sig[0] = 0.5f;
        sig[1] = 2.0f;
        sig[2] = SKP_MUL(3.0f, u2);
        o[0] = skp_spectral_free_path(sig, 3u, k % 3u, u, 1.5f, &o[1]);
        break;
    case 25:
        o[0] = skp_exp(skp_from_bits(k << 7));
        o[1] = skp_exp(-skp_from_bits(k << 7));
        o[2] = skp_exp(SKP_MUL(200.0f, u) - 100.0f);
        o[3] = skp_transmittance(2.5f, SKP_MUL(10.0f, u));
        break;
    case 26:
        pc_walk(k, u, u2, pc_u2(k ^ 0x5bd1e995u), maj, o);
        break;
    case 27:
        skp_schlick_new(0.7f, &sch);
        o[0] = skp_schlick_sample_cos(sch, u);
        o[1] = skp_schlick_pdf(sch, o[0]);
        skp_schlick_new(SKP_MUL(2.0f, u2) - 1.0f, &sch);
        o[2] = skp_schlick_sample_cos(sch, u);
        o[3] = skp_schlick_pdf(sch, o[2]);
        break;
    case 28:
        skp_schlick_new(k & 8u ? -0.4f : 0.85f, &sch);
        pc_dir_out(skp_schlick_sample_dir(sch, pc_dir(k), u, u2), o);
        break;
    case 29: /* the Dirac limits g = +-1 */
        skp_hg_new(1.0f, &hg);
        o[0] = skp_hg_sample_cos(hg, u);
        o[1] = skp_hg_pdf(hg, SKP_MUL(2.0f, u) - 1.0f);
        skp_hg_new(-1.0f, &hg);
        o[2] = skp_hg_sample_cos_sin(hg, u, &s, &pdf);
        o[3] = skp_hg_pdf(hg, SKP_MUL(2.0f, u2) - 1.0f) + s + pdf;
        break;
    case 30:
        skp_hg_new(k & 8u ? 1.0f : -1.0f, &hg);
        pc_dir_out(skp_hg_sample_dir(hg, pc_dir(k), u, u2), o);
        break;
    case 31: /* Dirac lobes in the mixtures */
        skp_two_lobe_new(1.0f, -0.3f, u2, &tl);
        o[0] = skp_two_lobe_sample_cos(tl, u);
        o[1] = skp_two_lobe_pdf(tl, o[0]);
        skp_fog_new(k & 8u ? -1.0f : 1.0f, 0.6f, 20.0f, k & 16u ? 1.0f : u2, &fog);
        o[2] = skp_fog_sample_cos(fog, u);
        o[3] = skp_fog_pdf(fog, o[2]);
        break;
    case 32:
        skp_draine_new(k & 8u ? 0.5f : -0.3f, k & 8u ? 1.0f : 250.0f, &dr);
        pc_dir_out(skp_draine_sample_dir(dr, pc_dir(k), u, u2), o);
        break;
    case 33:
        skp_fog_new(0.85f, 0.45f, 250.0f, k & 8u ? 0.3f : 1.0f, &fog);
        pc_dir_out(skp_fog_sample_dir(fog, pc_dir(k), u, u2), o);
        break;
    case 34: /* cos theta of the direction samplers */
        skp_hg_new(0.7f, &hg);
        o[0] = skp_hg_sample_dir(hg, pc_dir(k), u, u2).cos_theta;
        o[1] = skp_rayleigh_sample_dir(pc_dir(k), u, u2).cos_theta;
        o[2] = skp_isotropic_sample_dir(u, u2).cos_theta;
        skp_two_lobe_new(0.8f, -0.3f, 0.9f, &tl);
        o[3] = skp_two_lobe_sample_dir(tl, pc_dir(k), u, u2).cos_theta;
        break;
    default:
        v = skp_direction_about(pc_dir(k), SKP_MUL(2.0f, u) - 1.0f, u2, u);
        o[0] = v.x; o[1] = v.y; o[2] = v.z;
        break;
    }
}

#endif /* PORTABLE_CASES_H */
