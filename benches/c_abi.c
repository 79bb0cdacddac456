/* Speed and accuracy as a C renderer sees them: libscatterkit called through
 * include/scatterkit.h, beside the peers' published formulas written inline
 * in C. Built at -O2 and linked against libscatterkit.a by the main example
 * (examples/speed_accuracy), which puts these points on the chart and in
 * docs/measured/PERFORMANCE.md as "through the C ABI".
 *
 * Peers, re-implemented from their published descriptions (not copied):
 *   pbrt-v4 SampleHenyeyGreenstein (Pharr, Jakob, Humphreys): the textbook
 *     inverse with g clamped to [-0.99, 0.99], isotropic below |g| < 1e-3,
 *     sin/cos of 2 pi u, Frame::FromZ (Duff et al. 2017) and the HG pdf.
 *   Mitsuba 3 Rayleigh: Cardano with two cube roots.
 *   Cycles Rayleigh: Cardano with the fast inverse cube root (two Newton steps).
 *   Frisvad (2011) simplified rejection: mu = 2 xi - 1 kept with (1 + mu^2)/2.
 *   pbrt-v4 SampleUniformSphere: z from one uniform, r = sqrt(1 - z^2),
 *     sin/cos of 2 pi u, about +z (no frame), density 1/(4 pi).
 *   Jendersie & d'Eon (2023) eq. 6 for Draine, as published, in float.
 *   Cycles' Fournier-Forand sampler: the published forward CDF (Fournier &
 *     Jonasz 1999) with a first-order expansion within 1e-3 of delta = 1,
 *     inverted by up to 20 Newton steps in float from 50 degrees, the
 *     coefficients from the backscatter fraction and the index.
 * All map u in [0, 1) to cos theta with u = 0 giving -1 (the library's
 * orientation); directions are built the same way everywhere.
 *
 * Timing: ns per sample, the minimum over ROUNDS interleaved rounds of N
 * samples each (the minimum, since this shared machine's noise only ever
 * adds time), xoshiro256++ inline (or behind sk_rng where the API takes
 * one). Accuracy: max |cos theta - reference| over N + 1 evenly spaced u
 * (for directions, |dot(w_in, w_out) - reference|), the reference being the
 * library's double-precision sampler; -1 where not measured (rejection).
 * The portable f32 tier (scatterkit_portable.h) is measured inline, as a
 * renderer or kernel compiles it, and through its library batch,
 * sk_phase_sample_cos_n_portable.
 * Output: one line per measurement, "key<TAB>ns<TAB>max_error". */
#include "scatterkit.h"
#include "scatterkit_inline.h"
#include "scatterkit_portable.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#define N (1u << 18)
#define ROUNDS 15
#define BATCH 4096
#define PI_F 3.14159265358979323846f
#define INV_4PI_F 0.0795774715459476679f

/* xoshiro256++ (Blackman & Vigna). */
typedef struct { uint64_t s[4]; } xoshiro;
static inline uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
static inline uint64_t xo_next(xoshiro *r) {
    uint64_t *s = r->s;
    uint64_t out = rotl(s[0] + s[3], 23) + s[0];
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return out;
}
static inline float xo_float(xoshiro *r) { return (float)(xo_next(r) >> 40) * 0x1p-24f; }
static uint64_t xo_callback(void *state) { return xo_next((xoshiro *)state); }
static xoshiro xo_seed(uint64_t seed) {
    xoshiro r;
    int i;
    for (i = 0; i < 4; i++) { /* splitmix64 */
        uint64_t z = (seed += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        r.s[i] = z ^ (z >> 31);
    }
    return r;
}

static double now_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e9 + (double)t.tv_nsec;
}

static volatile float sink;

/* ---- the peers' formulas, inline ---- */

/* Duff et al. (2017) basis, as pbrt-v4's CoordinateSystem and Mitsuba 3's
 * coordinate_system. */
static inline sk_vec3 frame_dir(sk_vec3 n, float sin_t, float cos_t, float phi) {
    float sign = copysignf(1.0f, n.z);
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    sk_vec3 b1 = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    sk_vec3 b2 = {b, sign + n.y * n.y * a, -n.y};
    float x = sin_t * cosf(phi), y = sin_t * sinf(phi);
    sk_vec3 w = {x * b1.x + y * b2.x + cos_t * n.x, x * b1.y + y * b2.y + cos_t * n.y,
                 x * b1.z + y * b2.z + cos_t * n.z};
    return w;
}

