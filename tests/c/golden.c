/* Golden values through the C API: fixed inputs, every sampler, f32 and f64,
 * printed as exact bit patterns. tests/c_abi/golden.rs prints the same lines
 * through the Rust API; both must equal tests/golden/golden.txt. */
#include <inttypes.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scatterkit.h"

static uint64_t splitmix64(void *state) {
    uint64_t *s = (uint64_t *)state;
    uint64_t z = (*s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static uint32_t b32(float x) {
    uint32_t u;
    memcpy(&u, &x, 4);
    return u;
}
static uint64_t b64(double x) {
    uint64_t u;
    memcpy(&u, &x, 8);
    return u;
}

enum { K = 8 };
static const double US[K] = {0.0, 1e-7, 0.1, 0.37, 0.5, 0.8125, 0.999999, 1.0};

static void phase32(const char *name, const sk_phase *p) {
    const sk_vec3 w = {0.48f, 0.6f, 0.64f};
    int i;
    printf("%s f32", name);
    for (i = 0; i < K; i++) {
        float pdf;
        sk_vec3 d = sk_phase_sample_dir(p, w, (float)US[i], (float)US[(i + 3) % K], &pdf);
        printf(" %08" PRIx32 ":%08" PRIx32 ":%08" PRIx32 ":%08" PRIx32 ":%08" PRIx32, b32(sk_phase_sample_cos(p, (float)US[i])),
               b32(d.x), b32(d.y), b32(d.z), b32(pdf));
    }
    printf("\n");
}

static void phase64(const char *name, const sk_phase_f64 *p) {
    const sk_vec3_f64 w = {0.48, 0.6, 0.64};
    int i;
    printf("%s f64", name);
    for (i = 0; i < K; i++) {
        double pdf;
        sk_vec3_f64 d = sk_phase_sample_dir_f64(p, w, US[i], US[(i + 3) % K], &pdf);
        printf(" %016" PRIx64 ":%016" PRIx64 ":%016" PRIx64 ":%016" PRIx64 ":%016" PRIx64, b64(sk_phase_sample_cos_f64(p, US[i])),
               b64(d.x), b64(d.y), b64(d.z), b64(pdf));
    }
    printf("\n");
}

int main(void) {
    sk_phase p;
    sk_phase_f64 q;
    uint32_t m;
    int i;

#define BOTH(name, ctor32, ctor64)      \
    if ((ctor32) != SK_OK) return 1;    \
    phase32(name, &p);                  \
    if ((ctor64) != SK_OK) return 1;    \
    phase64(name, &q);
    BOTH("isotropic", sk_phase_new_isotropic(&p), sk_phase_new_isotropic_f64(&q))
    BOTH("rayleigh", sk_phase_new_rayleigh(&p), sk_phase_new_rayleigh_f64(&q))
    BOTH("rayleigh_depolarized_0.028", sk_phase_new_rayleigh_depolarized(0.028f, &p), sk_phase_new_rayleigh_depolarized_f64(0.028, &q))
    BOTH("hg_0.7", sk_phase_new_hg(0.7f, &p), sk_phase_new_hg_f64(0.7, &q))
    BOTH("hg_-0.999", sk_phase_new_hg(-0.999f, &p), sk_phase_new_hg_f64(-0.999, &q))
    BOTH("draine_0.3_250", sk_phase_new_draine(0.3f, 250.0f, &p), sk_phase_new_draine_f64(0.3, 250.0, &q))
    BOTH("cornette_shanks_0.6", sk_phase_new_cornette_shanks(0.6f, &p), sk_phase_new_cornette_shanks_f64(0.6, &q))
    BOTH("fog_2um", sk_phase_new_fog_diameter(2.0f, &p), sk_phase_new_fog_diameter_f64(2.0, &q))
    BOTH("two_lobe_hg_0.8_-0.3_0.9", sk_phase_new_two_lobe_hg(0.8f, -0.3f, 0.9f, &p), sk_phase_new_two_lobe_hg_f64(0.8, -0.3, 0.9, &q))
    BOTH("gegenbauer_-0.25_0.7", sk_phase_new_gegenbauer(-0.25f, 0.7f, &p), sk_phase_new_gegenbauer_f64(-0.25, 0.7, &q))
    BOTH("fournier_forand_1.1_4", sk_phase_new_fournier_forand(1.1f, 4.0f, &p), sk_phase_new_fournier_forand_f64(1.1, 4.0, &q))
    {
        /* Schlick through the generic constructor, as a new model arrives. */
        const float k32 = 0.6f;
        const double k64 = 0.6;
        BOTH("schlick_0.6", sk_phase_new(SK_PHASE_SCHLICK, &k32, 1, &p), sk_phase_new_f64(SK_PHASE_SCHLICK, &k64, 1, &q))
    }
    BOTH("particle_0.01_0.01", sk_phase_new_particle(0.01f, 0.01f, &p), sk_phase_new_particle_f64(0.01, 0.01, &q))

    for (m = SK_RAYLEIGH_REJECT_CUBE; m <= SK_RAYLEIGH_TABLE; m++) {
        uint64_t s32 = 7, s64 = 7;
        sk_rng r32 = {&s32, splitmix64}, r64 = {&s64, splitmix64};
        sk_vec3 w = {0.48f, 0.6f, 0.64f}, d;
        sk_vec3_f64 w64 = {0.48, 0.6, 0.64}, d64;
        printf("rayleigh_method_%" PRIu32 " f32", m);
        for (i = 0; i < K; i++) {
            if (sk_rayleigh_sample_dir(m, w, &r32, &d) != SK_OK) return 1;
            printf(" %08" PRIx32 ":%08" PRIx32 ":%08" PRIx32, b32(d.x), b32(d.y), b32(d.z));
        }
        printf("\nrayleigh_method_%" PRIu32 " f64", m);
        for (i = 0; i < K; i++) {
            if (sk_rayleigh_sample_dir_f64(m, w64, &r64, &d64) != SK_OK) return 1;
            printf(" %016" PRIx64 ":%016" PRIx64 ":%016" PRIx64, b64(d64.x), b64(d64.y), b64(d64.z));
        }
        printf("\n");
    }

    {
        const sk_vec3 n = {0.0f, 0.6f, 0.8f}, axis = {0.6f, 0.0f, 0.8f}, inc = {0.6f, 0.0f, -0.8f}, up = {0.0f, 0.0f, 1.0f};
        uint32_t pol;
        sk_surface s;
        uint64_t seed = 11;
        sk_rng r = {&seed, splitmix64};
        printf("lambert f32");
        for (i = 0; i < K; i++) {
            sk_vec3 d = sk_lambert_sample(n, (float)US[i], (float)US[(i + 3) % K]);
            printf(" %08" PRIx32 ":%08" PRIx32 ":%08" PRIx32, b32(d.x), b32(d.y), b32(d.z));
        }
        printf("\n");
        for (pol = SK_CROSSING_FOLD; pol <= SK_CROSSING_MIRROR; pol++) {
            printf("phong_%" PRIu32 " f32", pol);
            for (i = 0; i < K; i++) {
                sk_vec3 d = sk_phong_sample(axis, up, 3.0f, pol, (float)US[i], (float)US[(i + 3) % K]);
                printf(" %08" PRIx32 ":%08" PRIx32 ":%08" PRIx32, b32(d.x), b32(d.y), b32(d.z));
            }
            printf("\n");
        }
        if (sk_surface_new(SK_SURFACE_PHONG, 100.0f, SK_FRACTION_SCALAR, 0.0f, 50e-9f, SK_CROSSING_RESAMPLE, &s) != SK_OK) return 1;
        printf("interact f32");
        for (i = 0; i < K; i++) {
            sk_vec3 d;
            uint32_t ev;
            if (sk_surface_interact(&s, inc, up, 1.5f, 3.9f, 600e-9f, &r, &d, &ev) != SK_OK) return 1;
            printf(" %08" PRIx32 ":%08" PRIx32 ":%08" PRIx32 ":%" PRIu32, b32(d.x), b32(d.y), b32(d.z), ev);
        }
        printf("\n");
    }

    {
        const float st[3] = {0.5f, 1.0f, 2.0f}, ss[3] = {0.4f, 0.9f, 1.5f};
        const float dens[8] = {0.1f, 0.9f, 0.4f, 0.7f, 1.0f, 0.2f, 0.3f, 0.6f};
        sk_grid g;
        sk_track_args a;
        sk_track_result res;
        uint64_t seed = 13;
        sk_rng r = {&seed, splitmix64};
        const sk_vec3 o = {-0.5f, 0.31f, 0.47f}, d = {1.0f, 0.1f, 0.0f};
        printf("free_path f32");
        for (i = 0; i < K; i++) printf(" %08" PRIx32, b32(sk_free_path(2.0f, (float)US[i])));
        printf("\nhomogeneous f32");
        for (i = 0; i < K; i++) {
            float t, w[3];
            uint32_t sc;
            if (sk_homogeneous_sample(st, ss, 3, 1.0f, (float)US[i], (float)US[(i + 3) % K], &t, &sc, w) != SK_OK) return 1;
            printf(" %08" PRIx32 ":%" PRIu32 ":%08" PRIx32 ":%08" PRIx32 ":%08" PRIx32, b32(t), sc, b32(w[0]), b32(w[1]), b32(w[2]));
        }
        if (sk_grid_new(dens, 2, 2, 2, 1.0f, 3.0f, &g) != SK_OK) return 1;
        memset(&a, 0, sizeof a);
        a.medium.grid = &g;
        a.o = o, a.d = d, a.t_max = 3.0f, a.rng = &r;
        printf("\ndelta_track f32");
        for (i = 0; i < K; i++) {
            if (sk_delta_track(&a, &res) != SK_OK) return 1;
            printf(" %08" PRIx32 ":%" PRIu32, b32(res.t), (uint32_t)res.event);
        }
        printf("\nratio_track f32");
        for (i = 0; i < K; i++) {
            if (sk_ratio_track(&a, &res) != SK_OK) return 1;
            printf(" %08" PRIx32, b32(res.tr));
        }
        printf("\n");
    }
    return 0;
}
