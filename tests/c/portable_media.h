/* A per-medium table of model constants, as transport kernels keep their
 * media, shared by tests/c/portable_spaces.c (the host and OpenCL kernels
 * reading the table from __constant and __global memory), the CUDA device
 * compile of tests/c_abi/portable.rs, and written again in Rust there:
 * index k reads medium k % PM_MEDIA straight from the table T, whatever
 * its address space, and hashes 40 outputs (six direction samples with
 * their cos theta and density, five cosines and five densities). */
#ifndef PORTABLE_MEDIA_H
#define PORTABLE_MEDIA_H

#include "portable_cases.h"

#define PM_MEDIA 4u
#define PM_N 1048576u /* 2^20 indices */

/* One medium's phase functions. */
typedef struct pm_medium {
    skp_hg hg;
    skp_two_lobe two;
    skp_fog fog;
    skp_draine draine;
    skp_schlick schlick;
} pm_medium;

/* Medium m's constants: ordinary values and the edges (|g| = 1 lobes, a
   weight of 0 or 1, g = 0, k = 0). 1 when every constructor accepted. */
SKP_FN int pm_medium_new(skp_u32 m, pm_medium *o) {
    int ok = 1;
    switch (m) {
    case 0:
        ok &= skp_hg_new(0.85f, &o->hg);
        ok &= skp_two_lobe_new(0.8f, -0.3f, 0.9f, &o->two);
        ok &= skp_fog_new(0.85f, 0.45f, 250.0f, 0.3f, &o->fog);
        ok &= skp_draine_new(0.5f, 1.0f, &o->draine);
        ok &= skp_schlick_new(0.7f, &o->schlick);
        break;
    case 1:
        ok &= skp_hg_new(-0.4f, &o->hg);
        ok &= skp_two_lobe_new(1.0f, -0.3f, 0.25f, &o->two);
        ok &= skp_fog_new(0.9f, 0.6f, 20.0f, 0.1f, &o->fog);
        ok &= skp_draine_new(-0.3f, 250.0f, &o->draine);
        ok &= skp_schlick_new(-0.4f, &o->schlick);
        break;
    case 2:
        ok &= skp_hg_new(1.0f, &o->hg);
        ok &= skp_two_lobe_new(0.5f, 0.99f, 0.5f, &o->two);
        ok &= skp_fog_new(-1.0f, 0.6f, 20.0f, 0.4f, &o->fog);
        ok &= skp_draine_new(0.9f, 10.0f, &o->draine);
        ok &= skp_schlick_new(0.0f, &o->schlick);
        break;
    default:
        ok &= skp_hg_new(0.0f, &o->hg);
        ok &= skp_two_lobe_new(0.2f, -1.0f, 1.0f, &o->two);
        ok &= skp_fog_new(0.85f, 0.45f, 250.0f, 1.0f, &o->fog);
        ok &= skp_draine_new(0.01f, 1000.0f, &o->draine);
        ok &= skp_schlick_new(0.95f, &o->schlick);
        break;
    }
    return ok;
}

/* The uniforms of index k: scrambled over [0, 1), the last 16 indices the
   special values of portable_cases.h. */
SKP_FN float pm_u(skp_u32 k) {
    return k >= PM_N - 16u ? pc_u(PC_N - PM_N + k) : pc_u2(k ^ 0x9e3779b9u);
}

/* FNV-1a of one float's bits into h, NaN canonical. */
SKP_FN skp_u32 pm_mix(skp_u32 h, float x) {
    skp_u32 w = skp_bits(x);
    w = (w & 0x7fffffffu) > 0x7f800000u ? 0x7fc00000u : w;
    return (h ^ w) * 16777619u;
}

SKP_FN skp_u32 pm_mix_dir(skp_u32 h, skp_dir_sample r) {
    h = pm_mix(h, r.dir.x);
    h = pm_mix(h, r.dir.y);
    h = pm_mix(h, r.dir.z);
    h = pm_mix(h, r.cos_theta);
    return pm_mix(h, r.pdf);
}

/* Index k's hash into h, the constants read from T[k % PM_MEDIA] as they
   stand: T may be a __constant, __global or private table (OpenCL), a
   __constant__ or device one (CUDA), or a host array. */
#define PM_HASH(T, k, h)                                                               \
    do {                                                                               \
        skp_u32 m_ = (k) % PM_MEDIA;                                                   \
        float u_ = pm_u(k), v_ = pc_u2(k), c_;                                         \
        skp_vec3 w_ = pc_dir(k);                                                       \
        h = 2166136261u;                                                               \
        h = pm_mix_dir(h, skp_hg_sample_dir(T[m_].hg, w_, u_, v_));                    \
        h = pm_mix_dir(h, skp_two_lobe_sample_dir(T[m_].two, w_, u_, v_));             \
        h = pm_mix_dir(h, skp_fog_sample_dir(T[m_].fog, w_, u_, v_));                  \
        h = pm_mix_dir(h, skp_draine_sample_dir(T[m_].draine, w_, u_, v_));            \
        h = pm_mix_dir(h, skp_schlick_sample_dir(T[m_].schlick, w_, u_, v_));          \
        h = pm_mix_dir(h, skp_rayleigh_sample_dir(w_, u_, v_));                        \
        c_ = SKP_MUL(2.0f, v_) - 1.0f;                                                 \
        h = pm_mix(h, skp_hg_sample_cos(T[m_].hg, u_));                                \
        h = pm_mix(h, skp_hg_pdf(T[m_].hg, c_));                                       \
        h = pm_mix(h, skp_two_lobe_sample_cos(T[m_].two, u_));                         \
        h = pm_mix(h, skp_two_lobe_pdf(T[m_].two, c_));                                \
        h = pm_mix(h, skp_fog_sample_cos(T[m_].fog, u_));                              \
        h = pm_mix(h, skp_fog_pdf(T[m_].fog, c_));                                     \
        h = pm_mix(h, skp_draine_sample_cos(T[m_].draine, u_));                        \
        h = pm_mix(h, skp_draine_pdf(T[m_].draine, c_));                               \
        h = pm_mix(h, skp_schlick_sample_cos(T[m_].schlick, u_));                      \
        h = pm_mix(h, skp_schlick_pdf(T[m_].schlick, c_));                             \
    } while (0)

#endif /* PORTABLE_MEDIA_H */