static inline float pbrt_hg_cos(float g, float u) {
    g = g < -0.99f ? -0.99f : (g > 0.99f ? 0.99f : g);
    if (fabsf(g) < 1e-3f) return 2.0f * u - 1.0f;
    float sq = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
    return (1.0f + g * g - sq * sq) / (2.0f * g);
}
/* Two HG lobes chosen by one uniform (the usual renderer sampler): u < w
 * picks lobe 1 and u / w is reused inside it, else lobe 2 with (u - w) /
 * (1 - w). */
static inline float two_lobe_cos(float g1, float g2, float w, float u) {
    return u < w ? pbrt_hg_cos(g1, u / w) : pbrt_hg_cos(g2, (u - w) / (1.0f - w));
}
/* Cycles-style Fournier-Forand: coefficients (n, v, c) from backscatter
 * fraction b and index n; the published forward CDF and density in float;
 * Newton on cos theta. */
typedef struct { float n, v, c; } ff_coeffs;
static ff_coeffs ff_setup(float b, float n) {
    float k = 4.0f / (3.0f * (n - 1.0f) * (n - 1.0f));
    float d90 = 0.5f * k, d180 = k;
    ff_coeffs r;
    r.n = n;
    r.v = -logf(2.0f * b * (d90 - 1.0f) + 1.0f) / logf(d90);
    r.c = (powf(d180, -r.v) - 1.0f) / (d180 - 1.0f);
    return r;
}
static inline float ff_pdf_published(float cos_t, float d, float dv, float v, float s, float c) {
    float md = 1.0f - d, mdv = 1.0f - dv, pf;
    if (fabsf(md) < 1e-3f) {
        pf = v * ((v - 1.0f) - (v + 1.0f) / s) * (1.0f / (8.0f * PI_F));
        pf += v * (v + 1.0f) * md * (2.0f * (v - 1.0f) - (2.0f * v + 1.0f) / s) * (1.0f / (24.0f * PI_F));
    } else {
        pf = (v * md - mdv + (d * mdv - v * md) / s) / (4.0f * PI_F * md * md * dv);
    }
    return pf + c * (1.0f / (16.0f * PI_F)) * (3.0f * cos_t * cos_t - 1.0f);
}
static inline float cycles_ff_cos(ff_coeffs k, float u) {
    float cos_t = 0.64278760968f, kk = 4.0f / (3.0f * (k.n - 1.0f) * (k.n - 1.0f));
    int it;
    for (it = 0; it < 20; it++) {
        float s = 0.5f * (1.0f - cos_t), d = kk * s, dv = powf(d, k.v), md = 1.0f - d, cdf, pf, next;
        if (fabsf(md) < 1e-3f)
            cdf = 1.0f + k.v * (1.0f - s) * (1.0f - 0.5f * (k.v + 1.0f) * md);
        else
            cdf = (1.0f - dv * d - (1.0f - dv) * s) / (md * dv);
        cdf += k.c * 0.125f * cos_t * (1.0f - cos_t * cos_t);
        pf = ff_pdf_published(cos_t, d, dv, k.v, s, k.c);
        next = cos_t + (cdf - u) / (2.0f * PI_F * pf);
        if (next >= 1.0f) next = fmaxf(0.5f * (cos_t + 1.0f), 0.99f);
        if (fabsf(cos_t - next) < 1e-6f || next == 1.0f) return next;
        cos_t = next;
    }
    return cos_t;
}
static inline float pbrt_hg_pdf(float g, float cos_t) {
    float denom = 1.0f + g * g - 2.0f * g * cos_t;
    return INV_4PI_F * (1.0f - g * g) / (denom * sqrtf(denom));
}
static inline sk_vec3 pbrt_hg_dir(float g, sk_vec3 w, float u1, float u2, float *pdf) {
    float c = pbrt_hg_cos(g, u1);
    float s = sqrtf(fmaxf(0.0f, 1.0f - c * c));
    *pdf = pbrt_hg_pdf(g, c);
    return frame_dir(w, s, c, 2.0f * PI_F * u2);
}

static inline float mitsuba_rayleigh_cos(float u) {
    float z = 2.0f * (2.0f * u - 1.0f);
    float r = sqrtf(z * z + 1.0f);
    return cbrtf(z + r) + cbrtf(z - r);
}

static inline float fast_inv_cbrt(float x) {
    union { float f; uint32_t i; } v;
    v.f = x;
    v.i = 0x54a24242u - v.i / 3u;
    float y = v.f;
    y = y * (4.0f - x * y * y * y) * (1.0f / 3.0f);
    y = y * (4.0f - x * y * y * y) * (1.0f / 3.0f);
    return y;
}
static inline float cycles_rayleigh_cos(float u) {
    float z = 2.0f * (2.0f * u - 1.0f);
    float inv_w = fast_inv_cbrt(z + sqrtf(z * z + 1.0f));
    return 1.0f / inv_w - inv_w;
}

static inline sk_vec3 rayleigh_dir_from_cos(sk_vec3 w, float c, float u2, float *pdf) {
    *pdf = 3.0f / (16.0f * PI_F) * (1.0f + c * c);
    return frame_dir(w, sqrtf(fmaxf(0.0f, 1.0f - c * c)), c, 2.0f * PI_F * u2);
}

static inline sk_vec3 simplified_rejection_dir(xoshiro *r, sk_vec3 w) {
    float mu;
    for (;;) {
        mu = 2.0f * xo_float(r) - 1.0f;
        if (2.0f * xo_float(r) <= 1.0f + mu * mu) break;
    }
    return frame_dir(w, sqrtf(fmaxf(0.0f, 1.0f - mu * mu)), mu, 2.0f * PI_F * xo_float(r));
}

static inline sk_vec3 isotropic_dir(sk_vec3 w, float u1, float u2, float *pdf) {
    float c = 2.0f * u1 - 1.0f;
    *pdf = INV_4PI_F;
    return frame_dir(w, sqrtf(fmaxf(0.0f, (1.0f - c) * (1.0f + c))), c, 2.0f * PI_F * u2);
}

/* pbrt-v4's SampleUniformSphere (z = 2u - 1 here, the file's orientation),
   about +z as pbrt returns it: the peer of skp_isotropic_sample_dir. */
static inline sk_vec3 pbrt_uniform_sphere(float u1, float u2, float *pdf) {
    float z = 2.0f * u1 - 1.0f, r = sqrtf(fmaxf(0.0f, 1.0f - z * z)), phi = 2.0f * PI_F * u2;
    sk_vec3 d = {r * cosf(phi), r * sinf(phi), z};
    *pdf = INV_4PI_F;
    return d;
}

/* The portable header's samplers with this file's vector type. */
static skp_hg php;
static inline sk_vec3 from_skp(skp_vec3 v) {
    sk_vec3 r = {v.x, v.y, v.z};
    return r;
}
static inline skp_vec3 to_skp(sk_vec3 v) {
    skp_vec3 r;
    r.x = v.x;
    r.y = v.y;
    r.z = v.z;
    return r;
}
static inline sk_vec3 header_hg_dir(sk_vec3 w, float u1, float u2, float *pdf) {
    skp_dir_sample r = skp_hg_sample_dir(php, to_skp(w), u1, u2);
    *pdf = r.pdf;
    return from_skp(r.dir);
}
static inline sk_vec3 header_rayleigh_dir(sk_vec3 w, float u1, float u2, float *pdf) {
    skp_dir_sample r = skp_rayleigh_sample_dir(to_skp(w), u1, u2);
    *pdf = r.pdf;
    return from_skp(r.dir);
}
/* The isotropic direction about w (the header's own is about +z; this one
   is for the accuracy check about W_IN). */
static inline sk_vec3 header_iso_dir_about(sk_vec3 w, float u1, float u2, float *pdf) {
    float s, mu = skp_isotropic_sample_cos_sin(u1, &s);
    *pdf = SKP_INV_4PI;
    return from_skp(skp_direction_about(to_skp(w), mu, s, u2));
}

/* Eq. 6 of Jendersie & d'Eon (2023), as published. */
static inline float draine_eq6(float g, float a, float u) {
    float g2 = g * g, g4 = g2 * g2;
    float t0 = a - a * g2;
    float t1 = a * g4 - a;
    float t2 = -3.0f * (4.0f * (g4 - g2) + t1 * (1.0f + g2));
    float t3 = g * (2.0f * u - 1.0f);
    float t4 = 3.0f * g2 * (1.0f + t3) + a * (2.0f + g2 * (1.0f + (1.0f + 2.0f * g2) * t3));
    float t5 = t0 * (t1 * t2 + t4 * t4) + t1 * t1 * t1;
    float t6 = t0 * 4.0f * (g4 - g2);
    float t7 = cbrtf(t5 + sqrtf(t5 * t5 - t6 * t6 * t6));
    float t8 = 2.0f * (t1 + t6 / t7 + t7) / t0;
    float t9 = sqrtf(6.0f * (1.0f + g2) + t8);
    float d = sqrtf(6.0f * (1.0f + g2) - t8 + 8.0f * t4 / (t0 * t9)) - t9;
    return g / 2.0f + (1.0f / (2.0f * g) - d * d / (8.0f * g));
}

/* ---- harness ---- */

#define MAX_CASES 64
typedef struct {
    const char *key;
    double best;
    double err;
} result;
static result results[MAX_CASES];
static int n_results;

static result *slot(const char *key) {
    int i;
    for (i = 0; i < n_results; i++)
        if (strcmp(results[i].key, key) == 0) return &results[i];
    results[n_results].key = key;
    results[n_results].best = 1e300;
    results[n_results].err = -1.0;
    return &results[n_results++];
}
static void record(const char *key, double t0, double t1, double count) {
    result *r = slot(key);
    double ns = (t1 - t0) / count;
    if (ns < r->best) r->best = ns;
}

/* Times the statement given (using `rng`, adding to `acc`) N times. */
#define TIME(key, ...)                          \
    do {                                         \
        xoshiro rng = xo_seed(7);                \
        float acc = 0.0f;                        \
        uint32_t it;                             \
        double t0 = now_ns();                    \
        for (it = 0; it < N; it++) { __VA_ARGS__; }     \
        record(key, t0, now_ns(), (double)N);    \
        sink = acc;                              \
        (void)rng;                               \
    } while (0)

static const sk_vec3 W_IN = {0.48f, 0.6f, 0.64f};

/* Batch inputs: BATCH directions and uniforms, structure of arrays. */
static float bu1[BATCH], bu2[BATCH], bwx[BATCH], bwy[BATCH], bwz[BATCH];
static float box[BATCH], boy[BATCH], boz[BATCH], bpdf[BATCH], bcos[BATCH];

static void fill_batch(void) {
    xoshiro r = xo_seed(11);
    int i;
    for (i = 0; i < BATCH; i++) {
        float c = 2.0f * xo_float(&r) - 1.0f, phi = 2.0f * PI_F * xo_float(&r);
        float s = sqrtf(fmaxf(0.0f, 1.0f - c * c));
        bwx[i] = s * cosf(phi);
        bwy[i] = s * sinf(phi);
        bwz[i] = c;
        bu1[i] = xo_float(&r);
        bu2[i] = xo_float(&r);
    }
}

/* Times a pass over the batch arrays `N / BATCH` times. */
/* Each repetition of a batch computes what the last one did: without a
   barrier, -O3 may run the loop once and drop the repeats (the inline-C
   cosine loop read 0.03 ns per sample at -O3 -march=native). The empty asm
   with a memory clobber makes every repetition read and write memory. */
#if defined(__GNUC__)
#define BATCH_BARRIER() __asm__ __volatile__("" ::: "memory")
#else
#define BATCH_BARRIER() ((void)0)
#endif

#define TIME_BATCH(key, ...)                                  \
    do {                                                       \
        uint32_t rep;                                          \
        double t0 = now_ns();                                  \
        for (rep = 0; rep < N / BATCH; rep++) { __VA_ARGS__; BATCH_BARRIER(); } \
        record(key, t0, now_ns(), (double)N);                  \
        sink = box[rep & (BATCH - 1)] + bcos[rep & (BATCH - 1)]; \
    } while (0)

static sk_phase iso, hg, ray, fog, two, ff, draine[4];
static sk_mixture mix;
static sk_phase_cos_inline hgi;
static sk_phase_f64 hg64, ray64, fog64, two64, ff64, draine64[4];
static ff_coeffs ffc;
static const float DRAINE_G[4] = {0.5f, 0.9f, 0.3f, 0.01f};
static const float DRAINE_A[4] = {1.0f, 10.0f, 250.0f, 1000.0f};
static const char *DRAINE_SK[4] = {"draine_0.5_1.sk", "draine_0.9_10.sk", "draine_0.3_250.sk",
                                   "draine_0.01_1000.sk"};
static const char *DRAINE_HEADER[4] = {"draine_0.5_1.header", "draine_0.9_10.header",
                                       "draine_0.3_250.header", "draine_0.01_1000.header"};
static skp_draine draine_p[4];
static skp_two_lobe two_p;
static const char *DRAINE_EQ6[4] = {"draine_0.5_1.eq6", "draine_0.9_10.eq6", "draine_0.3_250.eq6",
                                    "draine_0.01_1000.eq6"};

static void time_round(void) {
    int k;
    float pdf;
    sk_rng crng;
    xoshiro cstate;

    TIME("iso_dir.sk", {
        sk_vec3 d = sk_phase_sample_dir(&iso, W_IN, xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME("iso_dir.c", {
        sk_vec3 d = isotropic_dir(W_IN, xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    /* About +z, z does not depend on the azimuth: every component is summed
       here and for skp_isotropic_sample_dir, so neither loses its sine and
       cosine to dead-code elimination. */
    TIME("iso_dir.pbrt", {
        sk_vec3 d = pbrt_uniform_sphere(xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.x + d.y + d.z + pdf;
    });
    TIME("hg_dir.sk", {
        sk_vec3 d = sk_phase_sample_dir(&hg, W_IN, xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME("hg_dir.pbrt", {
        sk_vec3 d = pbrt_hg_dir(0.7f, W_IN, xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME("hg_cos.sk", acc += sk_phase_sample_cos(&hg, xo_float(&rng)));
    TIME("hg_cos.pbrt", acc += pbrt_hg_cos(0.7f, xo_float(&rng)));
    TIME("hg_cos.inline", acc += sk_phase_cos_inline_sample(&hgi, xo_float(&rng)));
    TIME("hg_cos.header", acc += skp_hg_sample_cos(php, xo_float(&rng)));
    TIME("hg_dir.header", {
        sk_vec3 d = header_hg_dir(W_IN, xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME("iso_dir.header", {
        skp_dir_sample d = skp_isotropic_sample_dir(xo_float(&rng), xo_float(&rng));
        acc += d.dir.x + d.dir.y + d.dir.z + d.pdf;
    });
    TIME("rayleigh_dir.header", {
        sk_vec3 d = header_rayleigh_dir(W_IN, xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME_BATCH("hg_cos_n.portable", sk_phase_sample_cos_n_portable(&hg, bu1, bcos, BATCH));
    TIME_BATCH("hg_cos_n.header", {
        int i;
        for (i = 0; i < BATCH; i++) bcos[i] = skp_hg_sample_cos(php, bu1[i]);
    });
    TIME_BATCH("hg_cos_n.sk", sk_phase_sample_cos_n(&hg, bu1, bcos, BATCH));
    TIME_BATCH("hg_cos_n.pbrt", {
        int i;
        for (i = 0; i < BATCH; i++) bcos[i] = pbrt_hg_cos(0.7f, bu1[i]);
    });
    TIME_BATCH("hg_dir_n.sk", sk_phase_sample_dir_n(&hg, bwx, bwy, bwz, bu1, bu2, box, boy, boz,
                                                    bpdf, BATCH));
    TIME_BATCH("hg_dir_n.portable", sk_phase_sample_dir_n_portable(&hg, bwx, bwy, bwz, bu1, bu2, box,
                                                                   boy, boz, bpdf, BATCH));
    TIME_BATCH("hg_dir_n.pbrt", {
        int i;
        for (i = 0; i < BATCH; i++) {
            sk_vec3 w = {bwx[i], bwy[i], bwz[i]};
            sk_vec3 d = pbrt_hg_dir(0.7f, w, bu1[i], bu2[i], &bpdf[i]);
            box[i] = d.x;
            boy[i] = d.y;
            boz[i] = d.z;
        }
    });
    TIME("rayleigh_dir.sk", {
        sk_vec3 d = sk_phase_sample_dir(&ray, W_IN, xo_float(&rng), xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME("rayleigh_dir.mitsuba", {
        float c = mitsuba_rayleigh_cos(xo_float(&rng));
        sk_vec3 d = rayleigh_dir_from_cos(W_IN, c, xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME("rayleigh_dir.cycles", {
        float c = cycles_rayleigh_cos(xo_float(&rng));
        sk_vec3 d = rayleigh_dir_from_cos(W_IN, c, xo_float(&rng), &pdf);
        acc += d.z + pdf;
    });
    TIME("rayleigh_dir.simplified", acc += simplified_rejection_dir(&rng, W_IN).z);
    cstate = xo_seed(7);
    crng.state = &cstate;
    crng.next_u64 = xo_callback;
    {
        static const uint32_t methods[3] = {SK_RAYLEIGH_DIRECT, SK_RAYLEIGH_DIRECT_MINIMAX,
                                            SK_RAYLEIGH_TABLE};
        static const char *keys[3] = {"rayleigh_rng_dir.direct", "rayleigh_rng_dir.minimax",
                                      "rayleigh_rng_dir.table"};
        for (k = 0; k < 3; k++) {
            uint32_t m = methods[k];
            TIME(keys[k], {
                sk_vec3 d;
                sk_rayleigh_sample_dir(m, W_IN, &crng, &d);
                acc += d.z;
            });
        }
    }
    TIME("rayleigh_rng_dir.simplified_callback", {
        /* The same rejection drawing through the callback, as the library must. */
        float mu;
        for (;;) {
            mu = 2.0f * (float)(crng.next_u64(crng.state) >> 40) * 0x1p-24f - 1.0f;
            if (2.0f * (float)(crng.next_u64(crng.state) >> 40) * 0x1p-24f <= 1.0f + mu * mu) break;
        }
        acc += frame_dir(W_IN, sqrtf(fmaxf(0.0f, 1.0f - mu * mu)), mu,
                         2.0f * PI_F * (float)(crng.next_u64(crng.state) >> 40) * 0x1p-24f)
                   .z;
    });
    TIME_BATCH("rayleigh_rng_dir_n.table",
               sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, bwx, bwy, bwz, &crng, box, boy, boz,
                                        BATCH));
    TIME("fog_cos.sk", acc += sk_phase_sample_cos(&fog, xo_float(&rng)));
    TIME("rayleigh_cos.sk", acc += sk_phase_sample_cos(&ray, xo_float(&rng)));
    TIME("mix_lobe.sk", acc += sk_mixture_sample_cos_by_lobe(&mix, xo_float(&rng)));
    TIME("fog_cos.lobe", acc += sk_phase_sample_cos_by_lobe(&fog, xo_float(&rng)));
    TIME("two_lobe_cos.sk", acc += sk_phase_sample_cos(&two, xo_float(&rng)));
    TIME("two_lobe_cos.sk_lobe", acc += sk_phase_sample_cos_by_lobe(&two, xo_float(&rng)));
    TIME("two_lobe_cos.c", acc += two_lobe_cos(0.8f, -0.3f, 0.9f, xo_float(&rng)));
    TIME("two_lobe_cos.header", acc += skp_two_lobe_sample_cos(two_p, xo_float(&rng)));
    TIME("ff_cos.sk", acc += sk_phase_sample_cos(&ff, xo_float(&rng)));
    TIME("ff_cos.cycles", acc += cycles_ff_cos(ffc, xo_float(&rng)));
    for (k = 0; k < 4; k++) {
        float g = DRAINE_G[k], a = DRAINE_A[k];
        TIME(DRAINE_SK[k], acc += sk_phase_sample_cos(&draine[k], xo_float(&rng)));
        TIME(DRAINE_EQ6[k], acc += draine_eq6(g, a, xo_float(&rng)));
        TIME(DRAINE_HEADER[k], acc += skp_draine_sample_cos(draine_p[k], xo_float(&rng)));
    }
}

/* max |f(u) - ref(u)| over N + 1 evenly spaced u; a NaN counts as 2. */
#define MAX_ERR(key, ref64, ...)                                  \
    do {                                                                \
        double e = 0.0;                                                 \
        uint32_t i;                                                     \
        for (i = 0; i <= N; i++) {                                      \
            float u = (float)i / (float)N;                              \
            double d = fabs((double)(__VA_ARGS__) - sk_phase_sample_cos_f64(ref64, (double)u)); \
            if (!(d <= 2.0)) d = 2.0;                                   \
            if (d > e) e = d;                                           \
        }                                                               \
        slot(key)->err = e;                                             \
    } while (0)

/* Directions: max |dot(w_in, w_out) - ref(u1)| with u2 from a generator. */
#define MAX_DIR_ERR(key, ref64, ...)                            \
    do {                                                                 \
        double e = 0.0;                                                  \
        uint32_t i;                                                      \
        xoshiro rng = xo_seed(3);                                        \
        for (i = 0; i <= N; i++) {                                       \
            float u1 = (float)i / (float)N, u2 = xo_float(&rng);         \
            sk_vec3 d = __VA_ARGS__;                                    \
            double c = (double)W_IN.x * d.x + (double)W_IN.y * d.y + (double)W_IN.z * d.z; \
            double dd = fabs(c - sk_phase_sample_cos_f64(ref64, (double)u1)); \
            if (!(dd <= 2.0)) dd = 2.0;                                  \
            if (dd > e) e = dd;                                          \
        }                                                                \
        slot(key)->err = e;                                              \
    } while (0)

static void accuracy(void) {
    int k;
    float pdf;
    sk_phase_f64 iso64;
    sk_phase_new_isotropic_f64(&iso64);
    MAX_DIR_ERR("iso_dir.sk", &iso64, sk_phase_sample_dir(&iso, W_IN, u1, u2, &pdf));
    MAX_DIR_ERR("iso_dir.c", &iso64, isotropic_dir(W_IN, u1, u2, &pdf));
    MAX_ERR("iso_dir.pbrt", &iso64, pbrt_uniform_sphere(u, 0.3f, &pdf).z);
    MAX_DIR_ERR("hg_dir.sk", &hg64, sk_phase_sample_dir(&hg, W_IN, u1, u2, &pdf));
    MAX_DIR_ERR("hg_dir.pbrt", &hg64, pbrt_hg_dir(0.7f, W_IN, u1, u2, &pdf));
    MAX_ERR("hg_cos.sk", &hg64, sk_phase_sample_cos(&hg, u));
    MAX_ERR("hg_cos.pbrt", &hg64, pbrt_hg_cos(0.7f, u));
    MAX_ERR("hg_cos.inline", &hg64, sk_phase_cos_inline_sample(&hgi, u));
    MAX_ERR("hg_cos_n.sk", &hg64, sk_phase_sample_cos(&hg, u));
    MAX_ERR("hg_cos_n.pbrt", &hg64, pbrt_hg_cos(0.7f, u));
    /* The batch returns the header's bits (tests/c/portable_batch.c). */
    MAX_ERR("hg_cos_n.portable", &hg64, skp_hg_sample_cos(php, u));
    MAX_ERR("hg_cos_n.header", &hg64, skp_hg_sample_cos(php, u));
    MAX_ERR("hg_cos.header", &hg64, skp_hg_sample_cos(php, u));
    MAX_DIR_ERR("hg_dir.header", &hg64, header_hg_dir(W_IN, u1, u2, &pdf));
    /* The direction batch returns the header's bits (tests/c/portable_batch.c). */
    MAX_DIR_ERR("hg_dir_n.portable", &hg64, header_hg_dir(W_IN, u1, u2, &pdf));
    MAX_DIR_ERR("iso_dir.header", &iso64, header_iso_dir_about(W_IN, u1, u2, &pdf));
    MAX_DIR_ERR("rayleigh_dir.header", &ray64, header_rayleigh_dir(W_IN, u1, u2, &pdf));
    MAX_DIR_ERR("rayleigh_dir.sk", &ray64, sk_phase_sample_dir(&ray, W_IN, u1, u2, &pdf));
    MAX_DIR_ERR("rayleigh_dir.mitsuba", &ray64,
                rayleigh_dir_from_cos(W_IN, mitsuba_rayleigh_cos(u1), u2, &pdf));
    MAX_DIR_ERR("rayleigh_dir.cycles", &ray64,
                rayleigh_dir_from_cos(W_IN, cycles_rayleigh_cos(u1), u2, &pdf));
    MAX_ERR("fog_cos.sk", &fog64, sk_phase_sample_cos(&fog, u));
    MAX_ERR("two_lobe_cos.sk", &two64, sk_phase_sample_cos(&two, u));
    /* Cycles maps u to the forward CDF: its cos theta for 1 - u is ours for u. */
    MAX_ERR("ff_cos.sk", &ff64, sk_phase_sample_cos(&ff, u));
    MAX_ERR("ff_cos.cycles", &ff64, cycles_ff_cos(ffc, 1.0f - u));
    for (k = 0; k < 4; k++) {
        float g = DRAINE_G[k], a = DRAINE_A[k];
        MAX_ERR(DRAINE_SK[k], &draine64[k], sk_phase_sample_cos(&draine[k], u));
        MAX_ERR(DRAINE_EQ6[k], &draine64[k], draine_eq6(g, a, u));
        MAX_ERR(DRAINE_HEADER[k], &draine64[k], skp_draine_sample_cos(draine_p[k], u));
    }
}

/* The batch call must give what the scalar call gives, bit for bit. */
static int batch_agrees(void) {
    int i;
    float pdf;
    if (sk_phase_sample_dir_n(&hg, bwx, bwy, bwz, bu1, bu2, box, boy, boz, bpdf, BATCH) != SK_OK)
        return 0;
    for (i = 0; i < BATCH; i++) {
        sk_vec3 w = {bwx[i], bwy[i], bwz[i]};
        sk_vec3 d = sk_phase_sample_dir(&hg, w, bu1[i], bu2[i], &pdf);
        if (memcmp(&d.x, &box[i], 4) || memcmp(&d.y, &boy[i], 4) || memcmp(&d.z, &boz[i], 4) ||
            memcmp(&pdf, &bpdf[i], 4))
            return 0;
    }
    return 1;
}

int main(void) {
    int k, r;
    if (sk_phase_new_isotropic(&iso) || sk_phase_new_hg(0.7f, &hg) || sk_phase_new_rayleigh(&ray) ||
        sk_phase_new_fog_diameter(2.0f, &fog) || sk_phase_new_hg_f64(0.7, &hg64) ||
        sk_phase_new_rayleigh_f64(&ray64) || sk_phase_new_fog_diameter_f64(2.0, &fog64) ||
        sk_phase_new_two_lobe_hg(0.8f, -0.3f, 0.9f, &two) || sk_phase_new_two_lobe_hg_f64(0.8, -0.3, 0.9, &two64) ||
        sk_phase_new_fournier_forand_backscatter(0.0183f, 1.1f, &ff) ||
        sk_phase_new_fournier_forand_backscatter_f64(0.0183, 1.1, &ff64) ||
        sk_phase_cos_inline_new(&hg, &hgi) || !skp_hg_new(0.7f, &php) ||
        !skp_two_lobe_new(0.8f, -0.3f, 0.9f, &two_p)) {
        fprintf(stderr, "constructor failed\n");
        return 1;
    }
    for (k = 0; k < 4; k++) {
        if (sk_phase_new_draine(DRAINE_G[k], DRAINE_A[k], &draine[k]) ||
            sk_phase_new_draine_f64((double)DRAINE_G[k], (double)DRAINE_A[k], &draine64[k]) ||
            !skp_draine_new(DRAINE_G[k], DRAINE_A[k], &draine_p[k])) {
            fprintf(stderr, "constructor failed\n");
            return 1;
        }
    }
    {
        /* Rayleigh, HG g = 0.7 and the 2 um fog, 50 : 30 : 20. */
        sk_mixture_part parts[3] = {{&ray, NULL, 0.5f}, {&hg, NULL, 0.3f}, {&fog, NULL, 0.2f}};
        if (sk_mixture_new(parts, 3, &mix)) {
            fprintf(stderr, "constructor failed\n");
            return 1;
        }
    }
    ffc = ff_setup(0.0183f, 1.1f);
    fill_batch();
    if (!batch_agrees()) {
        fprintf(stderr, "sk_phase_sample_dir_n differs from sk_phase_sample_dir\n");
        return 1;
    }
    for (r = 0; r < ROUNDS; r++) time_round();
    accuracy();
    for (k = 0; k < n_results; k++)
        printf("%s\t%.3f\t%.3e\n", results[k].key, results[k].best, results[k].err);
    return 0;
}
