/* The bad-input matrix: every function of include/scatterkit.h, called with
 * NULL in each pointer argument, NaN, +-inf, -0, a subnormal and +-max in each
 * float argument, out-of-range enum values, and n = 0 and n = SIZE_MAX, and
 * checked against the documented status or NaN. tests/c_abi/matrix.rs fails if a
 * header function does not appear here. Exits with the number of failures. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scatterkit.h"

#define CHECK_CASE i
#include "check.h"

/* The special values each float argument is tried with. */
static const float FS[] = {NAN, INFINITY, -INFINITY, -0.0f, 1e-40f, FLT_MAX, -FLT_MAX};
static const double DS[] = {NAN, INFINITY, -INFINITY, -0.0, 1e-310, DBL_MAX, -DBL_MAX};
enum { NS = 7 };
/* Which of them are "bad" for a parameter that must be finite. */
static int bad(double x) { return isnan(x) || isinf(x); }

static uint64_t counter(void *state) {
    uint64_t *s = (uint64_t *)state;
    return *s += 0x9e3779b97f4a7c15ULL;
}
/* SplitMix64: the counter mixed, for Monte Carlo that needs independent
 * draws. */
static uint64_t splitmix(void *state) {
    uint64_t z = counter(state);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static int in_unit(double x) { return x >= -1.0 && x <= 1.0; }
static int vec_nan3(sk_vec3 v) { return isnan(v.x) && isnan(v.y) && isnan(v.z); }
static int vec_nan3d(sk_vec3_f64 v) { return isnan(v.x) && isnan(v.y) && isnan(v.z); }
static int vec_unit(sk_vec3 v) { return fabs(sqrt((double)v.x * v.x + (double)v.y * v.y + (double)v.z * v.z) - 1.0) < 1e-5; }
static int vec_unitd(sk_vec3_f64 v) { return fabs(sqrt(v.x * v.x + v.y * v.y + v.z * v.z) - 1.0) < 1e-12; }

static void cube_roots_and_version(void) {
    int i;
    for (i = 0; i < NS; i++) {
        float f = FS[i], y = sk_cbrt(f), z = sk_cbrt_fast(f);
        double d = DS[i], w = sk_cbrt_f64(d), v = sk_cbrt_fast_f64(d);
        CHECK(isnan(f) ? isnan(y) && isnan(z) : isinf(f) || f == 0.0f ? y == f && z == f : isfinite(y) && isfinite(z));
        CHECK(isnan(d) ? isnan(w) && isnan(v) : isinf(d) || d == 0.0 ? w == d && v == d : isfinite(w) && isfinite(v));
        CHECK(signbit(y) == signbit(f) || isnan(f));
    }
    i = 0;
    CHECK(sk_version() != NULL && strlen(sk_version()) >= 5);
    /* Every status has its own string; any other value a fallback. */
    {
        const sk_status all[] = {SK_OK, SK_ERR_NULL, SK_ERR_DOMAIN, SK_ERR_SIZE, SK_ERR_METHOD, SK_ERR_BUDGET, SK_ERR_OVERLAP};
        const char *unknown = sk_status_string(7);
        int j;
        CHECK(unknown != NULL && strcmp(unknown, "unknown status") == 0);
        CHECK(strcmp(sk_status_string(UINT32_MAX), "unknown status") == 0);
        for (i = 0; i < (int)(sizeof all / sizeof all[0]); i++) {
            const char *s = sk_status_string(all[i]);
            CHECK(s != NULL && strlen(s) > 1 && strcmp(s, unknown) != 0);
            for (j = 0; j < i; j++) {
                CHECK(strcmp(s, sk_status_string(all[j])) != 0);
            }
        }
        CHECK(strcmp(sk_status_string(SK_OK), "ok") == 0);
    }
}

static void basis(void) {
    int i;
    sk_vec3 b1 = {7, 7, 7}, b2 = {7, 7, 7};
    sk_vec3_f64 c1 = {7, 7, 7}, c2 = {7, 7, 7};
    const sk_vec3 z = {0, 0, 1};
    const sk_vec3_f64 zd = {0, 0, 1};
    sk_onb(z, NULL, &b2);
    sk_onb(z, &b1, NULL);
    sk_onb_f64(zd, NULL, &c2);
    sk_onb_f64(zd, &c1, NULL);
    i = 0;
    CHECK(b1.x == 7 && b2.x == 7 && c1.x == 7 && c2.x == 7);
    for (i = 0; i < NS; i++) { /* any input: no crash, NaN in gives NaN out */
        sk_vec3 n = {FS[i], 0, 1};
        sk_vec3_f64 m = {DS[i], 0, 1};
        sk_onb(n, &b1, &b2);
        sk_onb_f64(m, &c1, &c2);
        CHECK(!isnan(FS[i]) || isnan(b1.x));
        CHECK(!isnan(DS[i]) || isnan(c1.x));
    }
}

/* Every phase constructor with each special in each float argument. */
static void phase_constructors(void) {
    int i;
    sk_phase p;
    sk_phase_f64 q;
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double d = DS[i];
        int g_ok = f > -1.0f && f < 1.0f, gd_ok = d > -1.0 && d < 1.0;
        int a_ok = f >= 0.0f && isfinite(f), ad_ok = d >= 0.0 && isfinite(d);
        CHECK(sk_phase_new_hg(f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_hg_f64(d, &q) == (gd_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_cornette_shanks(f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_cornette_shanks_f64(d, &q) == (gd_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_draine(f, 1.0f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_draine(0.3f, f, &p) == (a_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_draine_f64(d, 1.0, &q) == (gd_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_draine_f64(0.3, d, &q) == (ad_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog(f, 0.5f, 1.0f, 0.5f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog(0.5f, f, 1.0f, 0.5f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog(0.5f, 0.5f, f, 0.5f, &p) == (a_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog(0.5f, 0.5f, 1.0f, f, &p) == (f >= 0.0f && f <= 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog_f64(d, 0.5, 1.0, 0.5, &q) == (gd_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog_f64(0.5, 0.5, 1.0, d, &q) == (d >= 0.0 && d <= 1.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_two_lobe_hg(f, 0.5f, 0.5f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_two_lobe_hg(0.5f, f, 0.5f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_two_lobe_hg(0.5f, -0.5f, f, &p) == (f >= 0.0f && f <= 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_two_lobe_hg_f64(d, 0.5, 0.5, &q) == (gd_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_two_lobe_hg_f64(0.5, d, 0.5, &q) == (gd_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_two_lobe_hg_f64(0.5, -0.5, d, &q) == (d >= 0.0 && d <= 1.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand(f, 4.0f, &p) == (f > 1.0f && f <= 1.8f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand(1.1f, f, &p) == (f > 3.0f && f < 5.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand_f64(d, 4.0, &q) == (d > 1.0 && d <= 1.8 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand_f64(1.1, d, &q) == (d > 3.0 && d < 5.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand_backscatter(f, 1.1f, &p) == (f >= FLT_MIN && f < 0.5f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand_backscatter(0.02f, f, &p) == (f > 1.0f && f <= 1.8f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand_backscatter_f64(d, 1.1, &q) == (d >= DBL_MIN && d < 0.5 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fournier_forand_backscatter_f64(0.02, d, &q) == (d > 1.0 && d <= 1.8 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_gegenbauer(f, 0.5f, &p) == (f > -0.5f && f <= 1000.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_gegenbauer(0.5f, f, &p) == (g_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_gegenbauer_f64(d, 0.5, &q) == (d > -0.5 && d <= 1000.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_gegenbauer_f64(0.5, d, &q) == (gd_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog_diameter(f, &p) == (f > 0.0f && f <= 50.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_fog_diameter_f64(d, &q) == (d > 0.0 && d <= 50.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_rayleigh_depolarized(f, &p) == (f >= 0.0f && f < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_rayleigh_depolarized_f64(d, &q) == (d >= 0.0 && d < 1.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_particle(f, 0.1f, &p) == (f > 0.0f && f <= 50.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_particle(2.0f, f, &p) == (f > 0.0f && f < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_particle_f64(d, 0.1, &q) == (d > 0.0 && d <= 50.0 ? SK_OK : SK_ERR_DOMAIN));
    }
    i = 0;
    CHECK(sk_phase_new_isotropic(NULL) == SK_ERR_NULL && sk_phase_new_isotropic_f64(NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_rayleigh(NULL) == SK_ERR_NULL && sk_phase_new_rayleigh_f64(NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_hg(0.1f, NULL) == SK_ERR_NULL && sk_phase_new_hg_f64(0.1, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_draine(0.1f, 1, NULL) == SK_ERR_NULL && sk_phase_new_draine_f64(0.1, 1, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_cornette_shanks(0.1f, NULL) == SK_ERR_NULL && sk_phase_new_cornette_shanks_f64(0.1, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_fog(0.1f, 0.1f, 1, 0.5f, NULL) == SK_ERR_NULL && sk_phase_new_fog_f64(0.1, 0.1, 1, 0.5, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_fog_diameter(2, NULL) == SK_ERR_NULL && sk_phase_new_fog_diameter_f64(2, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_fournier_forand(1.1f, 4.0f, NULL) == SK_ERR_NULL && sk_phase_new_fournier_forand_f64(1.1, 4.0, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_fournier_forand_backscatter(0.02f, 1.1f, NULL) == SK_ERR_NULL &&
          sk_phase_new_fournier_forand_backscatter_f64(0.02, 1.1, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_fournier_forand_backscatter_f64(0.0183, 1.1, &q) == SK_OK && fabs(sk_phase_cdf_f64(&q, 0.0) - 0.0183) < 1e-12);
    CHECK(sk_phase_new_gegenbauer(0.5f, 0.3f, NULL) == SK_ERR_NULL && sk_phase_new_gegenbauer_f64(0.5, 0.3, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_gegenbauer_f64(0.5, 0.3, &q) == SK_OK && fabs(sk_phase_mean_cosine_f64(&q) - 0.3) < 1e-10);
    CHECK(sk_phase_new_two_lobe_hg(0.8f, -0.3f, 0.9f, NULL) == SK_ERR_NULL && sk_phase_new_two_lobe_hg_f64(0.8, -0.3, 0.9, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_two_lobe_hg_f64(0.8, -0.3, 0.9, &q) == SK_OK && fabs(sk_phase_mean_cosine_f64(&q) - 0.69) < 1e-12);
    CHECK(sk_phase_new_rayleigh_depolarized(0.1f, NULL) == SK_ERR_NULL && sk_phase_new_rayleigh_depolarized_f64(0.1, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle(2, 0.1f, NULL) == SK_ERR_NULL && sk_phase_new_particle_f64(2, 0.1, NULL) == SK_ERR_NULL);
}

/* Queries of every phase kind with each special argument. */
/* The inline sampler's constants: NULL pointers, an unconstructed phase
   (out untouched), an HG phase (constants set) and another model (constants
   zero: the inline function calls the library). */
static void phase_cos_inline(void) {
    int i = 0;
    sk_phase p, zero;
    sk_phase_cos_inline c;
    memset(&zero, 0, sizeof zero);
    sk_phase_new_hg(0.3f, &p);
    CHECK(sk_phase_cos_inline_new(NULL, &c) == SK_ERR_NULL);
    CHECK(sk_phase_cos_inline_new(&p, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_cos_inline_new(NULL, NULL) == SK_ERR_NULL);
    c.reserved = 99;
    CHECK(sk_phase_cos_inline_new(&zero, &c) == SK_ERR_DOMAIN && c.reserved == 99);
    CHECK(sk_phase_cos_inline_new(&p, &c) == SK_OK && c.reserved == 0 && c.kab[2] != 0.0 && c.mirror == 0);
    sk_phase_new_hg(-0.3f, &p);
    CHECK(sk_phase_cos_inline_new(&p, &c) == SK_OK && c.kab[2] != 0.0 && c.mirror == 1);
    sk_phase_new_rayleigh(&p);
    CHECK(sk_phase_cos_inline_new(&p, &c) == SK_OK && c.kab[0] == 0.0 && c.kab[1] == 0.0 && c.kab[2] == 0.0);
}

/* What a phase holds: the model and its parameters, as built. */
static void phase_params(void) {
    int i = 0;
    sk_phase p, zero;
    sk_phase_f64 q;
    sk_phase_params pp;
    sk_phase_params_f64 qp;
    memset(&zero, 0, sizeof zero);
    CHECK(sk_phase_get_params(NULL, &pp) == SK_ERR_NULL);
    sk_phase_new_hg(0.3f, &p);
    CHECK(sk_phase_get_params(&p, NULL) == SK_ERR_NULL);
    pp.model = 99;
    CHECK(sk_phase_get_params(&zero, &pp) == SK_ERR_DOMAIN && pp.model == 99);
    CHECK(sk_phase_get_params(&p, &pp) == SK_OK && pp.model == SK_PHASE_HG && pp.count == 1 && pp.params[0] == 0.3f &&
          pp.params[1] == 0.0f);
    sk_phase_new_isotropic(&p);
    CHECK(sk_phase_get_params(&p, &pp) == SK_OK && pp.model == SK_PHASE_ISOTROPIC && pp.count == 0);
    sk_phase_new_rayleigh(&p);
    CHECK(sk_phase_get_params(&p, &pp) == SK_OK && pp.model == SK_PHASE_RAYLEIGH && pp.count == 0);
    sk_phase_new_rayleigh_depolarized(0.03f, &p);
    CHECK(sk_phase_get_params(&p, &pp) == SK_OK && pp.model == SK_PHASE_RAYLEIGH_DEPOLARIZED && pp.params[0] == 0.03f);
    sk_phase_new_draine(0.5f, 2.0f, &p);
    CHECK(sk_phase_get_params(&p, &pp) == SK_OK && pp.model == SK_PHASE_DRAINE && pp.count == 2 && pp.params[0] == 0.5f &&
          pp.params[1] == 2.0f);
    sk_phase_new_fog(0.9f, 0.2f, 10.0f, 0.3f, &p);
    CHECK(sk_phase_get_params(&p, &pp) == SK_OK && pp.model == SK_PHASE_FOG && pp.count == 4 && pp.params[0] == 0.9f &&
          pp.params[1] == 0.2f && pp.params[2] == 10.0f && pp.params[3] == 0.3f);
    sk_phase_new_fournier_forand_f64(1.1, 4.0, &q);
    CHECK(sk_phase_get_params_f64(&q, &qp) == SK_OK && qp.model == SK_PHASE_FOURNIER_FORAND && qp.count == 3 &&
          qp.params[0] == 1.1 && qp.params[1] == -0.5 && fabs(qp.params[2] - sk_phase_cdf_f64(&q, 0.0)) < 1e-12);
    sk_phase_new_gegenbauer(-0.25f, 0.7f, &p);
    CHECK(sk_phase_get_params(&p, &pp) == SK_OK && pp.model == SK_PHASE_GEGENBAUER && pp.count == 2 && pp.params[0] == -0.25f &&
          pp.params[1] == 0.7f);
    sk_phase_new_draine_f64(-0.25, 1000.0, &q);
    CHECK(sk_phase_get_params_f64(&q, &qp) == SK_OK && qp.model == SK_PHASE_DRAINE && qp.params[0] == -0.25 &&
          qp.params[1] == 1000.0);
    CHECK(sk_phase_get_params_f64(&q, NULL) == SK_ERR_NULL && sk_phase_get_params_f64(NULL, &qp) == SK_ERR_NULL);
}

static void phase_queries(void) {
    int i, k;
    sk_phase ps[6], zero;
    sk_phase_f64 qs[6], zero64;
    float u[3] = {0.1f, 0.5f, 0.9f}, out[3];
    double ud[3] = {0.1, 0.5, 0.9}, outd[3];
    memset(&zero, 0, sizeof zero);
    memset(&zero64, 0, sizeof zero64);
    sk_phase_new_isotropic(&ps[0]);
    sk_phase_new_rayleigh(&ps[1]);
    sk_phase_new_hg(0.9f, &ps[2]);
    sk_phase_new_draine(0.3f, 250.0f, &ps[3]);
    sk_phase_new_fog_diameter(2.0f, &ps[4]);
    sk_phase_new_rayleigh_depolarized(0.3f, &ps[5]);
    sk_phase_new_isotropic_f64(&qs[0]);
    sk_phase_new_rayleigh_f64(&qs[1]);
    sk_phase_new_hg_f64(0.9, &qs[2]);
    sk_phase_new_draine_f64(0.3, 250.0, &qs[3]);
    sk_phase_new_fog_diameter_f64(2.0, &qs[4]);
    sk_phase_new_rayleigh_depolarized_f64(0.3, &qs[5]);
    for (k = 0; k < 6; k++) {
        for (i = 0; i < NS; i++) {
            float f = FS[i];
            double d = DS[i];
            const sk_vec3 w = {0, 0, 1};
            const sk_vec3_f64 wd = {0, 0, 1};
            float pdf;
            double pdfd;
            /* Scalar u: clamped; NaN gives NaN. */
            float c = sk_phase_sample_cos(&ps[k], f), cl = sk_phase_sample_cos_by_lobe(&ps[k], f);
            double cd = sk_phase_sample_cos_f64(&qs[k], d), cld = sk_phase_sample_cos_by_lobe_f64(&qs[k], d);
            CHECK(isnan(f) ? isnan(c) && isnan(cl) : in_unit(c) && in_unit(cl));
            CHECK(isnan(d) ? isnan(cd) && isnan(cld) : in_unit(cd) && in_unit(cld));
            /* cdf: clamped argument, result in [0, 1]; NaN gives NaN. */
            c = sk_phase_cdf(&ps[k], f);
            cd = sk_phase_cdf_f64(&qs[k], d);
            CHECK(isnan(f) ? isnan(c) : c >= 0.0f && c <= 1.0f);
            CHECK(isnan(d) ? isnan(cd) : cd >= 0.0 && cd <= 1.0);
            /* pdf: NaN gives NaN; otherwise no NaN inside [-1, 1]. */
            c = sk_phase_pdf(&ps[k], f);
            cd = sk_phase_pdf_f64(&qs[k], d);
            CHECK(!isnan(f) || isnan(c));
            CHECK(!isnan(d) || isnan(cd));
            CHECK(!in_unit(f) || (c >= 0.0f && !isnan(c)));
            /* sample_dir: NaN u gives a NaN direction, else a unit one. */
            {
                sk_vec3 dir = sk_phase_sample_dir(&ps[k], w, f, 0.3f, &pdf);
                sk_vec3_f64 dird = sk_phase_sample_dir_f64(&qs[k], wd, d, 0.3, &pdfd);
                CHECK(isnan(f) ? isnan(dir.z) : vec_unit(dir) && pdf >= 0.0f);
                CHECK(isnan(d) ? isnan(dird.z) : vec_unitd(dird) && pdfd >= 0.0);
                dir = sk_phase_sample_dir(&ps[k], w, 0.3f, f, NULL);
                CHECK(isnan(f) ? isnan(dir.x) : vec_unit(dir));
            }
            /* Batches reject any u that is NaN or outside [0, 1] and write nothing. */
            u[1] = f;
            ud[1] = d;
            out[0] = outd[0] = 7.0f;
            CHECK(sk_phase_sample_cos_n(&ps[k], u, out, 3) == (f >= 0.0f && f <= 1.0f ? SK_OK : SK_ERR_DOMAIN));
            CHECK(sk_phase_sample_cos_n_f64(&qs[k], ud, outd, 3) == (d >= 0.0 && d <= 1.0 ? SK_OK : SK_ERR_DOMAIN));
            CHECK((f >= 0.0f && f <= 1.0f) || out[0] == 7.0f);
            {
                /* The portable tier: isotropic, HG and Rayleigh only. */
                sk_status r = sk_phase_sample_cos_n_portable(&ps[k], u, out, 3);
                CHECK(r == SK_ERR_METHOD || r == (f >= 0.0f && f <= 1.0f ? SK_OK : SK_ERR_DOMAIN));
            }
        }
        i = 0;
        u[1] = 0.5f;
        ud[1] = 0.5;
        CHECK(sk_phase_sample_cos_n(&ps[k], NULL, out, 3) == SK_ERR_NULL);
        CHECK(sk_phase_sample_cos_n(&ps[k], u, NULL, 3) == SK_ERR_NULL);
        CHECK(sk_phase_sample_cos_n(&ps[k], NULL, NULL, 0) == SK_OK);
        CHECK(sk_phase_sample_cos_n(&ps[k], u, out, SIZE_MAX) == SK_ERR_SIZE);
        {
            sk_status r = sk_phase_sample_cos_n_portable(&ps[k], u, out, 3);
            CHECK(r == SK_OK || r == SK_ERR_METHOD);
            if (r == SK_OK) {
                CHECK(sk_phase_sample_cos_n_portable(&ps[k], NULL, out, 3) == SK_ERR_NULL);
                CHECK(sk_phase_sample_cos_n_portable(&ps[k], u, NULL, 3) == SK_ERR_NULL);
                CHECK(sk_phase_sample_cos_n_portable(&ps[k], NULL, NULL, 0) == SK_OK);
                CHECK(sk_phase_sample_cos_n_portable(&ps[k], u, out, SIZE_MAX) == SK_ERR_SIZE);
                CHECK(sk_phase_sample_cos_n_portable(&ps[k], u, u + 1, 2) == SK_ERR_OVERLAP);
            }
        }
        CHECK(sk_phase_sample_cos_n_f64(&qs[k], NULL, outd, 3) == SK_ERR_NULL);
        CHECK(sk_phase_sample_cos_n_f64(&qs[k], ud, outd, SIZE_MAX) == SK_ERR_SIZE);
        CHECK(sk_phase_sample_cos_n_f64(&qs[k], ud, outd, 0) == SK_OK);
        CHECK(!isnan(sk_phase_mean_cosine(&ps[k])) && !isnan(sk_phase_mean_cosine_f64(&qs[k])));
    }
    i = 0;
    {
        const sk_vec3 w = {0, 0, 1};
        const sk_vec3_f64 wd = {0, 0, 1};
        const sk_phase *bad_p[2] = {NULL, &zero};
        const sk_phase_f64 *bad_q[2] = {NULL, &zero64};
        for (k = 0; k < 2; k++) {
            CHECK(isnan(sk_phase_pdf(bad_p[k], 0)) && isnan(sk_phase_pdf_f64(bad_q[k], 0)));
            CHECK(isnan(sk_phase_cdf(bad_p[k], 0)) && isnan(sk_phase_cdf_f64(bad_q[k], 0)));
            CHECK(isnan(sk_phase_mean_cosine(bad_p[k])) && isnan(sk_phase_mean_cosine_f64(bad_q[k])));
            CHECK(isnan(sk_phase_sample_cos(bad_p[k], 0.5f)) && isnan(sk_phase_sample_cos_f64(bad_q[k], 0.5)));
            CHECK(isnan(sk_phase_sample_cos_by_lobe(bad_p[k], 0.5f)) && isnan(sk_phase_sample_cos_by_lobe_f64(bad_q[k], 0.5)));
            CHECK(vec_nan3(sk_phase_sample_dir(bad_p[k], w, 0.5f, 0.5f, NULL)));
            CHECK(vec_nan3d(sk_phase_sample_dir_f64(bad_q[k], wd, 0.5, 0.5, NULL)));
            CHECK(sk_phase_sample_cos_n(bad_p[k], u, out, 3) == (k ? SK_ERR_DOMAIN : SK_ERR_NULL));
            CHECK(sk_phase_sample_cos_n_portable(bad_p[k], u, out, 3) == (k ? SK_ERR_DOMAIN : SK_ERR_NULL));
            CHECK(sk_phase_sample_cos_n_f64(bad_q[k], ud, outd, 3) == (k ? SK_ERR_DOMAIN : SK_ERR_NULL));
        }
    }
}

/* Direction batches (structure of arrays): special uniforms, NULL arrays,
 * n = 0 and SIZE_MAX, overlaps, bad phases and methods. */
static void direction_batches(void) {
    int i, k;
    sk_phase p, zero;
    sk_phase_f64 q, zero64;
    float wx[4] = {0, 0, 1, 0}, wy[4] = {0, 1, 0, 0}, wz[4] = {1, 0, 0, -1};
    float u1[4] = {0.1f, 0.5f, 0.9f, 0.3f}, u2[4] = {0.2f, 0.4f, 0.6f, 0.8f};
    float ox[4], oy[4], oz[4], pdf[4], big[8];
    double dx[4] = {0, 0, 1, 0}, dy[4] = {0, 1, 0, 0}, dz[4] = {1, 0, 0, -1};
    double v1[4] = {0.1, 0.5, 0.9, 0.3}, v2[4] = {0.2, 0.4, 0.6, 0.8};
    double px[4], py[4], pz[4], pdfd[4];
    uint64_t st = 1;
    sk_rng rng = {&st, counter}, no_fn = {&st, NULL};
    memset(&zero, 0, sizeof zero);
    memset(&zero64, 0, sizeof zero64);
    sk_phase_new_hg(0.5f, &p);
    sk_phase_new_hg_f64(0.5, &q);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double d = DS[i];
        int ok = f >= 0.0f && f <= 1.0f, okd = d >= 0.0 && d <= 1.0;
        for (k = 0; k < 2; k++) {
            float *uf = k ? u2 : u1;
            double *ud = k ? v2 : v1;
            float keep = uf[2];
            double keepd = ud[2];
            uf[2] = f;
            ud[2] = d;
            ox[0] = 7.0f;
            px[0] = 7.0;
            CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == (ok ? SK_OK : SK_ERR_DOMAIN));
            CHECK(ok || ox[0] == 7.0f);
            CHECK(sk_phase_sample_dir_n_portable(&p, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == (ok ? SK_OK : SK_ERR_DOMAIN));
            CHECK(ok || ox[0] == 7.0f);
            CHECK(sk_phase_sample_dir_n_f64(&q, dx, dy, dz, v1, v2, px, py, pz, pdfd, 4) == (okd ? SK_OK : SK_ERR_DOMAIN));
            CHECK(okd || px[0] == 7.0);
            uf[2] = keep;
            ud[2] = keepd;
        }
    }
    i = 0;
    /* NULL arrays (pdf_out may be NULL), sizes, bad phases. */
    CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, NULL, 4) == SK_OK);
    CHECK(sk_phase_sample_dir_n(NULL, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_n(&zero, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_ERR_DOMAIN);
    CHECK(sk_phase_sample_dir_n_f64(&zero64, dx, dy, dz, v1, v2, px, py, pz, pdfd, 4) == SK_ERR_DOMAIN);
    CHECK(sk_phase_sample_dir_n(&p, NULL, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, NULL, u2, ox, oy, oz, pdf, 4) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, u1, u2, ox, NULL, oz, pdf, 4) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_n_f64(&q, dx, dy, dz, v1, NULL, px, py, pz, pdfd, 4) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_n(&p, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0) == SK_OK);
    CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, pdf, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(sk_phase_sample_dir_n_f64(&q, dx, dy, dz, v1, v2, px, py, pz, pdfd, SIZE_MAX) == SK_ERR_SIZE);
    /* With cos theta: the same checks, and cos_out never NULL. */
    {
        float cosv[4];
        double cosd[4];
        CHECK(sk_phase_sample_dir_cos_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, 4) == SK_OK);
        CHECK(sk_phase_sample_dir_cos_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, cosv, NULL, 4) == SK_OK);
        CHECK(sk_phase_sample_dir_cos_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, NULL, pdf, 4) == SK_ERR_NULL);
        CHECK(sk_phase_sample_dir_cos_n(NULL, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, 4) == SK_ERR_NULL);
        CHECK(sk_phase_sample_dir_cos_n(&zero, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, 4) == SK_ERR_DOMAIN);
        CHECK(sk_phase_sample_dir_cos_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, ox, pdf, 4) == SK_ERR_OVERLAP);
        CHECK(sk_phase_sample_dir_cos_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, SIZE_MAX) == SK_ERR_SIZE);
        CHECK(sk_phase_sample_dir_cos_n(&p, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0) == SK_OK);
        CHECK(sk_phase_sample_dir_cos_n_f64(&q, dx, dy, dz, v1, v2, px, py, pz, cosd, pdfd, 4) == SK_OK);
        CHECK(sk_phase_sample_dir_cos_n_f64(&q, dx, dy, dz, v1, v2, px, py, pz, NULL, pdfd, 4) == SK_ERR_NULL);
        CHECK(sk_phase_sample_dir_cos_n_f64(&zero64, dx, dy, dz, v1, v2, px, py, pz, cosd, pdfd, 4) == SK_ERR_DOMAIN);
        CHECK(sk_phase_sample_dir_cos_n_portable(&p, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, 4) == SK_OK);
        CHECK(sk_phase_sample_dir_cos_n_portable(&p, wx, wy, wz, u1, u2, ox, oy, oz, NULL, pdf, 4) == SK_ERR_NULL);
        CHECK(sk_phase_sample_dir_cos_n_portable(&zero, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, 4) == SK_ERR_DOMAIN);
        u1[1] = NAN;
        CHECK(sk_phase_sample_dir_cos_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, 4) == SK_ERR_DOMAIN);
        CHECK(sk_phase_sample_dir_cos_n_portable(&p, wx, wy, wz, u1, u2, ox, oy, oz, cosv, pdf, 4) == SK_ERR_DOMAIN);
        u1[1] = 0.5f;
    }
    /* The portable tier's batch: the same checks; isotropic, HG and
       Rayleigh only. */
    CHECK(sk_phase_sample_dir_n_portable(&p, wx, wy, wz, u1, u2, ox, oy, oz, NULL, 4) == SK_OK);
    CHECK(sk_phase_sample_dir_n_portable(NULL, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_n_portable(&zero, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_ERR_DOMAIN);
    CHECK(sk_phase_sample_dir_n_portable(&p, wx, wy, wz, NULL, u2, ox, oy, oz, pdf, 4) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_n_portable(&p, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0) == SK_OK);
    CHECK(sk_phase_sample_dir_n_portable(&p, wx, wy, wz, u1, u2, ox, oy, oz, pdf, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(sk_phase_sample_dir_n_portable(&p, wx, wy, wz, u1, u2, ox, ox, oz, pdf, 4) == SK_ERR_OVERLAP);
    {
        sk_phase iso, ray, fog;
        sk_phase_new_isotropic(&iso);
        sk_phase_new_rayleigh(&ray);
        sk_phase_new_fog_diameter(2.0f, &fog);
        CHECK(sk_phase_sample_dir_n_portable(&iso, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_OK);
        CHECK(sk_phase_sample_dir_n_portable(&ray, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_OK);
        CHECK(sk_phase_sample_dir_n_portable(&fog, wx, wy, wz, u1, u2, ox, oy, oz, pdf, 4) == SK_ERR_METHOD);
    }
    /* In place is allowed; partial overlaps and shared outputs are not. */
    memcpy(big, wx, sizeof wx);
    CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, u1, u2, wx, wy, wz, pdf, 4) == SK_OK);
    CHECK(sk_phase_sample_dir_n(&p, big, wy, wz, u1, u2, big + 1, oy, oz, pdf, 4) == SK_ERR_OVERLAP);
    CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, u1, u2, ox, ox, oz, pdf, 4) == SK_ERR_OVERLAP);
    CHECK(sk_phase_sample_dir_n(&p, wx, wy, wz, u1, u2, ox, oy, oz, ox, 4) == SK_ERR_OVERLAP);
    CHECK(sk_phase_sample_dir_n_f64(&q, dx, dy, dz, v1, v2, px, py, px, pdfd, 4) == SK_ERR_OVERLAP);
    /* Rayleigh batches with the caller's generator. */
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, wx, wy, wz, &rng, ox, oy, oz, 4) == SK_OK);
    CHECK(sk_rayleigh_sample_dir_n_f64(SK_RAYLEIGH_SIMPLIFIED, dx, dy, dz, &rng, px, py, pz, 4) == SK_OK);
    CHECK(sk_rayleigh_sample_dir_n(8, wx, wy, wz, &rng, ox, oy, oz, 4) == SK_ERR_METHOD);
    CHECK(sk_rayleigh_sample_dir_n_f64(UINT32_MAX, dx, dy, dz, &rng, px, py, pz, 4) == SK_ERR_METHOD);
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, wx, wy, wz, NULL, ox, oy, oz, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, wx, wy, wz, &no_fn, ox, oy, oz, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, wx, NULL, wz, &rng, ox, oy, oz, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir_n_f64(SK_RAYLEIGH_TABLE, dx, dy, dz, &rng, px, py, NULL, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, NULL, NULL, NULL, &rng, NULL, NULL, NULL, 0) == SK_OK);
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, wx, wy, wz, &rng, ox, oy, oz, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(sk_rayleigh_sample_dir_n_f64(SK_RAYLEIGH_TABLE, dx, dy, dz, &rng, px, py, pz, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, wx, wy, wz, &rng, wx, wy, wz, 4) == SK_OK);
    CHECK(sk_rayleigh_sample_dir_n(SK_RAYLEIGH_TABLE, big, wy, wz, &rng, big + 2, oy, oz, 4) == SK_ERR_OVERLAP);
    CHECK(sk_rayleigh_sample_dir_n_f64(SK_RAYLEIGH_TABLE, dx, dy, dz, &rng, px, px, pz, 4) == SK_ERR_OVERLAP);
}

static void rayleigh_functions(void) {
    int i;
    uint64_t st = 1;
    sk_rng rng = {&st, counter}, no_fn = {&st, NULL};
    const uint32_t bad_methods[3] = {8, 1000, UINT32_MAX};
    sk_vec3 d, w = {0, 0, 1};
    sk_vec3_f64 dd, wd = {0, 0, 1};
    float c[4];
    double cd[4];
    for (i = 0; i < 3; i++) {
        uint32_t m = bad_methods[i];
        CHECK(sk_rayleigh_sample_dir(m, w, &rng, &d) == SK_ERR_METHOD);
        CHECK(sk_rayleigh_sample_dir_f64(m, wd, &rng, &dd) == SK_ERR_METHOD);
        CHECK(sk_rayleigh_sample_cos_n(m, &rng, c, 4) == SK_ERR_METHOD);
        CHECK(sk_rayleigh_sample_cos_n_f64(m, &rng, cd, 4) == SK_ERR_METHOD);
    }
    i = 0;
    CHECK(sk_rayleigh_sample_dir(SK_RAYLEIGH_TABLE, w, NULL, &d) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir(SK_RAYLEIGH_TABLE, w, &no_fn, &d) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir(SK_RAYLEIGH_TABLE, w, &rng, NULL) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir_f64(SK_RAYLEIGH_TABLE, wd, &rng, NULL) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_TABLE, &rng, NULL, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_TABLE, &rng, NULL, 0) == SK_OK);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_TABLE, &rng, c, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(sk_rayleigh_sample_cos_n_f64(SK_RAYLEIGH_TABLE, &no_fn, cd, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_cos_n_f64(SK_RAYLEIGH_TABLE, &rng, cd, SIZE_MAX) == SK_ERR_SIZE);
    for (i = 0; i < NS; i++) {
        double x = DS[i];
        int ok = x > 0.0 && isfinite(x);
        sk_vec3 wi = {FS[i], 0, 1};
        double cs = sk_rayleigh_cross_section_f64(x, 1e-9, 1.5);
        CHECK(ok ? cs >= 0.0 : isnan(cs));
        CHECK(ok ? !isnan(sk_rayleigh_cross_section_f64(500e-9, x, 1.5)) : isnan(sk_rayleigh_cross_section_f64(500e-9, x, 1.5)));
        CHECK(ok ? !isnan(sk_rayleigh_cross_section_f64(500e-9, 1e-9, x)) : isnan(sk_rayleigh_cross_section_f64(500e-9, 1e-9, x)));
        CHECK((x >= 0.0 && isfinite(x)) ? !isnan(sk_rayleigh_scattering_coeff_f64(x, 500e-9, 1e-9, 1.5))
                                        : isnan(sk_rayleigh_scattering_coeff_f64(x, 500e-9, 1e-9, 1.5)));
        /* A non-unit or NaN direction: no crash, status OK (not checked on the hot path). */
        CHECK(sk_rayleigh_sample_dir(SK_RAYLEIGH_DIRECT, wi, &rng, &d) == SK_OK);
    }
}

static void tables(void) {
    int i;
    float buf[2 * 33], cosines[3] = {-1, 0, 1}, pdf[3] = {1, 1, 1};
    double bufd[2 * 33], cosd[3] = {-1, 0, 1}, pdfd[3] = {1, 1, 1};
    sk_table t, bogus;
    sk_table_f64 td;
    sk_phase p;
    sk_phase_f64 q;
    sk_phase_new_hg(0.5f, &p);
    sk_phase_new_hg_f64(0.5, &q);
    i = 0;
    CHECK(sk_table_len(SK_TABLE_RAYLEIGH_CDF, 0) == 0 && sk_table_len(SK_TABLE_INVERSE, SIZE_MAX) == 0);
    CHECK(sk_table_len(3, 8) == 0 && sk_table_len(UINT32_MAX, 8) == 0 && sk_table_len(SK_TABLE_MEASURED, 8) == 18);
    CHECK(sk_table_new_rayleigh_cdf(buf, 33, 32, NULL) == SK_ERR_NULL && sk_table_new_rayleigh_cdf(NULL, 33, 32, &t) == SK_ERR_NULL);
    CHECK(sk_table_new_rayleigh_cdf(buf, 33, 0, &t) == SK_ERR_SIZE && sk_table_new_rayleigh_cdf(buf, 33, SIZE_MAX, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_rayleigh_cdf(buf, SIZE_MAX, 32, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_rayleigh_cdf_f64(bufd, 32, 32, &td) == SK_ERR_SIZE && sk_table_new_rayleigh_cdf_f64(NULL, 33, 32, &td) == SK_ERR_NULL);
    CHECK(sk_table_new_inverse(&p, buf, 66, 32, NULL) == SK_ERR_NULL && sk_table_new_inverse(NULL, buf, 66, 32, &t) == SK_ERR_NULL);
    CHECK(sk_table_new_inverse(&p, buf, 66, 0, &t) == SK_ERR_SIZE && sk_table_new_inverse(&p, buf, SIZE_MAX, 32, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_inverse_f64(&q, bufd, 65, 32, &td) == SK_ERR_SIZE && sk_table_new_inverse_f64(&q, NULL, 66, 32, &td) == SK_ERR_NULL);
    CHECK(sk_table_new_measured(cosines, pdf, 3, buf, 66, 32, NULL) == SK_ERR_NULL);
    CHECK(sk_table_new_measured(cosines, pdf, 0, buf, 66, 32, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_measured(cosines, pdf, SIZE_MAX, buf, 66, 32, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_measured_f64(cosd, pdfd, 3, bufd, 66, 0, &td) == SK_ERR_SIZE);
    CHECK(sk_table_new_measured_f64(cosd, NULL, 3, bufd, 66, 32, &td) == SK_ERR_NULL);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double d = DS[i];
        cosines[1] = f;
        pdf[1] = 1;
        CHECK(sk_table_new_measured(cosines, pdf, 3, buf, 66, 32, &t) == (f > -1.0f && f < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        cosines[1] = 0;
        pdf[1] = f;
        CHECK(sk_table_new_measured(cosines, pdf, 3, buf, 66, 32, &t) == (f >= 0.0f && isfinite(f) ? SK_OK : SK_ERR_DOMAIN));
        pdfd[1] = d;
        CHECK(sk_table_new_measured_f64(cosd, pdfd, 3, bufd, 66, 32, &td) == (d >= 0.0 && isfinite(d) ? SK_OK : SK_ERR_DOMAIN));
        pdfd[1] = 1;
        /* Lookups: u clamped, NaN gives NaN. */
        sk_table_new_rayleigh_cdf(buf, 33, 32, &t);
        CHECK(isnan(f) ? isnan(sk_table_sample_cos(&t, f)) : in_unit(sk_table_sample_cos(&t, f)));
        sk_table_new_inverse_f64(&q, bufd, 66, 32, &td);
        CHECK(isnan(d) ? isnan(sk_table_sample_cos_f64(&td, d)) : in_unit(sk_table_sample_cos_f64(&td, d)));
        /* pdf: NaN for NaN, 0 outside [-1, 1], finite and >= 0 inside. */
        {
            float pf = sk_table_pdf(&t, f), pu;
            double pd = sk_table_pdf_f64(&td, d);
            sk_vec3 w = {0, 0, 1}, dir;
            sk_vec3_f64 wd = {0, 0, 1}, dird;
            double pdd;
            CHECK(isnan(f) ? isnan(pf) : (fabsf(f) > 1.0f ? pf == 0.0f : pf >= 0.0f && isfinite(pf)));
            CHECK(isnan(d) ? isnan(pd) : (fabs(d) > 1.0 ? pd == 0.0 : pd >= 0.0));
            /* sample_dir: u clamped (NaN gives NaN), the pdf the table's. */
            dir = sk_table_sample_dir(&t, w, f, 0.25f, &pu);
            CHECK(isnan(f) ? vec_nan3(dir) || isnan(dir.z) : fabsf(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z - 1.0f) < 1e-5f);
            CHECK(isnan(f) ? isnan(pu) : pu == sk_table_pdf(&t, sk_table_sample_cos(&t, f)));
            dird = sk_table_sample_dir_f64(&td, wd, 0.5, d, &pdd);
            CHECK(isnan(d) ? isnan(dird.x) || isnan(dird.y) : fabs(dird.x * dird.x + dird.y * dird.y + dird.z * dird.z - 1.0) < 1e-12);
        }
    }
    i = 0;
    CHECK(isnan(sk_table_sample_cos(NULL, 0.5f)) && isnan(sk_table_sample_cos_f64(NULL, 0.5)));
    bogus = t;
    bogus.kind = 77;
    CHECK(isnan(sk_table_sample_cos(&bogus, 0.5f)));
    bogus.kind = SK_TABLE_RAYLEIGH_CDF;
    bogus.n = SIZE_MAX;
    CHECK(isnan(sk_table_sample_cos(&bogus, 0.5f)));
    bogus.n = 4;
    bogus.data = NULL;
    CHECK(isnan(sk_table_sample_cos(&bogus, 0.5f)));
    {
        /* NULL and malformed tables: NaN density and direction; pdf_out may
         * be NULL. */
        sk_vec3 w = {0, 0, 1};
        sk_vec3_f64 wd = {0, 0, 1};
        float pf = 0.0f;
        double pd = 0.0;
        CHECK(isnan(sk_table_pdf(NULL, 0.5f)) && isnan(sk_table_pdf_f64(NULL, 0.5)) && isnan(sk_table_pdf(&bogus, 0.5f)));
        CHECK(vec_nan3(sk_table_sample_dir(NULL, w, 0.5f, 0.5f, &pf)) && isnan(pf));
        CHECK(isnan(sk_table_sample_dir_f64(NULL, wd, 0.5, 0.5, &pd).x) && isnan(pd));
        CHECK(vec_nan3(sk_table_sample_dir(&bogus, w, 0.5f, 0.5f, NULL)));
        sk_table_new_inverse(&p, buf, 66, 32, &t);
        CHECK(!isnan(sk_table_sample_dir(&t, w, 0.5f, 0.5f, NULL).z));
    }
}

/* 2-D tables: sizes, NULLs, bad axes and slices, special x and u. */
static void tables2d(void) {
    int i;
    float buf[3 * 2 * 17];
    double bufd[3 * 2 * 17];
    sk_phase ph[3];
    sk_phase_f64 phd[3];
    sk_table2d t, bogus;
    sk_table2d_f64 td;
    sk_vec3 w = {0, 0, 1}, dir;
    sk_vec3_f64 wd = {0, 0, 1}, dird;
    float pf;
    double pd;
    i = 0;
    CHECK(sk_phase_new_hg(0.2f, &ph[0]) == SK_OK && sk_phase_new_hg(0.5f, &ph[1]) == SK_OK && sk_phase_new_rayleigh(&ph[2]) == SK_OK);
    CHECK(sk_phase_new_hg_f64(0.2, &phd[0]) == SK_OK && sk_phase_new_hg_f64(0.5, &phd[1]) == SK_OK && sk_phase_new_rayleigh_f64(&phd[2]) == SK_OK);
    CHECK(sk_table2d_len(16, 3) == 102 && sk_table2d_len(0, 3) == 0 && sk_table2d_len(16, 0) == 0 && sk_table2d_len(SIZE_MAX / 2, 3) == 0);
    CHECK(sk_table2d_new_inverse(ph, 3, buf, 102, 16, 0.0f, 1.0f, &t) == SK_OK && t.k == 3 && t.n == 16);
    CHECK(sk_table2d_new_inverse_f64(phd, 3, bufd, 102, 16, 0.0, 1.0, &td) == SK_OK);
    CHECK(sk_table2d_new_inverse(NULL, 3, buf, 102, 16, 0.0f, 1.0f, &t) == SK_ERR_NULL && sk_table2d_new_inverse(ph, 3, NULL, 102, 16, 0.0f, 1.0f, &t) == SK_ERR_NULL);
    CHECK(sk_table2d_new_inverse(ph, 3, buf, 102, 16, 0.0f, 1.0f, NULL) == SK_ERR_NULL && sk_table2d_new_inverse_f64(phd, 3, bufd, 101, 16, 0.0, 1.0, &td) == SK_ERR_SIZE);
    CHECK(sk_table2d_new_inverse(ph, 0, buf, 102, 16, 0.0f, 1.0f, &t) == SK_ERR_SIZE && sk_table2d_new_inverse(ph, 3, buf, 102, 0, 0.0f, 1.0f, &t) == SK_ERR_SIZE);
    CHECK(sk_table2d_new(buf, 102, 16, 3, 0.0f, 1.0f, &t) == SK_OK && sk_table2d_new_f64(bufd, 102, 16, 3, 0.0, 1.0, &td) == SK_OK);
    CHECK(sk_table2d_new(NULL, 102, 16, 3, 0.0f, 1.0f, &t) == SK_ERR_NULL && sk_table2d_new_f64(bufd, 102, 16, 3, 0.0, 1.0, NULL) == SK_ERR_NULL);
    CHECK(sk_table2d_new(buf, 101, 16, 3, 0.0f, 1.0f, &t) == SK_ERR_SIZE && sk_table2d_new(buf, SIZE_MAX, 16, 3, 0.0f, 1.0f, &t) == SK_ERR_SIZE);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double d = DS[i];
        sk_table2d_new(buf, 102, 16, 3, 0.0f, 1.0f, &t);
        sk_table2d_new_f64(bufd, 102, 16, 3, 0.0, 1.0, &td);
        /* Axis: x0 finite, dx finite and positive. */
        CHECK(sk_table2d_new(buf, 102, 16, 3, f, 1.0f, &bogus) == (isfinite(f) ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_table2d_new_inverse(ph, 3, buf, 102, 16, 0.0f, f, &bogus) == (isfinite(f) && f > 0.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_table2d_new_f64(bufd, 102, 16, 3, 0.0, d, &td) == (isfinite(d) && d > 0.0 ? SK_OK : SK_ERR_DOMAIN));
        sk_table2d_new_f64(bufd, 102, 16, 3, 0.0, 1.0, &td);
        /* Lookups: NaN x or u gives NaN; otherwise a cosine. */
        CHECK(isnan(f) ? isnan(sk_table2d_sample_cos(&t, f, 0.5f)) : in_unit(sk_table2d_sample_cos(&t, f, 0.5f)));
        CHECK(isnan(f) ? isnan(sk_table2d_sample_cos(&t, 0.5f, f)) : in_unit(sk_table2d_sample_cos(&t, 0.5f, f)));
        CHECK(isnan(d) ? isnan(sk_table2d_sample_cos_f64(&td, d, 0.5)) : in_unit(sk_table2d_sample_cos_f64(&td, d, 0.5)));
        pf = sk_table2d_pdf(&t, 0.5f, f);
        CHECK(isnan(f) ? isnan(pf) : (fabsf(f) > 1.0f ? pf == 0.0f : pf >= 0.0f));
        pd = sk_table2d_pdf_f64(&td, d, 0.3);
        CHECK(isnan(d) ? isnan(pd) : pd > 0.0 && isfinite(pd));
        dir = sk_table2d_sample_dir(&t, 0.7f, w, f, 0.25f, &pf);
        CHECK(isnan(f) ? isnan(pf) : vec_unit(dir) && pf == sk_table2d_pdf(&t, 0.7f, sk_table2d_sample_cos(&t, 0.7f, f)));
        dird = sk_table2d_sample_dir_f64(&td, d, wd, 0.5, 0.5, &pd);
        CHECK(isnan(d) ? vec_nan3d(dird) && isnan(pd) : vec_unitd(dird) && pd > 0.0);
    }
    i = 0;
    /* A slice that is not a monotone table in [-1, 1]. */
    buf[40] = 2.0f;
    CHECK(sk_table2d_new(buf, 102, 16, 3, 0.0f, 1.0f, &bogus) == SK_ERR_DOMAIN);
    bufd[41] = -1.0;
    CHECK(sk_table2d_new_f64(bufd, 102, 16, 3, 0.0, 1.0, &td) == SK_ERR_DOMAIN);
    /* NULL and malformed tables: NaN; pdf_out may be NULL. */
    CHECK(sk_table2d_new_inverse(ph, 3, buf, 102, 16, 0.0f, 1.0f, &t) == SK_OK);
    bogus = t;
    bogus.k = 0;
    CHECK(isnan(sk_table2d_sample_cos(&bogus, 0.5f, 0.5f)) && isnan(sk_table2d_pdf(&bogus, 0.5f, 0.5f)));
    bogus = t;
    bogus.dx = 0.0f;
    CHECK(isnan(sk_table2d_sample_cos(&bogus, 0.5f, 0.5f)) && vec_nan3(sk_table2d_sample_dir(&bogus, 0.5f, w, 0.5f, 0.5f, NULL)));
    bogus = t;
    bogus.data = NULL;
    CHECK(isnan(sk_table2d_sample_cos(&bogus, 0.5f, 0.5f)));
    CHECK(isnan(sk_table2d_sample_cos(NULL, 0.5f, 0.5f)) && isnan(sk_table2d_sample_cos_f64(NULL, 0.5, 0.5)));
    CHECK(isnan(sk_table2d_pdf(NULL, 0.5f, 0.5f)) && isnan(sk_table2d_pdf_f64(NULL, 0.5, 0.5)));
    CHECK(vec_nan3d(sk_table2d_sample_dir_f64(NULL, 0.5, wd, 0.5, 0.5, &pd)) && isnan(pd));
    /* Unconstructed phase among the slices. */
    memset(&ph[1], 0, sizeof ph[1]);
    CHECK(sk_table2d_new_inverse(ph, 3, buf, 102, 16, 0.0f, 1.0f, &t) == SK_ERR_DOMAIN);
}

/* The albedo curve: a small run, the inverse, NULLs and bad layers. */
static void albedo_curves(void) {
    int i = 0;
    uint64_t st = 1;
    sk_rng rng = {&st, splitmix}, no_fn = {&st, NULL};
    sk_phase_f64 hg, zero_p;
    sk_albedo_curve_f64 c, slab;
    double omega = -1.0;
    memset(&zero_p, 0, sizeof zero_p);
    CHECK(sk_phase_new_hg_f64(0.5, &hg) == SK_OK);
    CHECK(sk_albedo_curve_new_f64(&hg, INFINITY, 0.0, 2000, &rng, &c) == SK_OK && c.paths == 2000 && c.rho[0] == 1.0);
    CHECK(sk_albedo_curve_single_scattering_albedo_f64(&c, 0.4, &omega) == SK_OK && omega > 0.8 && omega < 1.0);
    CHECK(fabs(sk_albedo_curve_albedo_f64(&c, omega) - 0.4) < 1e-9 && sk_albedo_curve_std_error_f64(&c, omega) > 0.0);
    CHECK(sk_albedo_curve_new_f64(&hg, 2.0, 0.5, 500, &rng, &slab) == SK_OK && slab.rho[0] < 1.0);
    CHECK(sk_albedo_curve_single_scattering_albedo_f64(&slab, 0.99, &omega) == SK_ERR_DOMAIN);
    {
        /* A slab's fine nodes lie between the first two, falling; a curve
           whose fine arrays are zero (a semi-infinite layer's, or one stored
           from the coarse nodes alone) is the same beyond the first interval
           and at omega = 1. */
        sk_albedo_curve_f64 coarse = slab;
        CHECK(slab.fine_rho[0] <= slab.rho[0] && slab.fine_rho[0] >= slab.rho[1] &&
              slab.fine_rho[SK_ALBEDO_FINE - 1] >= slab.fine_rho[0]);
        CHECK(c.fine_rho[0] == 0.0 && c.fine_se[SK_ALBEDO_FINE - 1] == 0.0);
        memset(coarse.fine_rho, 0, sizeof coarse.fine_rho);
        memset(coarse.fine_se, 0, sizeof coarse.fine_se);
        CHECK(sk_albedo_curve_albedo_f64(&coarse, 0.5) == sk_albedo_curve_albedo_f64(&slab, 0.5));
        CHECK(sk_albedo_curve_albedo_f64(&coarse, 1.0) == sk_albedo_curve_albedo_f64(&slab, 1.0));
        CHECK(sk_albedo_curve_albedo_f64(&coarse, 0.99999) > 0.0 && sk_albedo_curve_albedo_f64(&slab, 0.99999) > 0.0);
    }
    CHECK(sk_albedo_curve_new_f64(NULL, INFINITY, 0.0, 10, &rng, &c) == SK_ERR_NULL && sk_albedo_curve_new_f64(&hg, INFINITY, 0.0, 10, NULL, &c) == SK_ERR_NULL);
    CHECK(sk_albedo_curve_new_f64(&hg, INFINITY, 0.0, 10, &no_fn, &c) == SK_ERR_NULL && sk_albedo_curve_new_f64(&hg, INFINITY, 0.0, 10, &rng, NULL) == SK_ERR_NULL);
    CHECK(sk_albedo_curve_new_f64(&zero_p, INFINITY, 0.0, 10, &rng, &slab) == SK_ERR_DOMAIN && sk_albedo_curve_new_f64(&hg, INFINITY, 0.0, 0, &rng, &slab) == SK_ERR_DOMAIN);
    for (i = 0; i < NS; i++) {
        double d = DS[i];
        /* tau: +inf (semi-infinite) or finite positive; mu0: 0 or (0, 1]. */
        CHECK(sk_albedo_curve_new_f64(&hg, d, 0.0, 10, &rng, &slab) == (d > 0.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_albedo_curve_new_f64(&hg, INFINITY, d, 10, &rng, &slab) == (d == 0.0 || (d > 0.0 && d <= 1.0) ? SK_OK : SK_ERR_DOMAIN));
        CHECK(isnan(d) || fabs(d) > 1.0 ? isnan(sk_albedo_curve_albedo_f64(&c, d)) : d == 0.0 || !isnan(sk_albedo_curve_albedo_f64(&c, d)));
        CHECK(sk_albedo_curve_single_scattering_albedo_f64(&c, d, &omega) == (d >= 0.0 && d <= 1.0 ? SK_OK : SK_ERR_DOMAIN));
    }
    i = 0;
    CHECK(isnan(sk_albedo_curve_albedo_f64(NULL, 0.5)) && isnan(sk_albedo_curve_std_error_f64(NULL, 0.5)));
    CHECK(sk_albedo_curve_single_scattering_albedo_f64(NULL, 0.5, &omega) == SK_ERR_NULL && sk_albedo_curve_single_scattering_albedo_f64(&c, 0.5, NULL) == SK_ERR_NULL);
}

static void surfaces(void) {
    int i;
    uint64_t st = 2;
    sk_rng rng = {&st, counter};
    sk_surface s;
    sk_surface_f64 sd;
    sk_vec3 n = {0, 0, 1}, d = {0.6f, 0, -0.8f}, out;
    sk_vec3_f64 nd = {0, 0, 1}, ddd = {0.6, 0, -0.8}, outd;
    uint32_t ev;
    sk_surface_new(SK_SURFACE_PHONG, 10, SK_FRACTION_SCALAR, 0, 5e-8f, SK_CROSSING_FOLD, &s);
    sk_surface_new_f64(SK_SURFACE_LAMBERT, 1, SK_FRACTION_CONSTANT, 0.5, 0, SK_CROSSING_MIRROR, &sd);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double g = DS[i];
        sk_vec3 v = {f, 0, -1};
        sk_vec3_f64 vd = {g, 0, -1};
        sk_vec3 r;
        /* Vectors with a special component: finite ones work, others are NaN/DOMAIN. */
        r = sk_reflect(v, n);
        CHECK(bad(f) ? vec_nan3(r) : vec_unit(r));
        r = sk_lambert_sample(v, 0.5f, 0.5f);
        CHECK(bad(f) ? vec_nan3(r) : vec_unit(r));
        CHECK(vec_unitd(sk_reflect_f64(ddd, nd)) && (bad(g) ? vec_nan3d(sk_reflect_f64(vd, nd)) : 1));
        CHECK(bad(g) ? vec_nan3d(sk_lambert_sample_f64(vd, 0.5, 0.5)) : vec_unitd(sk_lambert_sample_f64(vd, 0.5, 0.5)));
        CHECK(sk_refract(v, n, 1.0f, 1.5f, &r) == (bad(f) ? SK_ERR_DOMAIN : SK_OK));
        CHECK(sk_refract_f64(vd, nd, 1.0, 1.5, &outd) == (bad(g) ? SK_ERR_DOMAIN : SK_OK));
        /* n_i: valid and positive; refraction exists while n_i sin(theta_i)/n_t <= 1 (sin = 0.6). */
        CHECK(sk_refract(d, n, f, 1.5f, &r) == (f > 0.0f && isfinite(f) && f * 0.6f / 1.5f <= 1.0f ? SK_OK : SK_ERR_DOMAIN));
        /* Phong: alpha outside [1, 1e6] and special axes give NaN. */
        r = sk_phong_sample(n, n, f, SK_CROSSING_FOLD, 0.5f, 0.5f);
        CHECK((f >= 1.0f && f <= 1e6f) ? vec_unit(r) : vec_nan3(r));
        CHECK((g >= 1.0 && g <= 1e6) ? vec_unitd(sk_phong_sample_f64(nd, nd, g, SK_CROSSING_RESAMPLE, 0.5, 0.5))
                                      : vec_nan3d(sk_phong_sample_f64(nd, nd, g, SK_CROSSING_RESAMPLE, 0.5, 0.5)));
        CHECK(bad(f) ? vec_nan3(sk_phong_sample(v, n, 10, SK_CROSSING_MIRROR, 0.5f, 0.5f)) : 1);
        CHECK(vec_nan3d(sk_phong_sample_f64(nd, nd, 10, 3, 0.5, 0.5)) && vec_nan3(sk_phong_sample(n, n, 10, UINT32_MAX, 0.5f, 0.5f)));
        /* Uniforms: clamped, NaN gives NaN. */
        CHECK(isnan(f) ? isnan(sk_lambert_sample(n, f, 0.5f).z) : vec_unit(sk_lambert_sample(n, f, 0.5f)));
        /* Fresnel and fractions: NaN or the documented value. */
        CHECK((f > 0.0f && isfinite(f)) ? sk_fresnel_dielectric(0.5f, f, 1.5f) >= 0.0f : isnan(sk_fresnel_dielectric(0.5f, f, 1.5f)));
        CHECK(fabsf(f) <= 1.0f ? sk_fresnel_dielectric(f, 1.0f, 1.5f) >= 0.0f : isnan(sk_fresnel_dielectric(f, 1.0f, 1.5f)));
        CHECK(isnan(sk_fresnel_dielectric_f64(0.5, 1.0, g)) == !(g > 0.0 && isfinite(g)));
        /* Matched indices: no interface at any angle, grazing included (0
           was NaN, and a |cos| below 1e-4 reflected everything in float). */
        CHECK(fabsf(f) <= 1.0f ? sk_fresnel_dielectric(f, 1.33f, 1.33f) == 0.0f : isnan(sk_fresnel_dielectric(f, 1.33f, 1.33f)));
        CHECK(fabs(g) <= 1.0 ? sk_fresnel_dielectric_f64(g, 1.33, 1.33) == 0.0 : isnan(sk_fresnel_dielectric_f64(g, 1.33, 1.33)));
        CHECK((f > 0.0f && isfinite(f)) == !isnan(sk_scatter_fraction_reflect(f, 1e-8f, 1.5f, 1.0f)));
        CHECK((f >= 0.0f && isfinite(f)) == !isnan(sk_scatter_fraction_reflect(600e-9f, f, 1.5f, 1.0f)));
        CHECK((g >= 0.0 && isfinite(g)) == !isnan(sk_scatter_fraction_reflect_f64(600e-9, g, 1.5, 1.0)));
        CHECK((f > 0.0f && isfinite(f)) == !isnan(sk_scatter_fraction_transmit(600e-9f, 1e-8f, 1.5f, 1.0f, f, 1.0f)));
        CHECK((fabs(g) <= 1.0) == !isnan(sk_scatter_fraction_transmit_f64(600e-9, 1e-8, 1.5, 1.0, 3.9, g)));
        /* Surface constructor and interaction. */
        CHECK(sk_surface_new(SK_SURFACE_PHONG, f, SK_FRACTION_CONSTANT, 0.5f, 0, SK_CROSSING_FOLD, &s) ==
              (f >= 1.0f && f <= 1e6f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_surface_new_f64(SK_SURFACE_SPECULAR, 1, SK_FRACTION_CONSTANT, g, 0, SK_CROSSING_FOLD, &sd) ==
              (g >= 0.0 && g <= 1.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 1, SK_FRACTION_SCALAR, 0, f, SK_CROSSING_FOLD, &s) ==
              (f >= 0.0f && isfinite(f) ? SK_OK : SK_ERR_DOMAIN));
        if (sk_surface_new(SK_SURFACE_PHONG, 10, SK_FRACTION_SCALAR, 0, 5e-8f, SK_CROSSING_FOLD, &s) != SK_OK) failed++;
        /* n_i: finite and positive, at most 2^26 times n_t. */
        CHECK(sk_surface_interact(&s, d, n, f, 1.5f, 600e-9f, &rng, &out, &ev) ==
              (f > 0.0f && isfinite(f) && (double)f / 1.5 <= 67108864.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_surface_interact(&s, d, n, 1.0f, 1.5f, f, &rng, &out, &ev) == (f > 0.0f && isfinite(f) ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_surface_interact(&s, v, n, 1.0f, 1.5f, 600e-9f, &rng, &out, &ev) == (bad(f) ? SK_ERR_DOMAIN : SK_OK));
        sk_surface_new_f64(SK_SURFACE_LAMBERT, 1, SK_FRACTION_CONSTANT, 0.5, 0, SK_CROSSING_MIRROR, &sd);
        CHECK(sk_surface_interact_f64(&sd, ddd, vd, 1.0, 1.5, 1.0, &rng, &outd, &ev) == (bad(g) ? SK_ERR_DOMAIN : SK_OK));
    }
    i = 0;
    CHECK(sk_surface_new(3, 1, 0, 0.5f, 0, 0, &s) == SK_ERR_METHOD && sk_surface_new(0, 1, 2, 0.5f, 0, 0, &s) == SK_ERR_METHOD);
    CHECK(sk_surface_new(0, 1, 0, 0.5f, 0, UINT32_MAX, &s) == SK_ERR_METHOD && sk_surface_new_f64(9, 1, 0, 0.5, 0, 0, &sd) == SK_ERR_METHOD);
    CHECK(sk_surface_new(0, 1, 0, 0.5f, 0, 0, NULL) == SK_ERR_NULL && sk_surface_new_f64(0, 1, 0, 0.5, 0, 0, NULL) == SK_ERR_NULL);
    CHECK(sk_surface_interact(NULL, d, n, 1, 1.5f, 1, &rng, &out, &ev) == SK_ERR_NULL);
    CHECK(sk_surface_interact(&s, d, n, 1, 1.5f, 1, NULL, &out, &ev) == SK_ERR_NULL);
    CHECK(sk_surface_interact(&s, d, n, 1, 1.5f, 1, &rng, NULL, &ev) == SK_ERR_NULL);
    CHECK(sk_surface_interact_f64(&sd, ddd, nd, 1, 1.5, 1, &rng, &outd, NULL) == SK_ERR_NULL);
    CHECK(sk_refract(d, n, 1, 1.5f, NULL) == SK_ERR_NULL && sk_refract_f64(ddd, nd, 1, 1.5, NULL) == SK_ERR_NULL);
}

/* Tracking arguments: the ray [t_min, t_max] from o along d through a
 * grid or the caller's coefficients, with or without majorants. */
static sk_track_args targs(const sk_grid *g, sk_medium_fn f, void *ctx, const sk_majorants *m, sk_vec3 o, sk_vec3 d,
                           float t_min, float t_max, uint32_t budget, sk_rng *rng) {
    sk_track_args a;
    memset(&a, 0, sizeof a);
    a.medium.grid = g;
    a.medium.coefficients = f;
    a.medium.ctx = ctx;
    a.medium.majorants = m;
    a.medium.sigma_maj = 1.0f;
    a.o = o;
    a.d = d;
    a.t_min = t_min;
    a.t_max = t_max;
    a.budget = budget;
    a.rng = rng;
    return a;
}
static sk_track_args_f64 targs64(const sk_grid_f64 *g, sk_medium_fn_f64 f, void *ctx, const sk_majorants_f64 *m, sk_vec3_f64 o,
                                 sk_vec3_f64 d, double t_min, double t_max, uint32_t budget, sk_rng *rng) {
    sk_track_args_f64 a;
    memset(&a, 0, sizeof a);
    a.medium.grid = g;
    a.medium.coefficients = f;
    a.medium.ctx = ctx;
    a.medium.majorants = m;
    a.medium.sigma_maj = 1.0;
    a.o = o;
    a.d = d;
    a.t_min = t_min;
    a.t_max = t_max;
    a.budget = budget;
    a.rng = rng;
    return a;
}

static sk_coefficients coeff32(void *ctx, sk_vec3 p) {
    sk_coefficients c = {0.25f, 0.25f};
    (void)p;
    if (ctx) c.sigma_a = *(float *)ctx;
    return c;
}
static sk_coefficients_f64 coeff64(void *ctx, sk_vec3_f64 p) {
    sk_coefficients_f64 c = {0.25, 0.25};
    (void)p;
    if (ctx) c.sigma_s = *(double *)ctx;
    return c;
}

/* An emitted radiance: *ctx, or 1 without one. */
static float le32(void *ctx, sk_vec3 p) {
    (void)p;
    return ctx ? *(float *)ctx : 1.0f;
}
static double le64(void *ctx, sk_vec3_f64 p) {
    (void)p;
    return ctx ? *(double *)ctx : 1.0;
}

static void media(void) {
    int i;
    uint64_t st = 3;
    sk_rng rng = {&st, counter};
    const float values[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    const double valuesd[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    float sig[2] = {1, 2}, sgs[2] = {0.5f, 1}, w[2], t, ctxf;
    double sigd[2] = {1, 2}, sgsd[2] = {0.5, 1}, wd[2], td, ctxd;
    uint32_t ev;
    sk_grid g, zero_g;
    sk_grid_f64 gd;
    sk_track_result r;
    sk_track_result_f64 rd;
    sk_track_args a;
    sk_track_args_f64 ad;
    sk_vec3 o = {-1, 0.5f, 0.5f}, d = {1, 0, 0};
    sk_vec3_f64 od = {-1, 0.5, 0.5}, dd = {1, 0, 0};
    {
        /* sk_uniform: NULL rng or callback gives NaN without drawing; one
         * draw otherwise, converted as the samplers convert. */
        sk_rng no_fn = {&st, NULL};
        uint64_t before, word;
        i = 0;
        before = st;
        word = before + 0x9e3779b97f4a7c15ULL;
        CHECK(isnan(sk_uniform(NULL)) && isnan(sk_uniform_f64(NULL)));
        CHECK(isnan(sk_uniform(&no_fn)) && isnan(sk_uniform_f64(&no_fn)) && st == before);
        CHECK(sk_uniform(&rng) == (float)(word >> 40) * 0x1p-24f && st == word);
        word += 0x9e3779b97f4a7c15ULL;
        CHECK(sk_uniform_f64(&rng) == (double)(word >> 11) * 0x1p-53 && st == word);
    }
    sk_grid_new(values, 2, 2, 2, 1, 1, &g);
    sk_grid_new_f64(valuesd, 2, 2, 2, 1, 1, &gd);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double x = DS[i];
        sk_vec3 v = {f, 0.5f, 0.5f};
        sk_vec3_f64 vd = {x, 0.5, 0.5};
        float fp = sk_free_path(f, 0.5f);
        sk_coefficients c;
        sk_status s;
        CHECK((f >= 0.0f && isfinite(f)) ? fp >= 0.0f : isnan(fp));
        CHECK(isnan(f) ? isnan(sk_free_path(1.0f, f)) : sk_free_path(1.0f, f) >= 0.0f);
        CHECK(isnan(sk_free_path_f64(x, 0.5)) == !(x >= 0.0 && isfinite(x)));
        CHECK(isnan(sk_transmittance(f, 1.0f)) == !(f >= 0.0f) && isnan(sk_transmittance(1.0f, f)) == !(f >= 0.0f));
        CHECK(isnan(sk_transmittance_f64(x, 1.0)) == !(x >= 0.0));
        sig[1] = f;
        CHECK(sk_homogeneous_sample(sig, sgs, 2, 1.0f, 0.5f, 0.5f, &t, &ev, w) ==
              (f >= 1.0f && isfinite(f) ? SK_OK : SK_ERR_DOMAIN));
        sig[1] = 2;
        CHECK(sk_homogeneous_sample(sig, sgs, 2, f, 0.5f, 0.5f, &t, &ev, w) == (f >= 0.0f ? SK_OK : SK_ERR_DOMAIN));
        sigd[0] = x;
        CHECK(sk_homogeneous_sample_f64(sigd, sgsd, 2, 1.0, 0.5, 0.5, &td, &ev, wd) ==
              (x >= 0.5 && isfinite(x) ? SK_OK : SK_ERR_DOMAIN));
        sigd[0] = 1;
        /* FLT_MAX/DBL_MAX: the majorant (sigma_a + sigma_s) * 1 overflows. */
        CHECK(sk_grid_new(values, 2, 2, 2, f, 1, &g) == (f >= 0.0f && f < FLT_MAX ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_grid_new_f64(valuesd, 2, 2, 2, 1, x, &gd) == (x >= 0.0 && x < DBL_MAX ? SK_OK : SK_ERR_DOMAIN));
        sk_grid_new(values, 2, 2, 2, 1, 1, &g);
        sk_grid_new_f64(valuesd, 2, 2, 2, 1, 1, &gd);
        CHECK(isnan(f) ? isnan(sk_grid_density(&g, v)) : sk_grid_density(&g, v) >= 0.0f);
        CHECK(isnan(x) ? isnan(sk_grid_density_f64(&gd, vd)) : sk_grid_density_f64(&gd, vd) >= 0.0);
        c = sk_grid_coefficients(&g, v);
        CHECK(isnan(f) ? isnan(c.sigma_a) && isnan(c.sigma_s) : c.sigma_a >= 0.0f && c.sigma_s == c.sigma_a);
        CHECK(isnan(x) == isnan(sk_grid_coefficients_f64(&gd, vd).sigma_s));
        /* Through the grid with its one majorant: a bad origin or t_max is
         * DOMAIN, and out is untouched then. */
        r.t = 7.0f;
        a = targs(&g, NULL, NULL, NULL, v, d, 0, 3, 0, &rng);
        CHECK(sk_delta_track(&a, &r) == (bad(f) ? SK_ERR_DOMAIN : SK_OK));
        CHECK(!bad(f) || r.t == 7.0f);
        a = targs(&g, NULL, NULL, NULL, o, d, 0, f, 0, &rng);
        CHECK(sk_delta_track(&a, &r) == (f >= 0.0f ? SK_OK : SK_ERR_DOMAIN));
        ad = targs64(&gd, NULL, NULL, NULL, od, vd, 0, 3, 0, &rng);
        CHECK(sk_delta_track_f64(&ad, &rd) == (bad(x) ? SK_ERR_DOMAIN : SK_OK));
        a = targs(&g, NULL, NULL, NULL, v, d, 0, 3, 0, &rng);
        CHECK(sk_ratio_track(&a, &r) == (bad(f) ? SK_ERR_DOMAIN : SK_OK) && (bad(f) || (r.tr >= 0.0f && isnan(r.t))));
        ad = targs64(&gd, NULL, NULL, NULL, od, dd, 0, x, 0, &rng);
        CHECK(sk_ratio_track_f64(&ad, &rd) == (x >= 0.0 ? SK_OK : SK_ERR_DOMAIN));
        /* The caller's coefficients under one majorant sigma_maj = f: bad
         * -> DOMAIN; 0 or subnormal -> no tentative collision in [0, 3] ->
         * OK; FLT_MAX -> tiny steps until the budget runs out. The
         * coefficients (sigma_a = 0.25 or f, sigma_s 0.25) must stay
         * within it. */
        a = targs(NULL, coeff32, NULL, NULL, o, d, 0, 3, 1000, &rng);
        a.medium.sigma_maj = f;
        s = sk_delta_track(&a, &r);
        CHECK(s == (isnan(f) || isinf(f) || f < 0.0f ? SK_ERR_DOMAIN : f > 1e30f ? SK_ERR_BUDGET : SK_OK));
        ctxd = x;
        ad = targs64(NULL, coeff64, &ctxd, NULL, od, dd, 0, 3, 1000, &rng);
        ad.medium.sigma_maj = 50.0;
        CHECK(sk_ratio_track_f64(&ad, &rd) == (x >= 0.0 && x <= 49.75 ? SK_OK : SK_ERR_DOMAIN));
        a = targs(NULL, coeff32, NULL, NULL, o, d, f, 3, 1000, &rng);
        CHECK(sk_ratio_track(&a, &r) == (f >= 0.0f && f <= 3.0f ? SK_OK : SK_ERR_DOMAIN));
        ctxf = f;
        a = targs(NULL, coeff32, &ctxf, NULL, o, d, 0, 3, 1000, &rng);
        a.medium.sigma_maj = 50.0f;
        CHECK(sk_delta_track(&a, &r) == (f >= 0.0f && f <= 49.75f ? SK_OK : SK_ERR_DOMAIN));
    }
    i = 0;
    CHECK(sk_homogeneous_sample(sig, sgs, 0, 1, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_SIZE);
    CHECK(sk_homogeneous_sample(sig, sgs, SIZE_MAX, 1, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_SIZE);
    CHECK(sk_homogeneous_sample(NULL, sgs, 2, 1, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_NULL);
    CHECK(sk_homogeneous_sample_f64(sigd, sgsd, 2, 1, 0.5, 0.5, &td, &ev, NULL) == SK_ERR_NULL);
    CHECK(sk_grid_new(values, 0, 2, 2, 1, 1, &g) == SK_ERR_SIZE && sk_grid_new(NULL, 2, 2, 2, 1, 1, &g) == SK_ERR_NULL);
    CHECK(sk_grid_new(values, UINT32_MAX, UINT32_MAX, UINT32_MAX, 1, 1, &g) == SK_ERR_SIZE);
    CHECK(sk_grid_new_f64(valuesd, 2, 2, 2, 1, 1, NULL) == SK_ERR_NULL);
    CHECK(isnan(sk_grid_density(NULL, o)) && isnan(sk_grid_density_f64(NULL, od)));
    CHECK(isnan(sk_grid_coefficients(NULL, o).sigma_a) && isnan(sk_grid_coefficients_f64(NULL, od).sigma_a));
    /* A zeroed grid was never built: NaN and DOMAIN, never read. */
    memset(&zero_g, 0, sizeof zero_g);
    CHECK(isnan(sk_grid_density(&zero_g, o)) && sk_grid_set_box(&zero_g, (sk_vec3){0, 0, 0}, (sk_vec3){1, 1, 1}) == SK_ERR_DOMAIN);
    CHECK(sk_grid_set_sampling(&zero_g, SK_SAMPLING_CELLS) == SK_ERR_DOMAIN);
    a = targs(&zero_g, NULL, NULL, NULL, o, d, 0, 1, 0, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN && sk_ratio_track(&a, &r) == SK_ERR_DOMAIN);
    /* NULL arguments, results, generators; no medium, or two. */
    a = targs(&g, NULL, NULL, NULL, o, d, 0, 1, 0, &rng);
    CHECK(sk_delta_track(NULL, &r) == SK_ERR_NULL && sk_delta_track(&a, NULL) == SK_ERR_NULL);
    CHECK(sk_ratio_track(NULL, &r) == SK_ERR_NULL && sk_ratio_track(&a, NULL) == SK_ERR_NULL);
    a.rng = NULL;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_NULL);
    a = targs(NULL, NULL, NULL, NULL, o, d, 0, 1, 0, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_NULL && sk_ratio_track(&a, &r) == SK_ERR_NULL);
    a = targs(&g, coeff32, NULL, NULL, o, d, 0, 1, 0, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN);
    ad = targs64(&gd, NULL, NULL, NULL, od, dd, 0, 1, 0, NULL);
    CHECK(sk_delta_track_f64(&ad, &rd) == SK_ERR_NULL && sk_ratio_track_f64(NULL, &rd) == SK_ERR_NULL);
    CHECK(sk_delta_track_f64(NULL, &rd) == SK_ERR_NULL);
    ad.rng = &rng;
    CHECK(sk_ratio_track_f64(&ad, NULL) == SK_ERR_NULL);
    /* A callback with one majorant needs a finite segment: it has no box
     * to leave. Unknown flags are METHOD. */
    a = targs(NULL, coeff32, NULL, NULL, o, d, 0, INFINITY, 0, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN && sk_ratio_track(&a, &r) == SK_ERR_DOMAIN);
    a = targs(&g, NULL, NULL, NULL, o, d, 0, 1, 0, &rng);
    a.flags = 2;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_METHOD);
    a.flags = SK_TRACK_NONBOUNDING; /* needs majorants */
    CHECK(sk_ratio_track(&a, &r) == SK_ERR_DOMAIN);
    /* An escape through the grid's one majorant reports where the segment
     * leaves the box (t_max here, inside the box: see escapes()); the
     * budget is the caller's. */
    a = targs(&g, NULL, NULL, NULL, o, d, 0, 1.5f, 0, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_OK && (r.event != SK_TRACK_ESCAPED || r.t == 1.5f));
    a = targs(&g, NULL, NULL, NULL, o, d, 0, 1e6f, 1, &rng);
    CHECK(sk_ratio_track(&a, &r) == SK_ERR_BUDGET || r.steps <= 1);
}

/* A callback medium of sigma_s = *ctx everywhere. */
static sk_coefficients thin32(void *ctx, sk_vec3 p) {
    sk_coefficients c = {0, *(const float *)ctx};
    (void)p;
    return c;
}
static sk_coefficients_f64 thin64(void *ctx, sk_vec3_f64 p) {
    sk_coefficients_f64 c = {0, *(const double *)ctx};
    (void)p;
    return c;
}

/* Delta tracking reports an escape where the ray leaves the medium: its box
 * (the segment clipped to it; t_min for a ray that misses it), or t_max for
 * a callback with one majorant, which has no box. The same t whichever way
 * the medium is given (a grid, with or without majorants, or a callback with
 * majorants), in a vacuum (no tentative collision) and in a thin medium (the
 * walk steps past the end). The grid without majorants reported t_max. */
static void escapes(void) {
    /* Rays from inside, from below (entering at 1, leaving at 2), from below
     * with t_max inside the box, and one that misses it; t_min = 0.125. */
    const float oz[4] = {0.5f, -1, -1, -1}, ox[4] = {0.5f, 0.5f, 0.5f, 5}, tmax[4] = {10, 10, 1.5f, 10};
    const float box_t[4] = {0.5f, 2, 1.5f, 0.125f};
    float dens[8], mx[1], mn[1], thin[2] = {0, 1e-6f};
    double densd[8], mxd[1], mnd[1], thind[2] = {0, 1e-6};
    uint64_t st = 11;
    sk_rng rng = {&st, counter};
    sk_grid g;
    sk_grid_f64 gd;
    sk_majorants m, cm;
    sk_majorants_f64 md, cmd;
    int i, k, v;
    for (v = 0; v < 2; v++) {
        for (k = 0; k < 8; k++) dens[k] = thin[v], densd[k] = thind[v];
        sk_grid_new(dens, 2, 2, 2, 0, 1, &g);
        sk_grid_new_f64(densd, 2, 2, 2, 0, 1, &gd);
        sk_majorants_new_from_grid(&g, 1, 1, 1, mx, mn, 1, &m);
        sk_majorants_new_from_grid_f64(&gd, 1, 1, 1, mxd, mnd, 1, &md);
        sk_majorants_new(mx, NULL, 1, 1, 1, (sk_vec3){0, 0, 0}, (sk_vec3){1, 1, 1}, &cm);
        sk_majorants_new_f64(mxd, NULL, 1, 1, 1, (sk_vec3_f64){0, 0, 0}, (sk_vec3_f64){1, 1, 1}, &cmd);
        for (i = 0; i < 4; i++) {
            sk_vec3 o = {ox[i], 0.5f, oz[i]}, d = {0, 0, 1};
            sk_vec3_f64 od = {ox[i], 0.5, oz[i]}, dd = {0, 0, 1};
            sk_track_args a[4];
            sk_track_args_f64 ad[4];
            sk_track_result r;
            sk_track_result_f64 rd;
            a[0] = targs(&g, NULL, NULL, NULL, o, d, 0.125f, tmax[i], 0, &rng);
            a[1] = targs(&g, NULL, NULL, &m, o, d, 0.125f, tmax[i], 0, &rng);
            a[2] = targs(NULL, thin32, &thin[v], &cm, o, d, 0.125f, tmax[i], 0, &rng);
            a[3] = targs(NULL, thin32, &thin[v], NULL, o, d, 0.125f, tmax[i], 0, &rng);
            ad[0] = targs64(&gd, NULL, NULL, NULL, od, dd, 0.125, tmax[i], 0, &rng);
            ad[1] = targs64(&gd, NULL, NULL, &md, od, dd, 0.125, tmax[i], 0, &rng);
            ad[2] = targs64(NULL, thin64, &thind[v], &cmd, od, dd, 0.125, tmax[i], 0, &rng);
            ad[3] = targs64(NULL, thin64, &thind[v], NULL, od, dd, 0.125, tmax[i], 0, &rng);
            a[3].medium.sigma_maj = thin[v], ad[3].medium.sigma_maj = thind[v];
            for (k = 0; k < 4; k++) {
                float want = k < 3 ? box_t[i] : tmax[i];
                /* The thin medium collides with probability below 1e-5. */
                CHECK(sk_delta_track(&a[k], &r) == SK_OK && r.event == SK_TRACK_ESCAPED && r.t == want);
                CHECK(sk_delta_track_f64(&ad[k], &rd) == SK_OK && rd.event == SK_TRACK_ESCAPED && rd.t == want);
            }
        }
    }
    i = 0;
}

/* A march longer than any budget is SK_ERR_BUDGET whether it needs more
 * evaluations than the budget (depth 7.5e5: 3e6 strata) or more strata than
 * a uint32_t holds (depth 7.5e15); the second was SK_ERR_DOMAIN. Through a
 * callback with one majorant and with majorants over the segment's box. */
static void long_marches(void) {
    const double ends[2] = {1e6, 1e16};
    const double one[1] = {0.75};
    uint64_t st = 5;
    sk_rng rng = {&st, counter};
    double thind = 0.5;
    sk_majorants_f64 md;
    sk_vec3_f64 o = {0.5, 0.5, 0}, d = {0, 0, 1};
    int i, k;
    for (i = 0; i < 2; i++) {
        sk_vec3_f64 lo = {0, 0, 0}, hi = {1, 1, ends[i]};
        sk_track_args_f64 a[2];
        sk_track_result_f64 r;
        sk_majorants_new_f64(one, NULL, 1, 1, 1, lo, hi, &md);
        a[0] = targs64(NULL, thin64, &thind, NULL, o, d, 0, ends[i], 0, &rng);
        a[0].medium.sigma_maj = 0.75;
        a[1] = targs64(NULL, thin64, &thind, &md, o, d, 0, ends[i], 0, &rng);
        for (k = 0; k < 2; k++) {
            CHECK(sk_ray_march_f64(&a[k], &r) == SK_ERR_BUDGET);
            CHECK(sk_telescoping_march_f64(&a[k], &r) == SK_ERR_BUDGET);
        }
    }
    i = 0;
}

/* Grid boxes and sampling, majorant grids and tracking through them. */
static void majorants(void) {
    int i;
    uint64_t st = 5;
    sk_rng rng = {&st, counter}, no_fn = {&st, NULL};
    const float values[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    const double valuesd[8] = {1, 1, 1, 1, 1, 1, 1, 1};
    float store[8], neg[8] = {1, 1, 1, 1, 1, 1, 1, -1}, ctxf;
    /* Majorants of 50 over a unit path: a tentative collision is certain
     * (but for e^-50), so the coefficient checks below always run. */
    const float fifty[8] = {50, 50, 50, 50, 50, 50, 50, 50};
    const double fiftyd[8] = {50, 50, 50, 50, 50, 50, 50, 50};
    double stored[8], ctxd;
    sk_grid g, g2;
    sk_grid_f64 gd;
    sk_majorants m, mine, big;
    sk_majorants_f64 md, mined, bigd;
    sk_track_result tr;
    sk_track_result_f64 trd;
    sk_track_args a;
    sk_track_args_f64 ad;
    sk_vec3 o = {-1, 0.5f, 0.5f}, d = {1, 0, 0}, zero = {0, 0, 0}, one = {1, 1, 1};
    sk_vec3_f64 od = {-1, 0.5, 0.5}, dd = {1, 0, 0}, zerod = {0, 0, 0}, oned = {1, 1, 1};
    sk_grid_new(values, 2, 2, 2, 0.5f, 0.5f, &g);
    sk_grid_new_f64(valuesd, 2, 2, 2, 0.5, 0.5, &gd);
    i = 0;
    CHECK(sk_majorants_new(fifty, NULL, 2, 2, 2, zero, one, &big) == SK_OK);
    CHECK(sk_majorants_new_f64(fiftyd, NULL, 2, 2, 2, zerod, oned, &bigd) == SK_OK);
    CHECK(sk_majorant_len(0, 1, 1) == 0 && sk_majorant_len(16, 16, 16) == 4096);
    CHECK(sizeof(size_t) < 8 || sk_majorant_len(UINT32_MAX, UINT32_MAX, UINT32_MAX) == 0);
    CHECK(sk_grid_set_sampling(NULL, 0) == SK_ERR_NULL && sk_grid_set_sampling_f64(NULL, 0) == SK_ERR_NULL);
    CHECK(sk_grid_set_sampling(&g, 2) == SK_ERR_METHOD && sk_grid_density(&g, one) == 1.0f);
    CHECK(sk_grid_set_sampling_f64(&gd, UINT32_MAX) == SK_ERR_METHOD);
    /* Cell-centred values of a constant grid read the same everywhere. */
    CHECK(sk_grid_set_sampling(&g, SK_SAMPLING_CELLS) == SK_OK && sk_grid_density(&g, zero) == 1.0f);
    CHECK(sk_grid_set_box(NULL, zero, one) == SK_ERR_NULL && sk_grid_set_box_f64(NULL, zerod, oned) == SK_ERR_NULL);
    CHECK(sk_grid_set_box(&g, one, one) == SK_ERR_DOMAIN && sk_grid_set_box_f64(&gd, oned, zerod) == SK_ERR_DOMAIN);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double x = DS[i];
        sk_vec3 lo = {f, 0, 0}, v = {f, 0.5f, 0.5f};
        sk_vec3_f64 lod = {0, x, 0}, vd = {0.5, 0.5, x};
        /* A box from lo to (1, 1, 1): valid only for finite lo.x < 1. */
        g2 = g;
        CHECK(sk_grid_set_box(&g2, lo, one) == (isfinite(f) && f < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_grid_set_box_f64(&gd, lod, oned) == (isfinite(x) && x < 1.0 ? SK_OK : SK_ERR_DOMAIN));
        sk_grid_set_box_f64(&gd, zerod, oned);
        CHECK(sk_majorants_new_from_grid(&g, 2, 2, 2, store, NULL, 8, &m) == SK_OK);
        CHECK(sk_majorants_new_from_grid_f64(&gd, 2, 2, 2, stored, NULL, 8, &md) == SK_OK);
        /* Your own majorants: a bad value is DOMAIN. */
        store[3] = f;
        CHECK(sk_majorants_new(store, NULL, 2, 2, 2, zero, one, &mine) == (isfinite(f) && f >= 0.0f ? SK_OK : SK_ERR_DOMAIN));
        stored[5] = x;
        CHECK(sk_majorants_new_f64(stored, NULL, 2, 2, 2, lod, oned, &mined) ==
              (isfinite(x) && x >= 0.0 && x < 1.0 ? SK_OK : SK_ERR_DOMAIN));
        sk_majorants_new_from_grid(&g, 2, 2, 2, store, NULL, 8, &m);
        sk_majorants_new_from_grid_f64(&gd, 2, 2, 2, stored, NULL, 8, &md);
        /* Tracking: a bad origin or t_max is DOMAIN; out untouched then. */
        tr.t = 7.0f;
        a = targs(&g, NULL, NULL, &m, v, d, 0, 3, 1000, &rng);
        CHECK(sk_delta_track(&a, &tr) == (bad(f) ? SK_ERR_DOMAIN : SK_OK));
        CHECK(!bad(f) || tr.t == 7.0f);
        a = targs(&g, NULL, NULL, &m, o, d, 0, f, 1000, &rng);
        CHECK(sk_delta_track(&a, &tr) == (f >= 0.0f ? SK_OK : SK_ERR_DOMAIN));
        ad = targs64(&gd, NULL, NULL, &md, vd, dd, 0, 3, 1000, &rng);
        CHECK(sk_delta_track_f64(&ad, &trd) == (bad(x) ? SK_ERR_DOMAIN : SK_OK));
        tr.tr = 7.0f;
        a = targs(&g, NULL, NULL, &m, o, v, 0, 3, 1000, &rng);
        CHECK(sk_ratio_track(&a, &tr) == (bad(f) ? SK_ERR_DOMAIN : SK_OK));
        CHECK(!bad(f) || tr.tr == 7.0f);
        ad = targs64(&gd, NULL, NULL, &md, od, dd, 0, x, 1000, &rng);
        CHECK(sk_ratio_track_f64(&ad, &trd) == (x >= 0.0 ? SK_OK : SK_ERR_DOMAIN));
        /* The caller's medium: sigma_a = f against the cell majorant 50. */
        ctxf = f;
        a = targs(NULL, coeff32, &ctxf, &big, o, d, 0, 3, 1000, &rng);
        CHECK(sk_delta_track(&a, &tr) == (f >= 0.0f && f <= 49.0f ? SK_OK : SK_ERR_DOMAIN));
        ctxd = x;
        ad = targs64(NULL, coeff64, &ctxd, &bigd, od, dd, 0, 3, 1000, &rng);
        CHECK(sk_ratio_track_f64(&ad, &trd) == (x >= 0.0 && x <= 49.0 ? SK_OK : SK_ERR_DOMAIN));
        a = targs(NULL, coeff32, NULL, &m, o, d, f, 3, 1000, &rng);
        CHECK(sk_ratio_track(&a, &tr) == (f >= 0.0f && f <= 3.0f ? SK_OK : SK_ERR_DOMAIN));
        ad = targs64(NULL, coeff64, NULL, &md, od, dd, 0, x, 1000, &rng);
        CHECK(sk_delta_track_f64(&ad, &trd) == (x >= 0.0 ? SK_OK : SK_ERR_DOMAIN));
    }
    i = 0;
    /* NULL pointers and callbacks. */
    CHECK(sk_majorants_new_from_grid(NULL, 2, 2, 2, store, NULL, 8, &m) == SK_ERR_NULL);
    CHECK(sk_majorants_new_from_grid(&g, 2, 2, 2, NULL, NULL, 8, &m) == SK_ERR_NULL);
    CHECK(sk_majorants_new_from_grid_f64(&gd, 2, 2, 2, stored, NULL, 8, NULL) == SK_ERR_NULL);
    CHECK(sk_majorants_new(NULL, NULL, 2, 2, 2, zero, one, &m) == SK_ERR_NULL);
    CHECK(sk_majorants_new_f64(stored, NULL, 2, 2, 2, zerod, oned, NULL) == SK_ERR_NULL);
    sk_majorants_new_from_grid(&g, 2, 2, 2, store, NULL, 8, &m);
    a = targs(&g, NULL, NULL, &m, o, d, 0, 3, 10, &no_fn);
    CHECK(sk_delta_track(&a, &tr) == SK_ERR_NULL);
    a = targs(NULL, NULL, NULL, &m, o, d, 0, 3, 10, &rng);
    CHECK(sk_delta_track(&a, &tr) == SK_ERR_NULL);
    ad = targs64(&gd, NULL, NULL, &md, od, dd, 0, 3, 10, &rng);
    CHECK(sk_delta_track_f64(&ad, NULL) == SK_ERR_NULL);
    /* Sizes: zero dimensions, a short buffer. */
    CHECK(sk_majorants_new_from_grid(&g, 0, 2, 2, store, NULL, 8, &m) == SK_ERR_SIZE);
    CHECK(sk_majorants_new_from_grid(&g, 2, 2, 2, store, NULL, 7, &m) == SK_ERR_SIZE);
    CHECK(sk_majorants_new_from_grid_f64(&gd, 3, 3, 3, stored, NULL, 8, &md) == SK_ERR_SIZE);
    CHECK(sk_majorants_new(store, NULL, 2, 0, 2, zero, one, &mine) == SK_ERR_SIZE);
    CHECK(sk_majorants_new(neg, NULL, 2, 2, 2, zero, one, &mine) == SK_ERR_DOMAIN);
    sk_majorants_new_from_grid(&g, 2, 2, 2, store, NULL, 8, &m);
    /* Never built: a zeroed value, or one whose tag was overwritten. */
    memset(&mine, 0, sizeof mine);
    a = targs(&g, NULL, NULL, &mine, o, d, 0, 3, 10, &rng);
    CHECK(sk_delta_track(&a, &tr) == SK_ERR_DOMAIN && isnan(sk_majorants_optical_depth(&mine, o, d, 0, 3)));
    memcpy(&mine, &m, sizeof m);
    memset(&mine, 0xff, 4);
    CHECK(sk_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
    /* Majorants over another box than the grid's; a zero direction. */
    g2 = g;
    sk_grid_set_box(&g2, zero, (sk_vec3){2, 1, 1});
    a = targs(&g2, NULL, NULL, &m, o, d, 0, 3, 10, &rng);
    CHECK(sk_delta_track(&a, &tr) == SK_ERR_DOMAIN);
    a = targs(&g, NULL, NULL, &m, o, zero, 0, 3, 10, &rng);
    CHECK(sk_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
    /* The budget: 1 step through a medium that has many collisions. */
    a = targs(&g, NULL, NULL, &big, o, d, 0, 1e6f, 1, &rng);
    CHECK(sk_ratio_track(&a, &tr) == SK_ERR_BUDGET);
    ad = targs64(NULL, coeff64, NULL, &bigd, od, dd, 0, 1e6, 1, &rng);
    CHECK(sk_ratio_track_f64(&ad, &trd) == SK_ERR_BUDGET);
    {
        /* Values changed after building (checked once, then loaded in
         * constant time): caught where the walk meets them. */
        float kept8[8];
        int c;
        CHECK(sk_majorants_new_from_grid(&g, 2, 2, 2, store, NULL, 8, &m) == SK_OK);
        memcpy(kept8, store, sizeof store);
        a = targs(&g, NULL, NULL, &m, o, d, 0, 3, 1000, &rng);
        for (c = 0; c < 3; c++) {
            int k;
            for (k = 0; k < 8; k++) {
                store[k] = c == 0 ? NAN : c == 1 ? -1.0f : INFINITY;
            }
            CHECK(sk_delta_track(&a, &tr) == SK_ERR_DOMAIN && sk_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
            CHECK(isnan(sk_majorants_optical_depth(&m, o, d, 0, 3)));
        }
        memcpy(store, kept8, sizeof store);
        CHECK(sk_delta_track(&a, &tr) == SK_OK);
    }
    {
        /* Minorants and residual ratio tracking: the grid is constant
         * (sigma_t 1), so its minorants sit just below its majorants, and
         * swapping them inverts every cell. */
        float hi8[8], lo8[8];
        double hi8d[8], lo8d[8];
        const float zeros8[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        const double zeros8d[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        sk_majorants e, e2, eb;
        sk_majorants_f64 ed, ebd;
        CHECK(sk_majorants_new_from_grid(&g, 2, 2, 2, hi8, lo8, 8, &e) == SK_OK && lo8[0] <= hi8[0] && lo8[0] > 0.99f);
        CHECK(sk_majorants_new_from_grid_f64(&gd, 2, 2, 2, hi8d, lo8d, 8, &ed) == SK_OK);
        CHECK(sk_majorants_new_from_grid(&g, 2, 2, 2, hi8, lo8, 7, &e2) == SK_ERR_SIZE);
        CHECK(sk_majorants_new_from_grid(&g, 2, 2, 2, hi8, hi8 + 1, 8, &e2) == SK_ERR_OVERLAP);
        CHECK(sk_majorants_new(hi8, lo8, 2, 2, 2, zero, one, &e2) == SK_OK);
        CHECK(sk_majorants_new(lo8, hi8, 2, 2, 2, zero, one, &e2) == SK_ERR_DOMAIN);
        CHECK(sk_majorants_new(hi8, neg, 2, 2, 2, zero, one, &e2) == SK_ERR_DOMAIN);
        CHECK(sk_majorants_new_f64(hi8d, lo8d, 2, 2, 2, zerod, oned, &ebd) == SK_OK);
        CHECK(sk_majorants_new_f64(lo8d, hi8d, 2, 2, 2, zerod, oned, &ebd) == SK_ERR_DOMAIN);
        CHECK(sk_majorants_new(fifty, zeros8, 2, 2, 2, zero, one, &eb) == SK_OK);
        CHECK(sk_majorants_new_f64(fiftyd, zeros8d, 2, 2, 2, zerod, oned, &ebd) == SK_OK);
        /* Tracking: the constant grid is exact (no draw); bad rays, NULLs. */
        tr.tr = 7.0f;
        a = targs(&g, NULL, NULL, &e, o, d, 0, 3, 0, &rng);
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_OK && tr.steps == 0 && fabsf(tr.tr - expf(-1.0f)) < 1e-6f);
        ad = targs64(&gd, NULL, NULL, &ed, od, dd, 0, 3, 0, &rng);
        CHECK(sk_residual_ratio_track_f64(&ad, &trd) == SK_OK && fabs(trd.tr - exp(-1.0)) < 1e-14);
        tr.tr = 7.0f;
        a = targs(&g, NULL, NULL, &e, o, zero, 0, 3, 10, &rng);
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN && tr.tr == 7.0f);
        a = targs(&g, NULL, NULL, &e, o, d, 0, -1, 10, &rng);
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        ad = targs64(&gd, NULL, NULL, &ed, od, dd, 0, NAN, 10, &rng);
        CHECK(sk_residual_ratio_track_f64(&ad, &trd) == SK_ERR_DOMAIN);
        /* No minorants, no majorants: DOMAIN. NULLs. */
        a = targs(&g, NULL, NULL, &m, o, d, 0, 3, 10, &rng);
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        a.medium.majorants = NULL;
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        a = targs(&g, NULL, NULL, &e, o, d, 0, 3, 10, &no_fn);
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_NULL && sk_residual_ratio_track(NULL, &tr) == SK_ERR_NULL);
        CHECK(sk_residual_ratio_track_f64(&ad, NULL) == SK_ERR_NULL);
        /* Minorants changed after building to exceed the majorants, or to
         * go negative: caught on the ray. Another box. */
        memcpy(lo8, fifty, sizeof lo8);
        a = targs(&g, NULL, NULL, &e, o, d, 0, 3, 10, &rng);
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        memcpy(lo8, neg, sizeof lo8);
        lo8[0] = lo8[1] = lo8[2] = lo8[3] = lo8[4] = lo8[5] = lo8[6] = -1.0f;
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        sk_majorants_new_from_grid(&g, 2, 2, 2, hi8, lo8, 8, &e);
        g2 = g;
        sk_grid_set_box(&g2, zero, (sk_vec3){2, 1, 1});
        a.medium.grid = &g2;
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        /* The caller's medium against a majorant of 50 and a zero control:
         * draws are certain, so the coefficient check runs. */
        for (i = 0; i < NS; i++) {
            ctxf = FS[i];
            a = targs(NULL, coeff32, &ctxf, &eb, o, d, 0, 3, 1000, &rng);
            CHECK(sk_residual_ratio_track(&a, &tr) == (FS[i] >= 0.0f && FS[i] <= 49.0f ? SK_OK : SK_ERR_DOMAIN));
            ctxd = DS[i];
            ad = targs64(NULL, coeff64, &ctxd, &ebd, od, dd, 0, 3, 1000, &rng);
            CHECK(sk_residual_ratio_track_f64(&ad, &trd) == (DS[i] >= 0.0 && DS[i] <= 49.0 ? SK_OK : SK_ERR_DOMAIN));
        }
        i = 0;
        ad = targs64(NULL, coeff64, NULL, &ebd, od, dd, 0, 1e6, 1, &rng);
        CHECK(sk_residual_ratio_track_f64(&ad, &trd) == SK_ERR_BUDGET);
        /* The rate: `strata` 0 is 2, the same draws as 2 from the same
         * generator state; 1 draws about half as often (sigma_t 0.25 under
         * the majorant 50 with a zero control). */
        {
            uint32_t steps[3], k;
            for (k = 0; k < 3; k++) {
                st = 99;
                ctxf = 0.0f;
                a = targs(NULL, coeff32, &ctxf, &eb, o, d, 0, 3, 100000, &rng);
                a.strata = k;
                CHECK(sk_residual_ratio_track(&a, &tr) == SK_OK && tr.tr > 0.0f && tr.tr < 1.0f);
                steps[k] = tr.steps;
            }
            CHECK(steps[0] == steps[2] && steps[1] > 20 && steps[2] > 1.6 * steps[1] && steps[2] < 2.4 * steps[1]);
        }
    }
    {
        /* The majorant optical depth and the unbiased ray marchers: the
         * grid is constant (sigma_t 1) and the ray crosses 1 unit of it,
         * so the marches are exact; strata 0 lets the library choose. */
        sk_grid g3;
        sk_status s;
        float depth = sk_majorants_optical_depth(&m, o, d, 0, 3);
        CHECK(fabsf(depth - 1.0f) < 1e-5f);
        CHECK(fabs(sk_majorants_optical_depth_f64(&md, od, dd, 0, 3) - 1.0) < 1e-12);
        CHECK(isnan(sk_majorants_optical_depth(NULL, o, d, 0, 3)) && isnan(sk_majorants_optical_depth(&m, o, zero, 0, 3)));
        CHECK(isnan(sk_majorants_optical_depth_f64(&md, od, dd, 3, 1)) && isnan(sk_majorants_optical_depth_f64(&md, od, dd, NAN, 1)));
        tr.tr = 7.0f;
        a = targs(&g, NULL, NULL, NULL, o, d, 0, 3, 1000, &rng);
        a.strata = 4;
        CHECK(sk_ray_march(&a, &tr) == SK_OK && fabsf(tr.tr - expf(-1.0f)) < 1e-6f && tr.steps > 0);
        a.strata = 0;
        CHECK(sk_ray_march(&a, &tr) == SK_OK && fabsf(tr.tr - expf(-1.0f)) < 1e-6f);
        a.medium.majorants = &m;
        CHECK(sk_ray_march(&a, &tr) == SK_OK && fabsf(tr.tr - expf(-1.0f)) < 1e-6f);
        CHECK(sk_telescoping_march(&a, &tr) == SK_OK && fabsf(tr.tr - expf(-1.0f)) < 1e-6f);
        ad = targs64(&gd, NULL, NULL, NULL, od, dd, 0, 3, 1000, &rng);
        CHECK(sk_ray_march_f64(&ad, &trd) == SK_OK && fabs(trd.tr - exp(-1.0)) < 1e-14);
        CHECK(sk_telescoping_march_f64(&ad, &trd) == SK_OK && fabs(trd.tr - exp(-1.0)) < 1e-14);
        /* A ray that misses the box, or crosses only empty cells: 1 with
         * no evaluation, whatever the strata. */
        a = targs(&g, NULL, NULL, &m, (sk_vec3){3, 3, 3}, d, 0, INFINITY, 1000, &rng);
        CHECK(sk_ray_march(&a, &tr) == SK_OK && tr.tr == 1.0f && tr.steps == 0);
        a = targs(&g, NULL, NULL, NULL, o, zero, 0, 3, 1000, &rng);
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_DOMAIN && sk_telescoping_march(&a, &tr) == SK_ERR_DOMAIN);
        a = targs(&g, NULL, NULL, NULL, o, d, 0, -1, 1000, &rng);
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_DOMAIN);
        ad = targs64(&gd, NULL, NULL, NULL, od, dd, 0, NAN, 1000, &rng);
        CHECK(sk_ray_march_f64(&ad, &trd) == SK_ERR_DOMAIN && sk_telescoping_march_f64(&ad, &trd) == SK_ERR_DOMAIN);
        a = targs(&g, NULL, NULL, NULL, o, d, 0, 3, 3, &rng);
        a.strata = 4;
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_BUDGET && sk_telescoping_march(&a, &tr) == SK_ERR_BUDGET);
        a = targs(&g, NULL, NULL, NULL, o, d, 0, 3, 1000, &no_fn);
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_NULL && sk_telescoping_march(&a, &tr) == SK_ERR_NULL);
        CHECK(sk_ray_march(NULL, &tr) == SK_ERR_NULL && sk_ray_march_f64(&ad, NULL) == SK_ERR_NULL);
        CHECK(sk_telescoping_march(NULL, &tr) == SK_ERR_NULL && sk_telescoping_march_f64(&ad, NULL) == SK_ERR_NULL);
        memset(&g3, 0, sizeof g3);
        a = targs(&g3, NULL, NULL, NULL, o, d, 0, 3, 1000, &rng);
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_DOMAIN && sk_telescoping_march(&a, &tr) == SK_ERR_DOMAIN);
        /* The caller's medium: sigma_a = f (float) or sigma_s = x (double)
         * next to 0.25; an optical depth that overflows is DOMAIN. */
        for (i = 0; i < NS; i++) {
            ctxf = FS[i];
            a = targs(NULL, coeff32, &ctxf, NULL, o, d, 0, 3, 1 << 20, &rng);
            a.strata = 4;
            CHECK(sk_ray_march(&a, &tr) == (FS[i] >= 0.0f && FS[i] < 1e30f ? SK_OK : SK_ERR_DOMAIN));
            s = sk_telescoping_march(&a, &tr);
            CHECK(FS[i] >= 0.0f && FS[i] < 1e30f ? s == SK_OK : s == SK_ERR_DOMAIN || s == SK_ERR_BUDGET);
            ctxd = DS[i];
            ad = targs64(NULL, coeff64, &ctxd, NULL, od, dd, 0, 3, 1 << 20, &rng);
            ad.strata = 4;
            CHECK(sk_ray_march_f64(&ad, &trd) == (DS[i] >= 0.0 && DS[i] < 1e300 ? SK_OK : SK_ERR_DOMAIN));
            s = sk_telescoping_march_f64(&ad, &trd);
            CHECK(DS[i] >= 0.0 && DS[i] < 1e300 ? s == SK_OK : s == SK_ERR_DOMAIN || s == SK_ERR_BUDGET);
        }
        i = 0;
        {
            /* The optical depth is not rounded (0.3 over the unit path);
             * with majorants, a ray through empty cells has no residual to
             * march: exactly 1, with no evaluation (strata 0 or not). */
            const float tenths[8] = {0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f, 0.3f}, none[8] = {0, 0, 0, 0, 0, 0, 0, 0};
            float mzs[8];
            sk_majorants m3, mz;
            sk_grid gz;
            CHECK(sk_majorants_new(tenths, NULL, 2, 2, 2, zero, one, &m3) == SK_OK);
            CHECK(fabsf(sk_majorants_optical_depth(&m3, o, d, 0, 3) - 0.3f) < 1e-6f);
            CHECK(sk_grid_new(none, 2, 2, 2, 0.5f, 0.5f, &gz) == SK_OK);
            CHECK(sk_majorants_new_from_grid(&gz, 2, 2, 2, mzs, NULL, 8, &mz) == SK_OK);
            CHECK(sk_majorants_optical_depth(&mz, o, d, 0, 3) == 0.0f);
            a = targs(&gz, NULL, NULL, &mz, o, d, 0, 3, 1000, &rng);
            CHECK(sk_ray_march(&a, &tr) == SK_OK && tr.tr == 1.0f && tr.steps == 0);
            CHECK(sk_telescoping_march(&a, &tr) == SK_OK && tr.tr == 1.0f && tr.steps == 0);
            a.strata = 5;
            CHECK(sk_ray_march(&a, &tr) == SK_OK && tr.tr == 1.0f && tr.steps == 0);
            a.strata = 0;
            a.medium.majorants = NULL;
            CHECK(sk_ray_march(&a, &tr) == SK_OK && tr.tr == 1.0f);
        }
        {
            /* With majorants the strata follow the residual sigma_maj -
             * sigma_min: a grid constant in each cell, minorants equal to
             * majorants, is exact with no evaluation (sigma_t 2 over the
             * unit path); a majorant below the density is refused. */
            const float twos[8] = {2, 2, 2, 2, 2, 2, 2, 2}, ones[8] = {1, 1, 1, 1, 1, 1, 1, 1};
            sk_grid gc;
            sk_majorants exact, low;
            CHECK(sk_grid_new(ones, 2, 2, 2, 0.5f, 1.5f, &gc) == SK_OK);
            CHECK(sk_majorants_new(twos, twos, 2, 2, 2, zero, one, &exact) == SK_OK);
            CHECK(sk_majorants_new(ones, NULL, 2, 2, 2, zero, one, &low) == SK_OK);
            a = targs(&gc, NULL, NULL, &exact, o, d, 0, 3, 1000, &rng);
            CHECK(sk_ray_march(&a, &tr) == SK_OK && tr.steps == 0 && fabsf(tr.tr - expf(-2.0f)) < 1e-6f);
            CHECK(sk_telescoping_march(&a, &tr) == SK_OK && tr.steps == 0 && fabsf(tr.tr - expf(-2.0f)) < 1e-6f);
            a.medium.majorants = &low;
            CHECK(sk_ray_march(&a, &tr) == SK_ERR_DOMAIN);
            CHECK(sk_telescoping_march(&a, &tr) == SK_ERR_DOMAIN);
        }
        /* A callback needs a finite segment; strata 0 takes sigma_maj. */
        a = targs(NULL, coeff32, NULL, NULL, o, d, 0, INFINITY, 1000, &rng);
        a.strata = 4;
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_DOMAIN && sk_telescoping_march(&a, &tr) == SK_ERR_DOMAIN);
        a = targs(NULL, coeff32, NULL, NULL, o, d, 0, 3, 1000, &rng);
        CHECK(sk_ray_march(&a, &tr) == SK_OK && tr.steps >= 3);
        a.medium.sigma_maj = NAN;
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_DOMAIN);
    }
    {
        /* Equiangular sampling toward a point 1 unit off the x axis, over
         * [0, 2] (symmetric about the foot t0 = 1: the median is 1 and the
         * density there 1/(theta_b - theta_a) = 2/pi) and over [0, inf). */
        sk_vec3 x0 = {0, 0, 0}, xd = {1, 0, 0}, p = {1, 1, 0}, on_line = {5, 0, 0};
        sk_vec3_f64 x0d = {0, 0, 0}, xdd = {2, 0, 0}, pd = {1, 1, 0};
        sk_equiangular e, bad;
        sk_equiangular_f64 ed;
        float s;
        CHECK(sk_equiangular_new(x0, xd, 0, 2, p, &e) == SK_OK);
        CHECK(fabsf(sk_equiangular_sample(&e, 0.5f) - 1.0f) < 1e-6f);
        CHECK(fabsf(sk_equiangular_pdf(&e, 1.0f) - 0.63661977f) < 1e-6f);
        CHECK(sk_equiangular_pdf(&e, 2.5f) == 0.0f && sk_equiangular_pdf(&e, NAN) == 0.0f);
        CHECK(sk_equiangular_new_f64(x0d, xdd, 0, INFINITY, pd, &ed) == SK_OK);
        CHECK(fabs(sk_equiangular_pdf_f64(&ed, 1.0) - 4.0 / (3.0 * 3.14159265358979323846)) < 1e-15);
        CHECK(sk_equiangular_sample_f64(&ed, 1.0) >= 1.0 && !isnan(sk_equiangular_sample_f64(&ed, 1.0)));
        for (i = 0; i < NS; i++) {
            s = sk_equiangular_sample(&e, FS[i]);
            CHECK(isnan(FS[i]) ? isnan(s) : (s >= 0.0f && s <= 2.0f));
            s = sk_equiangular_pdf(&e, FS[i]);
            CHECK(s >= 0.0f && s < 1.0f);
            /* A subnormal length (1e-40) has a density beyond FLT_MAX. */
            CHECK(sk_equiangular_new(x0, xd, 0, FS[i], p, &bad) == (FS[i] > FLT_MIN ? SK_OK : SK_ERR_DOMAIN));
            CHECK(sk_equiangular_new(x0, xd, FS[i], 2, p, &bad) ==
                  (FS[i] >= 0.0f && FS[i] < 2.0f ? SK_OK : SK_ERR_DOMAIN));
            CHECK(sk_equiangular_new_f64(x0d, xdd, 0, 2, (sk_vec3_f64){1, DS[i], 0}, &ed) ==
                  (fabs(DS[i]) > 1e-150 && fabs(DS[i]) < 1e150 ? SK_OK : SK_ERR_DOMAIN));
        }
        i = 0;
        CHECK(sk_equiangular_new(x0, xd, 0, 2, p, NULL) == SK_ERR_NULL);
        CHECK(sk_equiangular_new(x0, zero, 0, 2, p, &bad) == SK_ERR_DOMAIN);
        CHECK(sk_equiangular_new(x0, xd, 0, 2, on_line, &bad) == SK_ERR_DOMAIN);
        CHECK(sk_equiangular_new(x0, xd, 1, 1, p, &bad) == SK_ERR_DOMAIN);
        CHECK(sk_equiangular_new_f64(x0d, xdd, 0, 2, (sk_vec3_f64){1, 1e-200, 0}, &ed) == SK_ERR_DOMAIN);
        CHECK(isnan(sk_equiangular_sample(NULL, 0.5f)) && isnan(sk_equiangular_pdf_f64(NULL, 1.0)));
        /* A state sk_equiangular_new would not write answers NaN. */
        bad = e;
        bad.state[1] = -1.0f;
        CHECK(isnan(sk_equiangular_sample(&bad, 0.5f)) && isnan(sk_equiangular_pdf(&bad, 1.0f)));
        bad = e;
        bad.state[2] = NAN;
        CHECK(isnan(sk_equiangular_sample(&bad, 0.5f)));
        bad = e;
        bad.state[3] = 3.0f;
        CHECK(isnan(sk_equiangular_pdf(&bad, 1.0f)));
    }
    {
        /* Emission. The exact integral over the constant grid's cells
         * (sigma_t 1, emission coefficient 1, a unit path): 1 - e^-1. */
        sk_majorants single;
        const float ones[8] = {1, 1, 1, 1, 1, 1, 1, 1};
        const double onesd[8] = {1, 1, 1, 1, 1, 1, 1, 1};
        sk_majorants j;
        sk_majorants_f64 jd;
        sk_status s;
        sk_grid g3;
        CHECK(sk_majorants_new(ones, NULL, 2, 2, 2, zero, one, &j) == SK_OK);
        CHECK(sk_majorants_new_f64(onesd, NULL, 2, 2, 2, zerod, oned, &jd) == SK_OK);
        CHECK(sk_majorants_new(ones, NULL, 1, 1, 1, zero, one, &single) == SK_OK);
        a = targs(NULL, NULL, NULL, &m, o, d, 0, 3, 0, &rng);
        a.medium.emission_cells = &j;
        CHECK(sk_emission_track(&a, &tr) == SK_OK && tr.steps == 0 && fabsf(tr.radiance - (1.0f - expf(-1.0f))) < 1e-6f &&
              fabsf(tr.tr - expf(-1.0f)) < 1e-6f);
        ad = targs64(NULL, NULL, NULL, &md, od, dd, 0, 3, 0, &rng);
        ad.medium.emission_cells = &jd;
        CHECK(sk_emission_track_f64(&ad, &trd) == SK_OK && fabs(trd.radiance - (1.0 - exp(-1.0))) < 1e-15);
        a.medium.emission_cells = &single;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN);
        a.medium.emission_cells = &j;
        a.t_min = 3, a.t_max = 1;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN);
        a.t_min = 0, a.t_max = 3, a.d = zero;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN);
        a.d = d, a.medium.majorants = NULL;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_NULL);
        ad.medium.emission_cells = NULL;
        CHECK(sk_emission_track_f64(&ad, &trd) == SK_ERR_NULL && sk_emission_track(&a, NULL) == SK_ERR_NULL);
        /* Tracking through the grid with L_e read from the same grid (1):
         * the majorant is exact, so one collision ends the walk with
         * radiance sigma_a L_e / sigma_maj = 0.5, or none leaves 0. */
        a = targs(&g, NULL, NULL, &m, o, d, 0, 3, 1000, &rng);
        a.medium.emission = &g;
        CHECK(sk_emission_track(&a, &tr) == SK_OK && (tr.radiance == 0.0f || fabsf(tr.radiance - 0.5f) < 1e-6f));
        ad = targs64(&gd, NULL, NULL, &md, od, dd, 0, 3, 1000, &rng);
        ad.medium.emission = &gd;
        CHECK(sk_emission_track_f64(&ad, &trd) == SK_OK);
        a.medium.majorants = NULL;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN); /* a grid needs majorants here */
        a.medium.majorants = &m;
        a.medium.emission = NULL;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN); /* no source */
        a.medium.emission = &g;
        a.medium.emission_fn = le32;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN); /* two sources */
        a.medium.emission_fn = NULL;
        a.rng = &no_fn;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_NULL);
        a.rng = &rng;
        a.d = zero;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN);
        a.d = d;
        a.medium.majorants = &big;
        a.t_max = 1e6f;
        a.budget = 1;
        s = sk_emission_track(&a, &tr);
        CHECK(s == SK_ERR_BUDGET || s == SK_ERR_DOMAIN);
        memset(&g3, 0, sizeof g3);
        a = targs(&g, NULL, NULL, &m, o, d, 0, 3, 1000, &rng);
        a.medium.emission = &g3;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN);
        /* The caller's medium under majorants of 50 (a collision is all
         * but certain, so L_e is read): L_e must be finite and >= 0; an
         * enormous one may overflow the sum, which is DOMAIN. */
        for (i = 0; i < NS; i++) {
            ctxf = FS[i];
            a = targs(NULL, coeff32, &ctxf, &big, o, d, 0, 3, 1000, &rng);
            a.medium.coefficients = coeff32;
            a.medium.ctx = &ctxf;
            a.medium.emission_fn = le32;
            /* coeff32 reads sigma_a from ctx too: keep it in range. */
            s = sk_emission_track(&a, &tr);
            CHECK(FS[i] >= 0.0f && FS[i] <= 49.0f ? s == SK_OK : s == SK_ERR_DOMAIN);
            CHECK(s != SK_OK || (tr.radiance >= 0.0f && isfinite(tr.radiance)));
            ctxd = DS[i];
            ad = targs64(NULL, coeff64, &ctxd, &bigd, od, dd, 0, 3, 1000, &rng);
            ad.medium.emission_fn = le64;
            s = sk_emission_track_f64(&ad, &trd);
            CHECK(DS[i] >= 0.0 && DS[i] <= 49.0 ? s == SK_OK : s == SK_ERR_DOMAIN);
        }
        i = 0;
        a = targs(NULL, coeff32, NULL, &big, o, d, 0, INFINITY, 1000, &rng);
        a.medium.emission_fn = le32;
        CHECK(sk_emission_track(&a, &tr) == SK_OK);
        a.t_min = 2, a.t_max = 1;
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN);
        /* One majorant for a callback medium, a finite segment. */
        a = targs(NULL, coeff32, NULL, NULL, o, d, 0, 3, 1000, &rng);
        a.medium.emission_fn = le32;
        CHECK(sk_emission_track(&a, &tr) == SK_OK && tr.radiance >= 0.0f);
    }
    {
        /* Majorants that may not bound: under majorants of 50 a tentative
         * collision is all but certain. sigma_a = 60 exceeds them (ratio
         * 60.25/50); the default 0.25 + 0.25 does not. */
        sk_status s;
        ctxf = 60.0f;
        a = targs(NULL, coeff32, &ctxf, &big, o, d, 0, 3, 100000, &rng);
        a.flags = SK_TRACK_NONBOUNDING;
        CHECK(sk_ratio_track(&a, &tr) == SK_OK && fabsf(tr.exceeded - 60.25f / 50.0f) < 1e-5f && tr.cell[0] < 2 &&
              tr.cell[1] < 2 && tr.cell[2] < 2);
        CHECK(sk_delta_track(&a, &tr) == SK_OK && fabsf(tr.exceeded - 60.25f / 50.0f) < 1e-5f && tr.event <= 2);
        a.flags = 0; /* the strict estimators refuse */
        CHECK(sk_ratio_track(&a, &tr) == SK_ERR_DOMAIN && sk_delta_track(&a, &tr) == SK_ERR_DOMAIN);
        a = targs(NULL, coeff32, NULL, &big, o, d, 0, 3, 100000, &rng);
        a.flags = SK_TRACK_NONBOUNDING;
        CHECK(sk_ratio_track(&a, &tr) == SK_OK && tr.exceeded == 0.0f && tr.tr >= 0.0f && tr.tr <= 1.0f);
        ad = targs64(NULL, coeff64, NULL, &bigd, od, dd, 0, 3, 100000, &rng);
        ad.flags = SK_TRACK_NONBOUNDING;
        CHECK(sk_delta_track_f64(&ad, &trd) == SK_OK && trd.weight == 1.0 && trd.exceeded == 0.0);
        /* The other estimators refuse the flag, as the header says. */
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN); /* no signed residual tracking */
        CHECK(sk_ray_march(&a, &tr) == SK_ERR_DOMAIN && sk_telescoping_march(&a, &tr) == SK_ERR_DOMAIN);
        CHECK(sk_emission_track(&a, &tr) == SK_ERR_DOMAIN);
        for (i = 0; i < NS; i++) {
            ctxf = FS[i];
            a = targs(NULL, coeff32, &ctxf, &big, o, d, 0, 3, 100000, &rng);
            a.flags = SK_TRACK_NONBOUNDING;
            s = sk_ratio_track(&a, &tr);
            CHECK(FS[i] >= 0.0f && isfinite(FS[i]) ? s == SK_OK || (FS[i] > 1e30f && s == SK_ERR_DOMAIN) : s == SK_ERR_DOMAIN);
            s = sk_delta_track(&a, &tr);
            CHECK(FS[i] >= 0.0f && isfinite(FS[i]) ? s == SK_OK || (FS[i] > 1e30f && s == SK_ERR_DOMAIN) : s == SK_ERR_DOMAIN);
            CHECK(s != SK_OK || isfinite(tr.weight));
            ctxd = DS[i];
            ad = targs64(NULL, coeff64, &ctxd, &bigd, od, dd, 0, 3, 100000, &rng);
            ad.flags = SK_TRACK_NONBOUNDING;
            s = sk_ratio_track_f64(&ad, &trd);
            CHECK(DS[i] >= 0.0 && isfinite(DS[i]) ? s == SK_OK || (DS[i] > 1e300 && s == SK_ERR_DOMAIN) : s == SK_ERR_DOMAIN);
            s = sk_delta_track_f64(&ad, &trd);
            CHECK(DS[i] >= 0.0 && isfinite(DS[i]) ? s == SK_OK || (DS[i] > 1e300 && s == SK_ERR_DOMAIN) : s == SK_ERR_DOMAIN);
            /* A bad t_min is DOMAIN; out untouched then. */
            tr.tr = 7.0f;
            a = targs(NULL, coeff32, NULL, &big, o, d, FS[i], 3, 1000, &rng);
            a.flags = SK_TRACK_NONBOUNDING;
            CHECK(sk_ratio_track(&a, &tr) == (FS[i] >= 0.0f && FS[i] <= 3.0f ? SK_OK : SK_ERR_DOMAIN));
            CHECK(FS[i] >= 0.0f && FS[i] <= 3.0f ? 1 : tr.tr == 7.0f);
        }
        i = 0;
        a = targs(NULL, coeff32, NULL, &big, o, zero, 0, 3, 10, &rng);
        a.flags = SK_TRACK_NONBOUNDING;
        CHECK(sk_delta_track(&a, &tr) == SK_ERR_DOMAIN);
        a.d = d;
        a.t_max = 1e6f;
        a.budget = 1;
        CHECK(sk_delta_track(&a, &tr) == SK_ERR_BUDGET && sk_ratio_track(&a, &tr) == SK_ERR_BUDGET);
    }
    {
        /* Spectral tracking: density majorants (the grid's coefficients sum
         * to 1), three channels, hero 1. */
        float sa[3] = {0.1f, 0.2f, 0.0f}, ss[3] = {0.3f, 0.0f, 0.5f}, w[3], u[3], l[3];
        double sad[3] = {0.1, 0.2, 0.0}, ssd[3] = {0.3, 0.0, 0.5}, wd[3], ud[3], ld[3];
        sk_spectrum sp = {sa, ss, 3, 1, w, u, l};
        sk_spectrum_f64 spd = {sad, ssd, 3, 1, wd, ud, ld};
        int k;
        a = targs(&g, NULL, NULL, &m, o, d, 0, 3, 1000, &rng);
        a.spectrum = &sp;
        ad = targs64(&gd, NULL, NULL, &md, od, dd, 0, 3, 1000, &rng);
        ad.spectrum = &spd;
        CHECK(sk_delta_track(&a, &tr) == SK_OK && sk_ratio_track(&a, &tr) == SK_OK && isnan(tr.tr));
        CHECK(sk_ratio_track_f64(&ad, &trd) == SK_OK && sk_delta_track_f64(&ad, &trd) == SK_OK);
        /* Only delta and ratio tracking, through a grid with majorants. */
        CHECK(sk_residual_ratio_track(&a, &tr) == SK_ERR_DOMAIN && sk_ray_march(&a, &tr) == SK_ERR_DOMAIN);
        a.medium.majorants = NULL;
        CHECK(sk_delta_track(&a, &tr) == SK_ERR_DOMAIN);
        a.medium.majorants = &m;
        /* NULL outputs, aliased outputs; an output over an input. */
        sp.weight = NULL;
        CHECK(sk_delta_track(&a, &tr) == SK_ERR_NULL);
        sp.weight = w, sp.r_u = w;
        CHECK(sk_ratio_track(&a, &tr) == SK_ERR_OVERLAP);
        sp.r_u = u, sp.weight = sa;
        CHECK(sk_delta_track(&a, &tr) == SK_ERR_OVERLAP);
        sp.weight = w;
        spd.r_l = NULL;
        CHECK(sk_ratio_track_f64(&ad, &trd) == SK_ERR_NULL);
        spd.r_l = ld;
        /* Channel counts, hero, coefficients. */
        sp.channels = 0;
        CHECK(sk_ratio_track(&a, &tr) == SK_ERR_SIZE);
        spd.channels = 17;
        CHECK(sk_ratio_track_f64(&ad, &trd) == SK_ERR_SIZE);
        spd.channels = SIZE_MAX;
        CHECK(sk_delta_track_f64(&ad, &trd) == SK_ERR_SIZE);
        sp.channels = 3;
        spd.channels = 3;
        sp.hero = 3;
        CHECK(sk_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        sp.hero = UINT32_MAX;
        CHECK(sk_delta_track(&a, &tr) == SK_ERR_DOMAIN);
        sp.hero = 0;
        for (k = 0; k < NS; k++) {
            float keep = sa[2];
            double keepd = ssd[0];
            i = k;
            sa[2] = FS[k];
            ssd[0] = DS[k];
            w[0] = 7.0f;
            CHECK(sk_ratio_track(&a, &tr) == (isfinite(FS[k]) && FS[k] >= 0.0f ? SK_OK : SK_ERR_DOMAIN));
            CHECK(isfinite(FS[k]) && FS[k] >= 0.0f ? 1 : w[0] == 7.0f);
            /* DBL_MAX: the channel's majorant (sigma_a + sigma_s) sigma_maj
               overflows at the first tentative collision. */
            CHECK(sk_delta_track_f64(&ad, &trd) ==
                  (isfinite(DS[k]) && DS[k] >= 0.0 && DS[k] < DBL_MAX ? SK_OK : SK_ERR_DOMAIN));
            sa[2] = keep;
            ssd[0] = keepd;
            a.t_max = FS[k];
            CHECK(sk_delta_track(&a, &tr) == (FS[k] >= 0.0f ? SK_OK : SK_ERR_DOMAIN));
            a.t_max = 3;
        }
        i = 0;
        /* Majorants over another box. */
        g2 = g;
        sk_grid_set_box(&g2, zero, (sk_vec3){2, 1, 1});
        a.medium.grid = &g2;
        CHECK(sk_ratio_track(&a, &tr) == SK_ERR_DOMAIN);
        /* A spectrum with a callback medium is refused. */
        a = targs(NULL, coeff32, NULL, &m, o, d, 0, 3, 1000, &rng);
        a.spectrum = &sp;
        CHECK(sk_delta_track(&a, &tr) == SK_ERR_DOMAIN);
    }
    /* An escape reports where the ray leaves the box. */
    a = targs(&g, NULL, NULL, &m, o, d, 0, 1.5f, 0, &rng);
    CHECK(sk_delta_track(&a, &tr) == SK_OK && (tr.event != SK_TRACK_ESCAPED || tr.t == 1.5f));
}

static void mie_tables(const sk_mie_f64 *sphere);
static void polydisperse(void);
static void particle_mie(void);
static void particle_measured(void);
static void polarization(void);
static void mixtures(void);

/* Mie: bad input from C, and the BHMIE example through the header. */
static void mie(void) {
    int i;
    static sk_complex_f64 buf[4096];
    sk_complex_f64 m = {1.55, 0.0}, s1, s2;
    sk_mie_f64 sphere, bogus;
    double x = sk_mie_size_parameter_f64(1.05, 0.6328, 1.0);
    size_t len = sk_mie_len_f64(x, m);
    i = 0;
    CHECK(len > 0 && len <= 4096);
    CHECK(sk_mie_new_f64(x, m, buf, len, &sphere) == SK_OK);
    /* Water's index: 1.3345 at 0.55 um (Daimon & Masumura), refused
     * outside [0.182, 1.129] um and for NULL. */
    {
        sk_complex_f64 w = {-1.0, -1.0};
        CHECK(sk_mie_water_index_f64(0.55, &w) == SK_OK && fabs(w.re - 1.3345) < 1e-4 && w.im == 0.0);
        w.re = -1.0;
        CHECK(sk_mie_water_index_f64(0.1, &w) == SK_ERR_DOMAIN && w.re == -1.0);
        CHECK(sk_mie_water_index_f64(NAN, &w) == SK_ERR_DOMAIN);
        CHECK(sk_mie_water_index_f64(2.0, &w) == SK_ERR_DOMAIN);
        CHECK(sk_mie_water_index_f64(0.55, NULL) == SK_ERR_NULL);
    }
    CHECK(fabs(sphere.efficiencies.q_ext - 3.10543) < 5e-6 && fabs(sphere.efficiencies.g - 0.63314) < 5e-6);
    CHECK(sk_mie_amplitudes_f64(&sphere, -1.0, &s1, &s2) == SK_OK);
    CHECK(fabs(4.0 * (s1.re * s1.re + s1.im * s1.im) / (x * x) - sphere.efficiencies.q_back) < 1e-12);
    CHECK(sk_mie_pdf_f64(&sphere, 1.0) > sk_mie_pdf_f64(&sphere, -1.0));
    CHECK(isnan(sk_mie_pdf_f64(&sphere, NAN)) && isnan(sk_mie_pdf_f64(NULL, 0.5)));
    CHECK(sk_mie_new_f64(x, m, NULL, len, &sphere) == SK_ERR_NULL && sk_mie_new_f64(x, m, buf, len, NULL) == SK_ERR_NULL);
    CHECK(sk_mie_new_f64(x, m, buf, len - 1, &sphere) == SK_ERR_SIZE);
    CHECK(sk_mie_new_f64(x, m, buf, SIZE_MAX, &sphere) == SK_ERR_SIZE);
    CHECK(sk_mie_amplitudes_f64(NULL, 0.5, &s1, &s2) == SK_ERR_NULL && sk_mie_amplitudes_f64(&sphere, 0.5, NULL, &s2) == SK_ERR_NULL);
    bogus = sphere;
    bogus.terms = SIZE_MAX;
    CHECK(sk_mie_amplitudes_f64(&bogus, 0.5, &s1, &s2) == SK_ERR_SIZE && isnan(sk_mie_pdf_f64(&bogus, 0.5)));
    for (i = 0; i < NS; i++) {
        double d = DS[i];
        sk_complex_f64 bad_re = {d, 0.0}, bad_im = {1.5, d};
        /* re: |m| >= 1e-100, and not the medium's own index m = 1. */
        int x_ok = d >= 1e-20 && d <= 1e5, re_ok = d >= 1e-100 && d <= 1000.0 && d != 1.0, im_ok = d >= 0.0 && d <= 1000.0;
        CHECK((sk_mie_len_f64(d, m) > 0) == x_ok);
        CHECK((sk_mie_len_f64(1.0, bad_re) > 0) == re_ok);
        CHECK((sk_mie_len_f64(1.0, bad_im) > 0) == im_ok);
        CHECK(sk_mie_new_f64(d, m, buf, 4096, &sphere) == (x_ok ? (sk_mie_len_f64(d, m) <= 4096 ? SK_OK : SK_ERR_SIZE) : SK_ERR_DOMAIN));
        CHECK(sk_mie_new_f64(1.0, bad_im, buf, 4096, &sphere) == (im_ok ? SK_OK : SK_ERR_DOMAIN));
    }
    mie_tables(&sphere);
    polydisperse();
    particle_mie();
    particle_measured();
}

/* Mie over size distributions: cumulus C.1 at 550 nm, bad input. */
static void polydisperse(void) {
    static sk_complex_f64 buf[1 << 12];
    double mu[3] = {1.0, 0.0, -1.0}, phase[3], scratch[3], lo = 7.0, hi = 7.0;
    sk_size_distribution_f64 c1 = {SK_SIZE_MODIFIED_GAMMA, {6.0, 1.5, 1.0}}, bad = c1;
    sk_polydisperse_f64 p;
    sk_mie_averages_f64 a, untouched;
    size_t len;
    int i = 0;
    CHECK(sk_size_distribution_range_f64(&c1, &lo, &hi) == SK_OK && lo > 0.05 && lo < 0.2 && hi > 30.0 && hi < 40.0);
    p.distribution = c1;
    p.r_min = 0.5;
    p.r_max = 10.0;
    p.wavelength = 0.55;
    p.n_medium = 1.0;
    p.m.re = 1.333;
    p.m.im = 1e-8;
    p.intervals = 64;
    len = sk_polydisperse_len_f64(&p);
    CHECK(len > 0 && len <= sizeof buf / sizeof buf[0]);
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, scratch, buf, len, &a) == SK_OK);
    CHECK(a.c_ext > a.c_sca && a.c_sca > 0.0 && a.g > 0.7 && a.g < 0.95 && phase[0] > phase[1]);
    CHECK(fabs(a.c_ext / a.area - 2.0) < 0.2 && a.errors[0] >= 0.0 && a.phase_error >= 0.0);
    untouched = a;
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, scratch, buf, len - 1, &a) == SK_ERR_SIZE);
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, phase + 1, buf, len, &a) == SK_ERR_OVERLAP);
    CHECK(sk_polydisperse_average_f64(NULL, mu, 3, phase, scratch, buf, len, &a) == SK_ERR_NULL);
    CHECK(sk_polydisperse_average_f64(&p, NULL, 3, phase, scratch, buf, len, &a) == SK_ERR_NULL);
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, NULL, scratch, buf, len, &a) == SK_ERR_NULL);
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, NULL, buf, len, &a) == SK_ERR_NULL);
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, scratch, NULL, len, &a) == SK_ERR_NULL);
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, scratch, buf, len, NULL) == SK_ERR_NULL);
    CHECK(sk_polydisperse_average_f64(&p, mu, SIZE_MAX, phase, scratch, buf, len, &a) == SK_ERR_SIZE);
    CHECK(memcmp(&a, &untouched, sizeof a) == 0);
    CHECK(sk_polydisperse_average_f64(&p, NULL, 0, NULL, NULL, buf, len, &a) == SK_OK);
    mu[1] = 1.5;
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, scratch, buf, len, &a) == SK_ERR_DOMAIN);
    mu[1] = 0.0;
    CHECK(sk_size_distribution_range_f64(NULL, &lo, &hi) == SK_ERR_NULL && sk_size_distribution_range_f64(&c1, NULL, &hi) == SK_ERR_NULL);
    CHECK(sk_size_distribution_range_f64(&c1, &lo, NULL) == SK_ERR_NULL && sk_polydisperse_len_f64(NULL) == 0);
    bad.kind = 3;
    CHECK(sk_size_distribution_range_f64(&bad, &lo, &hi) == SK_ERR_DOMAIN);
    p.distribution = bad;
    CHECK(sk_polydisperse_len_f64(&p) == 0 && sk_polydisperse_average_f64(&p, mu, 3, phase, scratch, buf, len, &a) == SK_ERR_DOMAIN);
    /* Junge's power law: no natural range, averages over the given one. */
    bad.kind = SK_SIZE_JUNGE;
    bad.params[0] = 4.0;
    CHECK(sk_size_distribution_range_f64(&bad, &lo, &hi) == SK_ERR_DOMAIN);
    p.distribution = bad;
    CHECK(sk_polydisperse_average_f64(&p, mu, 3, phase, scratch, buf, len, &a) == SK_OK && a.g > 0.5 && a.g < 1.0);
    for (i = 0; i < NS; i++) {
        p.distribution.params[0] = DS[i];
        CHECK((sk_polydisperse_len_f64(&p) == 0) == !(DS[i] > 0.0 && DS[i] <= 10.0));
    }
    p.distribution = c1;
    for (i = 0; i < NS; i++) {
        double d = DS[i];
        sk_polydisperse_f64 q = p;
        bad = c1;
        bad.params[i % 3] = d;
        {
            int ok = i % 3 == 0 ? (d >= 0.0 && d <= 100.0) : i % 3 == 1 ? (d > 0.0 && d < 1e100) : (d > 0.0 && d <= 10.0);
            /* Valid parameters may still put the range beyond doubles. */
            sk_status st = sk_size_distribution_range_f64(&bad, &lo, &hi);
            CHECK(ok ? (st == SK_ERR_DOMAIN || (st == SK_OK && lo > 0.0 && lo < hi)) : st == SK_ERR_DOMAIN);
        }
        q.r_min = d;
        CHECK(sk_polydisperse_len_f64(&q) == 0 || (d > 0.0 && d < p.r_max));
        q = p;
        q.wavelength = d;
        CHECK(sk_polydisperse_len_f64(&q) == 0 || (d > 0.0 && isfinite(d)));
        q = p;
        q.intervals = (size_t)i * 3;
        CHECK((sk_polydisperse_len_f64(&q) == 0) == (i == 0 || (i * 3) % 4 != 0));
    }
}

/* The chooser against tabulated data: a tabulated HG, bad input. */
static void particle_measured(void) {
    static double cosv[1001], pdf[1001], work[4096 + 8];
    sk_phase_f64 hg;
    sk_particle_choice_f64 c, kept;
    int i = 0;
    CHECK(sk_phase_new_hg_f64(0.8, &hg) == SK_OK);
    for (i = 0; i < 1001; i++) {
        cosv[i] = cos(3.14159265358979 * i / 1000.0);
        pdf[i] = sk_phase_pdf_f64(&hg, cosv[i]);
    }
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.02, 0, work, 4096, &c) == SK_OK);
    CHECK(c.model == SK_PARTICLE_HG && c.within_tolerance == 1 && c.distance <= 0.02 && isnan(c.x) && isnan(c.m.re));
    CHECK(isnan(c.distances[4]) && fabs(sk_phase_mean_cosine_f64(&c.phase) - 0.8) < 5e-3);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 1e-9, 1, work, 4096, &c) == SK_OK);
    CHECK(c.model == SK_PARTICLE_MIE_TABLE && c.distance == 0.0 && isnan(sk_phase_pdf_f64(&c.phase, 0.5)));
    kept = c;
    CHECK(sk_phase_new_particle_measured_f64(NULL, pdf, 1001, 0.1, 0, work, 4096, &c) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle_measured_f64(cosv, NULL, 1001, 0.1, 0, work, 4096, &c) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, NULL, 4096, &c) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, work, 4096, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1, 0.1, 0, work, 4096, &c) == SK_ERR_SIZE);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 0, 0.1, 0, work, 4096, &c) == SK_ERR_SIZE);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, SIZE_MAX, 0.1, 0, work, 4096, &c) == SK_ERR_SIZE);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, work, 4095, &c) == SK_ERR_SIZE);
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, work, SIZE_MAX, &c) == SK_ERR_SIZE);
    /* work overlapping the data. */
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, pdf + 500, 4096, &c) == SK_ERR_OVERLAP);
    CHECK(sk_phase_new_particle_measured_f64(work + 8, pdf, 10, 0.1, 0, work, 4096, &c) == SK_ERR_OVERLAP);
    pdf[3] = -1.0;
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, work, 4096, &c) == SK_ERR_DOMAIN);
    pdf[3] = NAN;
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, work, 4096, &c) == SK_ERR_DOMAIN);
    pdf[3] = sk_phase_pdf_f64(&hg, cosv[3]);
    cosv[3] = cosv[5];
    CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 1001, 0.1, 0, work, 4096, &c) == SK_ERR_DOMAIN);
    cosv[3] = cos(3.14159265358979 * 3 / 1000.0);
    CHECK(c.model == kept.model && c.distance == kept.distance && c.within_tolerance == kept.within_tolerance);
    for (i = 0; i < NS; i++) {
        double d = DS[i];
        CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 3, d, 1, work, 4096, &c) == (d > 0.0 && d < 1.0 ? SK_OK : SK_ERR_DOMAIN));
        cosv[0] = d;
        CHECK(sk_phase_new_particle_measured_f64(cosv, pdf, 3, 0.5, 1, work, 4096, &c) ==
              (d >= -1.0 && d <= 1.0 && d > cosv[1] ? SK_OK : SK_ERR_DOMAIN));
        cosv[0] = 1.0;
    }
}

/* The honest chooser against Mie: water at 550 nm, bad input. */
static void particle_mie(void) {
    static sk_complex_f64 buf[1024];
    static double work[4096];
    sk_complex_f64 water = {0.0, 0.0}, glass = {1.5, 0.0};
    sk_particle_choice_f64 c, kept;
    size_t len = sk_particle_mie_len_f64(0.01, 0.55, water);
    int i = 0;
    CHECK(len > 0 && len <= 1024 && sk_particle_mie_len_f64(1.0, 2.0, water) == 0);
    CHECK(sk_particle_mie_len_f64(1.0, 2.0, glass) > 0);
    CHECK(sk_phase_new_particle_mie_f64(0.01, 0.55, water, 0.01, 1, buf, 1024, work, 4096, &c) == SK_OK);
    CHECK(c.model == SK_PARTICLE_RAYLEIGH && c.within_tolerance == 1 && c.distance < 0.01 && fabs(c.m.re - 1.3345) < 1e-3);
    CHECK(fabs(sk_phase_pdf_f64(&c.phase, 1.0) - 3.0 / (8.0 * 3.14159265358979)) < 1e-12);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, buf, 1024, work, 4096, &c) == SK_OK);
    CHECK(c.model == SK_PARTICLE_MIE_TABLE && c.distance == 0.0 && isnan(sk_phase_pdf_f64(&c.phase, 0.5)));
    /* With a table, two-lobe HG, Fournier-Forand and Rayleigh + HG are not
     * fitted. */
    CHECK(isnan(c.distances[5]) && isnan(c.distances[6]) && isnan(c.distances[7]));
    /* 4 um without a table: two-lobe HG is the closest (none within 0.1),
     * never farther than one HG, and samples like a phase. */
    CHECK(sk_phase_new_particle_mie_f64(4.0, 0.55, water, 0.1, 0, buf, 1024, work, 4096, &c) == SK_OK);
    CHECK(c.model == SK_PARTICLE_TWO_LOBE_HG && c.within_tolerance == 0 && c.distance == c.distances[5] &&
          c.distances[5] <= c.distances[1] && c.distances[6] > 0.0 && c.distances[6] < 1.0);
    CHECK(fabs(sk_phase_sample_cos_f64(&c.phase, 0.5)) <= 1.0 && sk_phase_pdf_f64(&c.phase, 0.5) > 0.0);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 0, buf, 1024, work, 4096, &c) == SK_OK);
    CHECK(c.within_tolerance == 0 && c.model != SK_PARTICLE_MIE_TABLE && sk_phase_pdf_f64(&c.phase, 0.5) > 0.0);
    kept = c;
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, NULL, 1024, work, 4096, &c) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, buf, 1024, NULL, 4096, &c) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, buf, 1024, work, 4096, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, buf, 3, work, 4096, &c) == SK_ERR_SIZE);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, buf, 1024, work, 4095, &c) == SK_ERR_SIZE);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, buf, SIZE_MAX, work, 4096, &c) == SK_ERR_SIZE);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 0.55, water, 0.01, 1, (sk_complex_f64 *)work, 100, work, 4096, &c) == SK_ERR_OVERLAP);
    CHECK(sk_phase_new_particle_mie_f64(1.0, 2.0, water, 0.01, 1, buf, 1024, work, 4096, &c) == SK_ERR_DOMAIN);
    /* Unchanged on error (the fields, not the phase's opaque bytes, whose
     * enum padding is not defined). */
    CHECK(c.model == kept.model && c.within_tolerance == kept.within_tolerance && c.distance == kept.distance &&
          c.x == kept.x && memcmp(c.distances, kept.distances, sizeof c.distances) == 0);
    for (i = 0; i < NS; i++) {
        double d = DS[i];
        CHECK(sk_phase_new_particle_mie_f64(d, 0.55, water, 0.1, 1, buf, 1024, work, 4096, &c) ==
              (d > 0.0 && sk_particle_mie_len_f64(d, 0.55, water) > 0 ? (sk_particle_mie_len_f64(d, 0.55, water) <= 1024 ? SK_OK : SK_ERR_SIZE) : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_particle_mie_f64(0.1, 0.55, water, d, 1, buf, 1024, work, 4096, &c) == (d > 0.0 && d < 1.0 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_particle_mie_f64(0.1, d, water, 0.1, 1, buf, 1024, work, 4096, &c) == SK_ERR_DOMAIN);
    }
}

/* Mie tables: sizes, tabulation into sk_table_new_measured_f64, bad input. */
static void mie_tables(const sk_mie_f64 *sphere) {
    static double c[256], p[256], tb[2 * 513];
    size_t angles = 7, intervals = 7;
    int i = 0;
    sk_table_f64 t;
    CHECK(sk_mie_table_len_f64(100.0, &angles, &intervals) == SK_OK && angles == 4000 && intervals == 16384);
    CHECK(sk_mie_table_len_f64(NAN, &angles, &intervals) == SK_ERR_DOMAIN && angles == 4000);
    CHECK(sk_mie_table_len_f64(0.0, &angles, &intervals) == SK_ERR_DOMAIN);
    CHECK(sk_mie_table_len_f64(1.0, NULL, &intervals) == SK_ERR_NULL && sk_mie_table_len_f64(1.0, &angles, NULL) == SK_ERR_NULL);
    CHECK(sk_mie_tabulate_f64(sphere, c, p, 256) == SK_OK && c[0] == 1.0 && c[255] == -1.0);
    for (i = 1; i < 256; i++) CHECK(c[i] < c[i - 1] && p[i] > 0.0);
    i = 0;
    CHECK(sk_table_new_measured_f64(c, p, 256, tb, 2 * 513, 512, &t) == SK_OK);
    CHECK(sk_table_sample_cos_f64(&t, 0.999) > 0.9 * sk_table_sample_cos_f64(&t, 1.0));
    CHECK(sk_mie_tabulate_f64(NULL, c, p, 256) == SK_ERR_NULL && sk_mie_tabulate_f64(sphere, NULL, p, 256) == SK_ERR_NULL);
    CHECK(sk_mie_tabulate_f64(sphere, c, NULL, 256) == SK_ERR_NULL);
    CHECK(sk_mie_tabulate_f64(sphere, c, p, 1) == SK_ERR_SIZE && sk_mie_tabulate_f64(sphere, c, p, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(sk_mie_tabulate_f64(sphere, c, c + 1, 100) == SK_ERR_OVERLAP);
}

/* The verbs every phase-like handle speaks: each batch is bit for bit its
 * scalar call, in place too; bad uniforms, overlaps, NULLs and sizes give
 * their statuses with nothing written. One adapter per handle, float. */
typedef struct {
    const char *name;
    const void *h;
    float (*cos)(const void *h, float u);
    sk_status (*cos_n)(const void *h, const float *u, float *out, size_t n);
    sk_vec3 (*dir)(const void *h, sk_vec3 w, float u1, float u2, float *pdf);
    sk_status (*dir_n)(const void *h, const float *wx, const float *wy, const float *wz, const float *u1, const float *u2,
                       float *ox, float *oy, float *oz, float *pdf, size_t n);
} verbs32;

static float tab_cos(const void *h, float u) { return sk_table_sample_cos((const sk_table *)h, u); }
static sk_status tab_cos_n(const void *h, const float *u, float *o, size_t n) { return sk_table_sample_cos_n((const sk_table *)h, u, o, n); }
static sk_vec3 tab_dir(const void *h, sk_vec3 w, float a, float b, float *pdf) { return sk_table_sample_dir((const sk_table *)h, w, a, b, pdf); }
static sk_status tab_dir_n(const void *h, const float *wx, const float *wy, const float *wz, const float *a, const float *b, float *ox,
                           float *oy, float *oz, float *pdf, size_t n) {
    return sk_table_sample_dir_n((const sk_table *)h, wx, wy, wz, a, b, ox, oy, oz, pdf, n);
}
static float t2_cos(const void *h, float u) { return sk_table2d_sample_cos((const sk_table2d *)h, 0.37f, u); }
static sk_status t2_cos_n(const void *h, const float *u, float *o, size_t n) { return sk_table2d_sample_cos_n((const sk_table2d *)h, 0.37f, u, o, n); }
static sk_vec3 t2_dir(const void *h, sk_vec3 w, float a, float b, float *pdf) { return sk_table2d_sample_dir((const sk_table2d *)h, 0.37f, w, a, b, pdf); }
static sk_status t2_dir_n(const void *h, const float *wx, const float *wy, const float *wz, const float *a, const float *b, float *ox,
                          float *oy, float *oz, float *pdf, size_t n) {
    return sk_table2d_sample_dir_n((const sk_table2d *)h, 0.37f, wx, wy, wz, a, b, ox, oy, oz, pdf, n);
}
static float lg_cos(const void *h, float u) { return sk_legendre_sample_cos((const sk_legendre *)h, u); }
static sk_status lg_cos_n(const void *h, const float *u, float *o, size_t n) { return sk_legendre_sample_cos_n((const sk_legendre *)h, u, o, n); }
static sk_vec3 lg_dir(const void *h, sk_vec3 w, float a, float b, float *pdf) { return sk_legendre_sample_dir((const sk_legendre *)h, w, a, b, pdf); }
static sk_status lg_dir_n(const void *h, const float *wx, const float *wy, const float *wz, const float *a, const float *b, float *ox,
                          float *oy, float *oz, float *pdf, size_t n) {
    return sk_legendre_sample_dir_n((const sk_legendre *)h, wx, wy, wz, a, b, ox, oy, oz, pdf, n);
}
static float mx_cos(const void *h, float u) { return sk_mixture_sample_cos((const sk_mixture *)h, u); }
static sk_status mx_cos_n(const void *h, const float *u, float *o, size_t n) { return sk_mixture_sample_cos_n((const sk_mixture *)h, u, o, n); }
static sk_vec3 mx_dir(const void *h, sk_vec3 w, float a, float b, float *pdf) { return sk_mixture_sample_dir((const sk_mixture *)h, w, a, b, pdf); }
static sk_status mx_dir_n(const void *h, const float *wx, const float *wy, const float *wz, const float *a, const float *b, float *ox,
                          float *oy, float *oz, float *pdf, size_t n) {
    return sk_mixture_sample_dir_n((const sk_mixture *)h, wx, wy, wz, a, b, ox, oy, oz, pdf, n);
}

static int same_bits(float a, float b) { return memcmp(&a, &b, sizeof a) == 0; }

static void check_verbs(const verbs32 *v, const void *zeroed) {
    enum { N = 9 };
    const float us[N] = {0.0f, 1e-7f, 0.1f, 0.25f, 0.5f, 0.7f, 0.9f, 0.999f, 1.0f};
    float u[N], c[N], wx[N], wy[N], wz[N], ox[N], oy[N], oz[N], pdf[N], big[N + 1];
    int i, k;
    for (k = 0; k < N; k++) {
        float s = sinf(0.7f * k + 0.3f), t = cosf(0.7f * k + 0.3f);
        wx[k] = s * 0.6f, wy[k] = s * 0.8f, wz[k] = t;
        u[k] = us[k];
    }
    i = 0;
    /* Bit for bit the scalar calls; in place too. */
    CHECK(v->cos_n(v->h, u, c, N) == SK_OK);
    for (k = 0; k < N; k++) CHECK(same_bits(c[k], v->cos(v->h, u[k])));
    memcpy(big, u, sizeof u);
    CHECK(v->cos_n(v->h, big, big, N) == SK_OK && memcmp(big, c, sizeof c) == 0);
    CHECK(v->dir_n(v->h, wx, wy, wz, u, us, ox, oy, oz, pdf, N) == SK_OK);
    for (k = 0; k < N; k++) {
        float p;
        sk_vec3 w = {wx[k], wy[k], wz[k]}, d = v->dir(v->h, w, u[k], us[k], &p);
        CHECK(same_bits(d.x, ox[k]) && same_bits(d.y, oy[k]) && same_bits(d.z, oz[k]) && same_bits(p, pdf[k]));
    }
    /* Bad uniforms: DOMAIN, nothing written. */
    for (i = 0; i < NS; i++) {
        int ok = FS[i] >= 0.0f && FS[i] <= 1.0f;
        memcpy(big, u, sizeof u);
        big[3] = FS[i];
        c[3] = 7.0f;
        CHECK(v->cos_n(v->h, big, c, N) == (ok ? SK_OK : SK_ERR_DOMAIN) && (ok || c[3] == 7.0f));
        ox[0] = 7.0f;
        CHECK(v->dir_n(v->h, wx, wy, wz, u, big, ox, oy, oz, NULL, N) == (ok ? SK_OK : SK_ERR_DOMAIN) && (ok || ox[0] == 7.0f));
    }
    i = 0;
    /* Overlaps, NULLs, sizes, never-built handles. */
    memcpy(big, u, sizeof u);
    CHECK(v->cos_n(v->h, big, big + 1, 4) == SK_ERR_OVERLAP);
    CHECK(v->dir_n(v->h, wx, wy, wz, u, u, ox, ox, oz, pdf, N) == SK_ERR_OVERLAP);
    CHECK(v->dir_n(v->h, big, wy, wz, u, u, big + 1, oy, oz, pdf, 4) == SK_ERR_OVERLAP);
    CHECK(v->cos_n(v->h, NULL, c, N) == SK_ERR_NULL && v->cos_n(v->h, u, NULL, N) == SK_ERR_NULL);
    CHECK(v->cos_n(v->h, NULL, NULL, 0) == SK_OK && v->cos_n(v->h, u, c, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(v->dir_n(v->h, NULL, wy, wz, u, u, ox, oy, oz, pdf, N) == SK_ERR_NULL);
    CHECK(v->dir_n(v->h, wx, wy, wz, u, u, ox, oy, NULL, pdf, N) == SK_ERR_NULL);
    CHECK(v->dir_n(v->h, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL, 0) == SK_OK);
    CHECK(v->dir_n(v->h, wx, wy, wz, u, u, ox, oy, oz, pdf, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(v->cos_n(NULL, u, c, N) == SK_ERR_NULL && v->dir_n(NULL, wx, wy, wz, u, u, ox, oy, oz, pdf, N) == SK_ERR_NULL);
    {
        sk_status a = v->cos_n(zeroed, u, c, N), b = v->dir_n(zeroed, wx, wy, wz, u, u, ox, oy, oz, pdf, N);
        CHECK((a == SK_ERR_DOMAIN || a == SK_ERR_SIZE) && a == b);
        CHECK(isnan(v->cos(zeroed, 0.5f)) && isnan(v->dir(zeroed, (sk_vec3){0, 0, 1}, 0.5f, 0.5f, pdf).x) && isnan(pdf[0]));
    }
    if (failed) printf("  (in the verbs of %s)\n", v->name);
}

/* The generic constructor: the inverse of sk_phase_get_params for every
 * model, its statuses, and Schlick (which has no named constructor). */
static void phase_new_generic(void) {
    sk_phase p, q, named[9];
    sk_phase_f64 pd;
    sk_phase_params a, b;
    sk_phase_params_f64 ad;
    const float k = 0.6f, two[2] = {0.5f, 0.3f};
    const double kd = 0.6;
    int i = 0, m, models = 8;
    sk_phase_new_isotropic(&named[0]);
    sk_phase_new_rayleigh(&named[1]);
    sk_phase_new_rayleigh_depolarized(0.03f, &named[2]);
    sk_phase_new_hg(0.7f, &named[3]);
    sk_phase_new_draine(0.5f, 2.0f, &named[4]);
    sk_phase_new_fog_diameter(2.0f, &named[5]);
    sk_phase_new_gegenbauer(0.4f, 0.6f, &named[6]);
    sk_phase_new_fournier_forand(1.1f, 4.0f, &named[7]);
    CHECK(sk_phase_new(SK_PHASE_SCHLICK, &k, 1, &named[models++]) == SK_OK);
    for (m = 0; m < models; m++) {
        /* Rebuilt from what it reports: the same model, the same answers. */
        CHECK(sk_phase_get_params(&named[m], &a) == SK_OK && a.model == (uint32_t)(m + 1));
        CHECK(sk_phase_new(a.model, a.params, a.count, &q) == SK_OK && sk_phase_get_params(&q, &b) == SK_OK);
        CHECK(b.model == a.model && b.count == a.count && memcmp(a.params, b.params, sizeof a.params) == 0);
        CHECK(sk_phase_sample_cos(&q, 0.3f) == sk_phase_sample_cos(&named[m], 0.3f));
        /* One parameter too many or too few. */
        CHECK(sk_phase_new(a.model, a.params, a.count + 1, &q) == SK_ERR_SIZE);
        CHECK(a.count == 0 || sk_phase_new(a.model, a.params, a.count - 1, &q) == SK_ERR_SIZE);
    }
    CHECK(sk_phase_new_f64(SK_PHASE_HG, &kd, 1, &pd) == SK_OK && sk_phase_get_params_f64(&pd, &ad) == SK_OK);
    CHECK(ad.model == SK_PHASE_HG && ad.count == 1 && ad.params[0] == 0.6);
    CHECK(fabs(sk_phase_cdf_f64(&pd, sk_phase_sample_cos_f64(&pd, 0.3)) - 0.3) < 1e-15);
    CHECK(sk_phase_new_f64(SK_PHASE_SCHLICK, &kd, 1, &pd) == SK_OK && fabs(sk_phase_cdf_f64(&pd, sk_phase_sample_cos_f64(&pd, 0.3)) - 0.3) < 1e-15);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double d = DS[i];
        CHECK(sk_phase_new(SK_PHASE_HG, &f, 1, &p) == (f > -1.0f && f < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new(SK_PHASE_SCHLICK, &f, 1, &p) == (f > -1.0f && f < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_phase_new_f64(SK_PHASE_HG, &d, 1, &pd) == (d > -1.0 && d < 1.0 ? SK_OK : SK_ERR_DOMAIN));
        {
            const float gp[2] = {f, 1.0f};
            CHECK(sk_phase_new(SK_PHASE_DRAINE, gp, 2, &p) == (f > -1.0f && f < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        }
    }
    i = 0;
    CHECK(sk_phase_new(SK_PHASE_HG, &k, 1, NULL) == SK_ERR_NULL && sk_phase_new(SK_PHASE_HG, NULL, 1, &p) == SK_ERR_NULL);
    CHECK(sk_phase_new_f64(SK_PHASE_HG, &kd, 1, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new(SK_PHASE_ISOTROPIC, NULL, 0, &p) == SK_OK);
    CHECK(sk_phase_new(0, &k, 1, &p) == SK_ERR_METHOD && sk_phase_new(99, &k, 1, &p) == SK_ERR_METHOD);
    CHECK(sk_phase_new_f64(UINT32_MAX, &kd, 1, &pd) == SK_ERR_METHOD);
    CHECK(sk_phase_new(SK_PHASE_DRAINE, two, SIZE_MAX, &p) == SK_ERR_SIZE);
    CHECK(sk_phase_new(SK_PHASE_HG, two, 2, &p) == SK_ERR_SIZE);
}

static void same_verbs(void) {
    static float tbuf[2 * 65], t2buf[2 * 65 * 3];
    static double tbufd[2 * 65], t2bufd[2 * 65 * 3];
    const float chi[3] = {1.0f, 0.3f, 0.1f};
    const double chid[3] = {1.0, 0.3, 0.1};
    sk_phase hg, three[3], ray;
    sk_phase_f64 hgd, threed[3];
    sk_table t, tz;
    sk_table_f64 td;
    sk_table2d t2, t2z;
    sk_table2d_f64 t2d;
    sk_legendre lg, lgz;
    sk_legendre_f64 lgd;
    sk_mixture m, mz;
    sk_mixture_f64 md;
    float mom[6];
    double momd[6];
    int i = 0, k;
    sk_phase_new_hg(0.6f, &hg);
    sk_phase_new_rayleigh(&ray);
    sk_phase_new_hg_f64(0.6, &hgd);
    for (k = 0; k < 3; k++) {
        sk_phase_new_hg(0.2f + 0.3f * k, &three[k]);
        sk_phase_new_hg_f64(0.2 + 0.3 * k, &threed[k]);
    }
    CHECK(sk_table_new_inverse(&hg, tbuf, 2 * 65, 64, &t) == SK_OK);
    CHECK(sk_table_new_inverse_f64(&hgd, tbufd, 2 * 65, 64, &td) == SK_OK);
    CHECK(sk_table2d_new_inverse(three, 3, t2buf, 2 * 65 * 3, 64, 0.0f, 0.5f, &t2) == SK_OK);
    CHECK(sk_table2d_new_inverse_f64(threed, 3, t2bufd, 2 * 65 * 3, 64, 0.0, 0.5, &t2d) == SK_OK);
    CHECK(sk_legendre_new(chi, 3, &lg) == SK_OK && sk_legendre_new_f64(chid, 3, &lgd) == SK_OK);
    {
        sk_mixture_part parts[2] = {{&ray, NULL, 0.5f}, {NULL, &t, 0.5f}};
        sk_mixture_part_f64 partsd[2] = {{&hgd, NULL, 0.5}, {NULL, &td, 0.5}};
        CHECK(sk_mixture_new(parts, 2, &m) == SK_OK && sk_mixture_new_f64(partsd, 2, &md) == SK_OK);
    }
    memset(&tz, 0, sizeof tz);
    memset(&t2z, 0, sizeof t2z);
    memset(&lgz, 0, sizeof lgz);
    memset(&mz, 0, sizeof mz);
    {
        const verbs32 all[4] = {{"sk_table", &t, tab_cos, tab_cos_n, tab_dir, tab_dir_n},
                                {"sk_table2d", &t2, t2_cos, t2_cos_n, t2_dir, t2_dir_n},
                                {"sk_legendre", &lg, lg_cos, lg_cos_n, lg_dir, lg_dir_n},
                                {"sk_mixture", &m, mx_cos, mx_cos_n, mx_dir, mx_dir_n}};
        const void *zeroed[4] = {&tz, &t2z, &lgz, &mz};
        for (k = 0; k < 4; k++) check_verbs(&all[k], zeroed[k]);
    }
    /* CDF and mean cosine agree with the samplers; moments: chi_0 = 1 and
     * chi_1 the mean cosine. */
    CHECK(fabsf(sk_table_cdf(&t, sk_table_sample_cos(&t, 0.3f)) - 0.3f) < 1e-5f);
    CHECK(fabs(sk_table_cdf_f64(&td, sk_table_sample_cos_f64(&td, 0.3)) - 0.3) < 1e-10);
    CHECK(fabsf(sk_table2d_cdf(&t2, 0.37f, sk_table2d_sample_cos(&t2, 0.37f, 0.6f)) - 0.6f) < 1e-5f);
    CHECK(fabs(sk_table2d_cdf_f64(&t2d, 0.37, sk_table2d_sample_cos_f64(&t2d, 0.37, 0.6)) - 0.6) < 1e-10);
    CHECK(fabsf(sk_table_mean_cosine(&t) - 0.6f) < 1e-3f && fabs(sk_table_mean_cosine_f64(&td) - 0.6) < 1e-3);
    CHECK(fabsf(sk_table2d_mean_cosine(&t2, 0.5f) - 0.5f) < 1e-3f && fabs(sk_table2d_mean_cosine_f64(&t2d, 0.0) - 0.2) < 1e-3);
    CHECK(sk_legendre_mean_cosine(&lg) == 0.3f && sk_legendre_mean_cosine_f64(&lgd) == 0.3);
    CHECK(sk_table_legendre_moments(&t, mom, 6) == SK_OK && fabsf(mom[0] - 1.0f) < 1e-6f && fabsf(mom[1] - sk_table_mean_cosine(&t)) < 1e-4f);
    CHECK(sk_table_legendre_moments_f64(&td, momd, 6) == SK_OK && fabs(momd[2] - 0.36) < 1e-3);
    CHECK(sk_table2d_legendre_moments(&t2, 0.5f, mom, 6) == SK_OK && fabsf(mom[1] - 0.5f) < 1e-3f);
    CHECK(sk_table2d_legendre_moments_f64(&t2d, 1.0, momd, 6) == SK_OK && fabs(momd[1] - 0.8) < 1e-3);
    CHECK(sk_legendre_legendre_moments(&lg, mom, 6) == SK_OK && mom[1] == 0.3f && mom[2] == 0.1f && mom[3] == 0.0f && mom[5] == 0.0f);
    CHECK(sk_legendre_legendre_moments_f64(&lgd, momd, 2) == SK_OK && momd[1] == 0.3);
    {
        double pd;
        sk_vec3_f64 w = {0, 0, 1}, dd = sk_legendre_sample_dir_f64(&lgd, w, 0.4, 0.6, &pd);
        CHECK(fabs(pd - sk_legendre_pdf_f64(&lgd, dd.z)) < 1e-12 * pd);
    }
    for (i = 0; i < NS; i++) {
        CHECK(isnan(FS[i]) == isnan(sk_table_cdf(&t, FS[i])) && isnan(DS[i]) == isnan(sk_table2d_cdf_f64(&t2d, 0.5, DS[i])));
        CHECK(isnan(FS[i]) == isnan(sk_table2d_mean_cosine(&t2, FS[i])));
    }
    i = 0;
    /* NULL and never-built handles; NULL out. */
    CHECK(isnan(sk_table_cdf(NULL, 0.0f)) && isnan(sk_table_mean_cosine(&tz)) && isnan(sk_table_mean_cosine_f64(NULL)));
    CHECK(isnan(sk_table2d_cdf(&t2z, 0.5f, 0.0f)) && isnan(sk_table2d_mean_cosine_f64(NULL, 0.5)));
    CHECK(isnan(sk_legendre_mean_cosine(&lgz)) && isnan(sk_legendre_mean_cosine_f64(NULL)));
    CHECK(sk_table_legendre_moments(NULL, mom, 6) == SK_ERR_NULL && sk_table_legendre_moments(&t, NULL, 6) == SK_ERR_NULL);
    CHECK(sk_table_legendre_moments(&tz, mom, 6) == SK_ERR_SIZE && sk_table_legendre_moments(&t, mom, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(sk_table2d_legendre_moments(&t2z, 0.5f, mom, 6) == SK_ERR_SIZE && sk_table2d_legendre_moments_f64(NULL, 0.5, momd, 6) == SK_ERR_NULL);
    CHECK(sk_legendre_legendre_moments(&lgz, mom, 6) == SK_ERR_DOMAIN && sk_legendre_legendre_moments_f64(&lgd, NULL, 6) == SK_ERR_NULL);
    CHECK(sk_legendre_legendre_moments(&lg, mom, 0) == SK_OK && sk_table_legendre_moments_f64(&td, NULL, 0) == SK_OK);
    /* The double batches: bit for bit too. */
    {
        const double u[4] = {0.0, 0.3, 0.8, 1.0}, wx[4] = {0, 0, 1, 0}, wy[4] = {0, 1, 0, 0}, wz[4] = {1, 0, 0, -1};
        double c[4], ox[4], oy[4], oz[4], pd[4];
        CHECK(sk_table_sample_cos_n_f64(&td, u, c, 4) == SK_OK && c[1] == sk_table_sample_cos_f64(&td, 0.3));
        CHECK(sk_table2d_sample_cos_n_f64(&t2d, 0.2, u, c, 4) == SK_OK && c[2] == sk_table2d_sample_cos_f64(&t2d, 0.2, 0.8));
        CHECK(sk_legendre_sample_cos_n_f64(&lgd, u, c, 4) == SK_OK && c[2] == sk_legendre_sample_cos_f64(&lgd, 0.8));
        CHECK(sk_table_sample_dir_n_f64(&td, wx, wy, wz, u, u, ox, oy, oz, pd, 4) == SK_OK);
        CHECK(sk_table2d_sample_dir_n_f64(&t2d, 0.2, wx, wy, wz, u, u, ox, oy, oz, NULL, 4) == SK_OK);
        CHECK(sk_legendre_sample_dir_n_f64(&lgd, wx, wy, wz, u, u, ox, oy, oz, pd, 4) == SK_OK);
        CHECK(sk_mixture_sample_dir_n_f64(&md, wx, wy, wz, u, u, ox, oy, oz, pd, 4) == SK_OK);
        {
            double p;
            sk_vec3_f64 w = {0, 1, 0}, d = sk_mixture_sample_dir_f64(&md, w, 0.3, 0.3, &p);
            CHECK(d.x == ox[1] && d.y == oy[1] && d.z == oz[1] && p == pd[1]);
        }
        CHECK(sk_table_sample_dir_n_f64(NULL, wx, wy, wz, u, u, ox, oy, oz, pd, 4) == SK_ERR_NULL);
        CHECK(sk_legendre_sample_cos_n_f64(&lgd, u, c, SIZE_MAX) == SK_ERR_SIZE);
    }
}

int main(void) {
    cube_roots_and_version();
    basis();
    phase_constructors();
    phase_queries();
    phase_params();
    phase_cos_inline();
    direction_batches();
    rayleigh_functions();
    tables();
    tables2d();
    albedo_curves();
    surfaces();
    media();
    majorants();
    escapes();
    long_marches();
    mie();
    polarization();
    mixtures();
    same_verbs();
    phase_new_generic();
    printf("matrix: %d checks passed, %d failed\n", passed, failed);
    return failed;
}

/* Stokes vectors and polarised Rayleigh: construction, every query with
 * valid input and with each kind of bad input, in both precisions. */
static void polarization(void) {
    sk_rayleigh_polarized p, zero;
    sk_rayleigh_polarized_f64 pd, zerod;
    const sk_vec3 k = {0, 0, 1}, e1 = {1, 0, 0}, w = {0.6f, 0, 0.8f}, r = {0.8f, 0, -0.6f};
    const sk_vec3_f64 kd = {0, 0, 1}, e1d = {1, 0, 0}, wd = {0.6, 0, 0.8}, rd = {0.8, 0, -0.6};
    sk_stokes s = {1.0f, 0.5f, 0.3f, 0.2f, {1, 0, 0}}, o, kept, bad_s;
    sk_stokes_f64 sd = {1.0, 0.5, 0.3, 0.2, {1, 0, 0}}, od, keptd, bad_sd;
    sk_stokes_sample x, keptx;
    sk_stokes_sample_f64 xd, keptxd;
    sk_rayleigh_mueller m;
    sk_rayleigh_mueller_f64 md;
    sk_vec3 v;
    int i = 0, j;
    memset(&zero, 0, sizeof zero);
    memset(&zerod, 0, sizeof zerod);
    CHECK(sk_rayleigh_polarized_new(0.028f, &p) == SK_OK && sk_rayleigh_polarized_new_f64(0.028, &pd) == SK_OK);
    CHECK(sk_rayleigh_polarized_new(0.5f, NULL) == SK_ERR_NULL && sk_rayleigh_polarized_new_f64(0.5, NULL) == SK_ERR_NULL);
    CHECK(sk_rayleigh_polarized_new(1.0f, &zero) == SK_ERR_DOMAIN && sk_rayleigh_polarized_new_f64(-0.1, &zerod) == SK_ERR_DOMAIN);
    for (i = 0; i < NS; i++) {
        sk_rayleigh_polarized t;
        sk_rayleigh_polarized_f64 td;
        CHECK(sk_rayleigh_polarized_new(FS[i], &t) == (FS[i] >= 0.0f && FS[i] < 1.0f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_rayleigh_polarized_new_f64(DS[i], &td) == (DS[i] >= 0.0 && DS[i] < 1.0 ? SK_OK : SK_ERR_DOMAIN));
    }
    /* The matrix: P11 at 90 degrees is 1 - Delta/4; NaN unconstructed. */
    m = sk_rayleigh_polarized_mueller(&p, 0.0f);
    md = sk_rayleigh_polarized_mueller_f64(&pd, 0.0);
    CHECK(m.p11 > 0.7f && m.p11 < 0.8f && m.p12 < 0.0f && m.p33 == 0.0f && fabs(md.p11 + md.p12 - 0.75 * 0.0) > 0.0);
    CHECK(isnan(sk_rayleigh_polarized_mueller(&zero, 0.5f).p11) && isnan(sk_rayleigh_polarized_mueller_f64(NULL, 0.5).p44));
    /* eval, pdf, both samplers with valid input. */
    CHECK(sk_rayleigh_polarized_eval(&p, k, &s, w, r, &o) == SK_OK && o.i > 0.0f && o.q * o.q + o.u * o.u + o.v * o.v <= o.i * o.i * 1.0001f);
    CHECK(sk_rayleigh_polarized_eval_f64(&pd, kd, &sd, wd, rd, &od) == SK_OK && fabs(od.i - sk_rayleigh_polarized_pdf_f64(&pd, kd, &sd, wd)) < 1e-15);
    CHECK(fabsf(sk_rayleigh_polarized_pdf(&p, k, &s, w) - o.i) < 1e-6f);
    CHECK(sk_rayleigh_polarized_sample(&p, k, &s, 0.3f, 0.7f, &x) == SK_OK && x.stokes.i == 1.0f && x.pdf > 0.0f);
    CHECK(fabsf(x.dir.x * x.dir.x + x.dir.y * x.dir.y + x.dir.z * x.dir.z - 1.0f) < 1e-5f);
    CHECK(sk_rayleigh_polarized_sample_f64(&pd, kd, &sd, 0.3, 0.7, &xd) == SK_OK && xd.stokes.i == 1.0 && xd.pdf > 0.0);
    CHECK(fabs(xd.pdf - sk_rayleigh_polarized_pdf_f64(&pd, kd, &sd, xd.dir)) < 1e-12);
    CHECK(sk_rayleigh_polarized_sample_scalar(&p, k, &s, 0.3f, 0.7f, &x) == SK_OK && x.stokes.i > 0.0f);
    CHECK(sk_rayleigh_polarized_sample_scalar_f64(&pd, kd, &sd, 0.3, 0.7, &xd) == SK_OK && xd.stokes.i > 0.0);
    /* Bad input: NULLs, unconstructed, bad directions, unphysical Stokes,
     * uniforms outside [0, 1]; nothing written on error. */
    kept = o;
    keptd = od;
    keptx = x;
    keptxd = xd;
    CHECK(sk_rayleigh_polarized_eval(NULL, k, &s, w, r, &o) == SK_ERR_NULL && sk_rayleigh_polarized_eval(&p, k, NULL, w, r, &o) == SK_ERR_NULL);
    CHECK(sk_rayleigh_polarized_eval(&p, k, &s, w, r, NULL) == SK_ERR_NULL && sk_rayleigh_polarized_eval(&zero, k, &s, w, r, &o) == SK_ERR_DOMAIN);
    CHECK(sk_rayleigh_polarized_eval_f64(NULL, kd, &sd, wd, rd, &od) == SK_ERR_NULL && sk_rayleigh_polarized_eval_f64(&zerod, kd, &sd, wd, rd, &od) == SK_ERR_DOMAIN);
    CHECK(sk_rayleigh_polarized_eval_f64(&pd, kd, &sd, wd, rd, NULL) == SK_ERR_NULL && sk_rayleigh_polarized_eval_f64(&pd, kd, NULL, wd, rd, &od) == SK_ERR_NULL);
    CHECK(sk_rayleigh_polarized_sample(NULL, k, &s, 0.5f, 0.5f, &x) == SK_ERR_NULL && sk_rayleigh_polarized_sample(&p, k, &s, 0.5f, 0.5f, NULL) == SK_ERR_NULL);
    CHECK(sk_rayleigh_polarized_sample_f64(&pd, kd, NULL, 0.5, 0.5, &xd) == SK_ERR_NULL && sk_rayleigh_polarized_sample_scalar(&zero, k, &s, 0.5f, 0.5f, &x) == SK_ERR_DOMAIN);
    CHECK(sk_rayleigh_polarized_sample_scalar_f64(&pd, kd, &sd, 0.5, 0.5, NULL) == SK_ERR_NULL && sk_rayleigh_polarized_sample_scalar(&p, k, NULL, 0.5f, 0.5f, &x) == SK_ERR_NULL);
    CHECK(isnan(sk_rayleigh_polarized_pdf(NULL, k, &s, w)) && isnan(sk_rayleigh_polarized_pdf(&p, k, NULL, w)) && isnan(sk_rayleigh_polarized_pdf_f64(&zerod, kd, &sd, wd)));
    bad_s = s;
    bad_s.q = 0.99f; /* Q^2 + U^2 + V^2 > I^2 */
    bad_sd = sd;
    bad_sd.i = -1.0;
    CHECK(sk_rayleigh_polarized_eval(&p, k, &bad_s, w, r, &o) == SK_ERR_DOMAIN && sk_rayleigh_polarized_eval_f64(&pd, kd, &bad_sd, wd, rd, &od) == SK_ERR_DOMAIN);
    CHECK(sk_rayleigh_polarized_sample(&p, k, &bad_s, 0.5f, 0.5f, &x) == SK_ERR_DOMAIN && isnan(sk_rayleigh_polarized_pdf_f64(&pd, kd, &bad_sd, wd)));
    bad_s = s;
    bad_s.reference.x = 2.0f;
    CHECK(sk_rayleigh_polarized_sample(&p, k, &bad_s, 0.5f, 0.5f, &x) == SK_ERR_DOMAIN);
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        double d = DS[i];
        sk_vec3 kb = {f, 0, 1};
        sk_vec3_f64 kbd = {d, 0, 1};
        int u_ok = f >= 0.0f && f <= 1.0f;
        int ud_ok = d >= 0.0 && d <= 1.0;
        CHECK(sk_rayleigh_polarized_sample(&p, k, &s, f, 0.5f, &x) == (u_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_rayleigh_polarized_sample(&p, k, &s, 0.5f, f, &x) == (u_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_rayleigh_polarized_sample_f64(&pd, kd, &sd, d, 0.5, &xd) == (ud_ok ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_rayleigh_polarized_sample_scalar_f64(&pd, kd, &sd, 0.5, d, &xd) == (ud_ok ? SK_OK : SK_ERR_DOMAIN));
        /* A direction off unit length (or not finite) is rejected. */
        CHECK(sk_rayleigh_polarized_eval(&p, kb, &s, w, r, &o) == (fabsf(f) < 1e-3f ? SK_OK : SK_ERR_DOMAIN));
        CHECK(sk_rayleigh_polarized_eval_f64(&pd, kd, &sd, kbd, rd, &od) == (fabs(d) < 1e-3 ? SK_OK : SK_ERR_DOMAIN));
        CHECK(isnan(sk_rayleigh_polarized_pdf(&p, kb, &s, w)) == !(fabsf(f) < 1e-3f));
        for (j = 0; j < 4; j++) {
            sk_stokes t = s;
            sk_stokes_f64 td = sd;
            float *fs = &t.i;
            double *ds = &td.i;
            fs[j] = f;
            ds[j] = d;
            CHECK(sk_rayleigh_polarized_sample(&p, k, &t, 0.5f, 0.5f, &x) != SK_OK || (t.i >= 0.0f && isfinite(t.i)));
            CHECK(sk_rayleigh_polarized_eval_f64(&pd, kd, &td, wd, rd, &od) != SK_OK || (td.i >= 0.0 && isfinite(td.i)));
        }
    }
    /* The samples after the loop wrote only on success. */
    x = keptx;
    xd = keptxd;
    o = kept;
    od = keptd;
    CHECK(sk_rayleigh_polarized_sample(&p, k, &bad_s, 0.5f, 0.5f, &x) == SK_ERR_DOMAIN && memcmp(&x, &keptx, sizeof x) == 0);
    CHECK(sk_rayleigh_polarized_eval_f64(&pd, kd, &bad_sd, wd, rd, &od) == SK_ERR_DOMAIN && memcmp(&od, &keptd, sizeof od) == 0);
    /* Rotation and the meridian reference. */
    o = sk_stokes_rotate(&s, k, (sk_vec3){0, 1, 0});
    CHECK(fabsf(o.q + 0.5f) < 1e-6f && fabsf(o.u + 0.3f) < 1e-6f && o.v == 0.2f && o.reference.y == 1.0f);
    od = sk_stokes_rotate_f64(&sd, kd, (sk_vec3_f64){0, 1, 0});
    CHECK(fabs(od.q + 0.5) < 1e-15 && isnan(sk_stokes_rotate(NULL, k, e1).i) && isnan(sk_stokes_rotate_f64(NULL, kd, e1d).q));
    v = sk_meridian_reference(k, 0.0f);
    CHECK(v.x == 1.0f && v.y == 0.0f && v.z == 0.0f);
    CHECK(sk_meridian_reference_f64((sk_vec3_f64){1, 0, 0}, 0.0).z == -1.0);
    {
        sk_vec3 b1, b2, ir = sk_implicit_reference(w);
        sk_vec3_f64 ird = sk_implicit_reference_f64(wd);
        sk_onb(w, &b1, &b2);
        CHECK(ir.x == b1.x && ir.y == b1.y && ir.z == b1.z && fabs(ird.x * wd.x + ird.y * wd.y + ird.z * wd.z) < 1e-15);
    }
}

/* Mixtures: Rayleigh, HG and a fog table; every query with valid and bad
 * input, both precisions. */
static void mixtures(void) {
    int i;
    sk_phase ray, hg, zero_p;
    sk_phase_f64 rayd, hgd;
    float buf[2 * 65];
    double bufd[2 * 65];
    sk_table tab, bad_tab;
    sk_table_f64 tabd;
    sk_mixture m, kept;
    sk_mixture_f64 md;
    sk_mixture_part parts[9];
    sk_mixture_part_f64 partsd[2];
    const sk_vec3 w = {0, 0, 1};
    const sk_vec3_f64 wd = {0, 0, 1};
    float pdf, mu, prev;
    double pdfd;
    sk_vec3 dir;
    i = 0;
    memset(&zero_p, 0, sizeof zero_p);
    sk_phase_new_rayleigh(&ray);
    sk_phase_new_hg(0.8f, &hg);
    sk_phase_new_rayleigh_f64(&rayd);
    sk_phase_new_hg_f64(0.8, &hgd);
    CHECK(sk_table_new_inverse(&hg, buf, 2 * 65, 64, &tab) == SK_OK);
    CHECK(sk_table_new_inverse_f64(&hgd, bufd, 2 * 65, 64, &tabd) == SK_OK);
    parts[0].phase = &ray, parts[0].table = NULL, parts[0].weight = 0.5f;
    parts[1].phase = &hg, parts[1].table = NULL, parts[1].weight = 0.3f;
    parts[2].phase = NULL, parts[2].table = &tab, parts[2].weight = 0.2f;
    partsd[0].phase = &rayd, partsd[0].table = NULL, partsd[0].weight = 0.7;
    partsd[1].phase = NULL, partsd[1].table = &tabd, partsd[1].weight = 0.3;
    i = 0;
    CHECK(sk_mixture_new(parts, 3, &m) == SK_OK);
    CHECK(sk_mixture_new_f64(partsd, 2, &md) == SK_OK);
    /* g = 0.3 * 0.8 + 0.2 * (the table's own g, near 0.8). */
    CHECK(fabsf(sk_mixture_mean_cosine(&m) - 0.4f) < 2e-3f);
    CHECK(fabs(sk_mixture_mean_cosine_f64(&md) - 0.3 * 0.8) < 2e-3);
    CHECK(fabsf(sk_mixture_cdf(&m, 1.0f) - 1.0f) < 1e-6f && fabsf(sk_mixture_cdf(&m, -1.0f)) < 1e-6f);
    CHECK(sk_mixture_pdf(&m, 0.5f) > 0.0f && sk_mixture_pdf_f64(&md, 0.5) > 0.0);
    mu = sk_mixture_sample_cos(&m, 0.3f);
    CHECK(fabsf(sk_mixture_cdf(&m, mu) - 0.3f) < 1e-5f);
    {
        /* Batches: bit for bit the single calls, in place too; bad u,
         * NULLs and overlaps refused with nothing written. */
        float us[33], out[33], bad[2] = {0.5f, NAN};
        double usd[33], outd[33];
        int k, same = 1;
        for (k = 0; k < 33; k++) us[k] = (float)k / 32.0f, usd[k] = (double)k / 32.0;
        CHECK(sk_mixture_sample_cos_n(&m, us, out, 33) == SK_OK);
        for (k = 0; k < 33; k++) same &= out[k] == sk_mixture_sample_cos(&m, us[k]);
        CHECK(sk_mixture_sample_cos_by_lobe_n(&m, us, out, 33) == SK_OK);
        for (k = 0; k < 33; k++) same &= out[k] == sk_mixture_sample_cos_by_lobe(&m, us[k]);
        CHECK(sk_mixture_sample_cos_n_f64(&md, usd, outd, 33) == SK_OK);
        for (k = 0; k < 33; k++) same &= outd[k] == sk_mixture_sample_cos_f64(&md, usd[k]);
        CHECK(sk_mixture_sample_cos_by_lobe_n_f64(&md, usd, outd, 33) == SK_OK);
        for (k = 0; k < 33; k++) same &= outd[k] == sk_mixture_sample_cos_by_lobe_f64(&md, usd[k]);
        CHECK(same);
        CHECK(sk_mixture_sample_cos_n(&m, us, us, 33) == SK_OK && us[16] == sk_mixture_sample_cos(&m, 0.5f));
        out[0] = 7.0f;
        CHECK(sk_mixture_sample_cos_n(&m, bad, out, 2) == SK_ERR_DOMAIN && out[0] == 7.0f);
        CHECK(sk_mixture_sample_cos_by_lobe_n(&m, out, out + 1, 2) == SK_ERR_DOMAIN);
        CHECK(sk_mixture_sample_cos_n(NULL, bad, out, 1) == SK_ERR_NULL);
        CHECK(sk_mixture_sample_cos_by_lobe_n(&m, NULL, out, 1) == SK_ERR_NULL && sk_mixture_sample_cos_n(&m, bad, NULL, 1) == SK_ERR_NULL);
        CHECK(sk_mixture_sample_cos_n(&m, NULL, NULL, 0) == SK_OK && sk_mixture_sample_cos_by_lobe_n_f64(NULL, usd, outd, 1) == SK_ERR_NULL);
        CHECK(sk_mixture_sample_cos_n_f64(&md, usd, outd, SIZE_MAX) == SK_ERR_SIZE);
    }
    CHECK(fabs(sk_mixture_cdf_f64(&md, sk_mixture_sample_cos_f64(&md, 0.6)) - 0.6) < 1e-12);
    prev = -2.0f;
    for (i = 0; i <= 1000; i++) {
        mu = sk_mixture_sample_cos(&m, (float)i / 1000.0f);
        CHECK(mu >= prev && mu <= 1.0f);
        prev = mu;
        CHECK(fabsf(sk_mixture_sample_cos_by_lobe(&m, (float)i / 1000.0f)) <= 1.0f);
    }
    i = 0;
    CHECK(fabs(sk_mixture_sample_cos_by_lobe_f64(&md, 0.5)) <= 1.0);
    dir = sk_mixture_sample_dir(&m, w, 0.3f, 0.7f, &pdf);
    CHECK(fabsf(dir.x * dir.x + dir.y * dir.y + dir.z * dir.z - 1.0f) < 1e-5f && fabsf(pdf - sk_mixture_pdf(&m, dir.z)) < 1e-3f * pdf);
    CHECK(!isnan(sk_mixture_sample_dir_f64(&md, wd, 0.3, 0.7, &pdfd).z) && pdfd > 0.0);
    CHECK(!isnan(sk_mixture_sample_dir(&m, w, 0.3f, 0.7f, NULL).x));
    /* Bad uniforms and angles. */
    for (i = 0; i < NS; i++) {
        float f = FS[i];
        mu = sk_mixture_sample_cos(&m, f);
        CHECK(isnan(f) ? isnan(mu) : fabsf(mu) <= 1.0f);
        mu = sk_mixture_sample_cos_by_lobe(&m, f);
        CHECK(isnan(f) ? isnan(mu) : fabsf(mu) <= 1.0f);
        CHECK(isnan(f) == isnan(sk_mixture_cdf(&m, f)));
        CHECK(isnan(DS[i]) == isnan(sk_mixture_cdf_f64(&md, DS[i])));
        /* A bad weight. */
        parts[1].weight = f;
        CHECK(sk_mixture_new(parts, 3, &kept) == (isfinite(f) && f >= 0.0f ? SK_OK : SK_ERR_DOMAIN));
    }
    i = 0;
    parts[1].weight = 0.3f;
    /* NULLs, counts, parts with neither or both, unconstructed phases,
     * malformed tables, all weights zero. */
    CHECK(sk_mixture_new(NULL, 3, &kept) == SK_ERR_NULL && sk_mixture_new(parts, 3, NULL) == SK_ERR_NULL);
    CHECK(sk_mixture_new(parts, 0, &kept) == SK_ERR_SIZE);
    for (i = 3; i < 9; i++) parts[i] = parts[0];
    CHECK(sk_mixture_new(parts, 8, &kept) == SK_OK && sk_mixture_new(parts, 9, &kept) == SK_ERR_SIZE);
    i = 0;
    parts[3].phase = NULL;
    CHECK(sk_mixture_new(parts, 4, &kept) == SK_ERR_NULL);
    parts[3].phase = &ray, parts[3].table = &tab;
    CHECK(sk_mixture_new(parts, 4, &kept) == SK_ERR_DOMAIN);
    parts[3].table = NULL, parts[3].phase = &zero_p;
    CHECK(sk_mixture_new(parts, 4, &kept) == SK_ERR_DOMAIN);
    bad_tab = tab;
    bad_tab.kind = 9;
    parts[3].phase = NULL, parts[3].table = &bad_tab;
    CHECK(sk_mixture_new(parts, 4, &kept) == SK_ERR_SIZE);
    parts[0].weight = parts[1].weight = parts[2].weight = 0.0f;
    CHECK(sk_mixture_new(parts, 3, &kept) == SK_ERR_DOMAIN);
    /* NULL and values sk_mixture_new did not build. */
    CHECK(isnan(sk_mixture_pdf(NULL, 0.0f)) && isnan(sk_mixture_cdf_f64(NULL, 0.0)));
    CHECK(isnan(sk_mixture_sample_cos(NULL, 0.5f)) && isnan(sk_mixture_sample_cos_by_lobe(NULL, 0.5f)));
    CHECK(isnan(sk_mixture_mean_cosine_f64(NULL)) && isnan(sk_mixture_sample_dir(NULL, w, 0.1f, 0.1f, &pdf).x) && isnan(pdf));
    /* A zeroed mixture, and one whose tag was overwritten: never loaded. */
    memset(&kept, 0, sizeof kept);
    CHECK(isnan(sk_mixture_pdf(&kept, 0.0f)) && isnan(sk_mixture_sample_cos_by_lobe(&kept, 0.5f)));
    CHECK(isnan(sk_mixture_sample_cos(&kept, 0.5f)) && isnan(sk_mixture_mean_cosine(&kept)));
    kept = m;
    memset(&kept, 0xff, 4);
    CHECK(isnan(sk_mixture_pdf(&kept, 0.0f)) && isnan(sk_mixture_sample_cos(&kept, 0.5f)));
    CHECK(isnan(sk_mixture_cdf(&kept, 0.0f)) && isnan(sk_mixture_sample_cos_by_lobe(&kept, 0.99f)));
    /* A copy is a mixture: the value is plain bytes. */
    memcpy(&kept, &m, sizeof m);
    CHECK(sk_mixture_sample_cos(&kept, 0.3f) == sk_mixture_sample_cos(&m, 0.3f));
    {
        /* Legendre moments: Rayleigh's (1, 0, 1/10, 0), HG's g^l, the
         * mixture's weighted sum; bad input. */
        float chi[4], chim[4];
        double chid[3];
        CHECK(sk_phase_legendre_moments(&ray, chi, 4) == SK_OK && chi[0] == 1.0f && chi[1] == 0.0f &&
              fabsf(chi[2] - 0.1f) < 1e-7f && chi[3] == 0.0f);
        CHECK(sk_phase_legendre_moments_f64(&hgd, chid, 3) == SK_OK && fabs(chid[2] - 0.64) < 1e-15);
        CHECK(sk_mixture_legendre_moments(&m, chim, 4) == SK_OK && fabsf(chim[0] - 1.0f) < 1e-6f &&
              fabsf(chim[1] - sk_mixture_mean_cosine(&m)) < 1e-5f);
        CHECK(sk_mixture_legendre_moments_f64(&md, chid, 3) == SK_OK && fabs(chid[0] - 1.0) < 1e-12);
        CHECK(sk_phase_legendre_moments(&ray, chi, 0) == SK_OK);
        {
            /* Each family set by (g, gamma) or (g, delta): its moments give
             * them back; outside its reach, bad floats and NULL: errors. */
            typedef sk_status (*by_moments)(float, float, sk_phase *);
            typedef sk_status (*by_moments_f64)(double, double, sk_phase_f64 *);
            static const struct {
                by_moments f;
                by_moments_f64 d;
                int j;
                float g, r, beyond;
            } fam[] = {
                {sk_phase_new_modified_hg, sk_phase_new_modified_hg_f64, 2, 0.8f, 1.5f, 1.81f},
                {sk_phase_new_modified_hg_delta, sk_phase_new_modified_hg_delta_f64, 3, 0.8f, 2.0f, 2.45f},
                {sk_phase_new_two_lobe_hg_gamma, sk_phase_new_two_lobe_hg_gamma_f64, 2, 0.8f, 1.5f, 1.81f},
                {sk_phase_new_two_lobe_hg_delta, sk_phase_new_two_lobe_hg_delta_f64, 3, 0.8f, 2.0f, 2.45f},
                {sk_phase_new_gegenbauer_gamma, sk_phase_new_gegenbauer_gamma_f64, 2, 0.8f, 2.2f, 2.5f},
                {sk_phase_new_gegenbauer_delta, sk_phase_new_gegenbauer_delta_f64, 3, 0.8f, 3.0f, 4.0f},
            };
            size_t f;
            sk_phase mhg;
            sk_phase_f64 mhgd;
            double chd[4];
            int k;
            for (f = 0; f < sizeof fam / sizeof fam[0]; f++) {
                int j = fam[f].j;
                i = (int)f;
                CHECK(fam[f].f(fam[f].g, fam[f].r, &mhg) == SK_OK && sk_phase_legendre_moments(&mhg, chi, 4) == SK_OK);
                CHECK(fabsf(chi[1] - fam[f].g) < 1e-5f && fabsf((1.0f - chi[j]) / (1.0f - chi[1]) - fam[f].r) < 1e-3f);
                CHECK(fam[f].d(fam[f].g, fam[f].r, &mhgd) == SK_OK && sk_phase_legendre_moments_f64(&mhgd, chd, 4) == SK_OK);
                CHECK(fabs((1.0 - chd[j]) / (1.0 - chd[1]) - fam[f].r) < 1e-9);
                CHECK(fam[f].d(fam[f].g, fam[f].beyond, &mhgd) == SK_ERR_DOMAIN);
                for (k = 0; k < NS; k++) {
                    CHECK(fam[f].f(FS[k], 1.2f, &mhg) == SK_ERR_DOMAIN);
                    CHECK(fam[f].f(0.5f, FS[k], &mhg) == SK_ERR_DOMAIN);
                }
            }
            i = 0;
            /* The same entry points called by name, with NULL out. */
            CHECK(sk_phase_new_modified_hg(0.8f, 1.5f, NULL) == SK_ERR_NULL && sk_phase_new_modified_hg_f64(0.8, 1.5, NULL) == SK_ERR_NULL);
            CHECK(sk_phase_new_modified_hg_delta(0.8f, 2.0f, NULL) == SK_ERR_NULL && sk_phase_new_modified_hg_delta_f64(0.8, 2.0, NULL) == SK_ERR_NULL);
            CHECK(sk_phase_new_two_lobe_hg_gamma(0.8f, 1.5f, NULL) == SK_ERR_NULL && sk_phase_new_two_lobe_hg_gamma_f64(0.8, 1.5, NULL) == SK_ERR_NULL);
            CHECK(sk_phase_new_two_lobe_hg_delta(0.8f, 2.0f, NULL) == SK_ERR_NULL && sk_phase_new_two_lobe_hg_delta_f64(0.8, 2.0, NULL) == SK_ERR_NULL);
            CHECK(sk_phase_new_gegenbauer_gamma(0.8f, 2.2f, NULL) == SK_ERR_NULL && sk_phase_new_gegenbauer_gamma_f64(0.8, 2.2, NULL) == SK_ERR_NULL);
            CHECK(sk_phase_new_gegenbauer_delta(0.8f, 3.0f, NULL) == SK_ERR_NULL && sk_phase_new_gegenbauer_delta_f64(0.8, 3.0, NULL) == SK_ERR_NULL);
        }
        CHECK(sk_phase_legendre_moments(NULL, chi, 4) == SK_ERR_NULL && sk_phase_legendre_moments(&ray, NULL, 4) == SK_ERR_NULL);
        CHECK(sk_phase_legendre_moments(&zero_p, chi, 4) == SK_ERR_DOMAIN);
        CHECK(sk_mixture_legendre_moments(NULL, chi, 4) == SK_ERR_NULL && sk_mixture_legendre_moments_f64(&md, NULL, 3) == SK_ERR_NULL);
        memset(&kept, 0, sizeof kept);
        CHECK(sk_mixture_legendre_moments(&kept, chi, 4) == SK_ERR_DOMAIN);
    }
    {
        /* Legendre series: Rayleigh's three moments sample as Rayleigh;
         * HG 0.9 cut at five moments goes negative. */
        const float chir[3] = {1.0f, 0.0f, 0.1f}, neg[5] = {1.0f, 0.9f, 0.81f, 0.729f, 0.6561f};
        const double chird[3] = {1.0, 0.0, 0.1};
        float bad_chi[2] = {1.0f, 0.0f}, where = 7.0f;
        double whered;
        sk_legendre lg, lg_bad;
        sk_legendre_f64 lgd;
        CHECK(sk_legendre_new(chir, 3, &lg) == SK_OK && sk_legendre_new_f64(chird, 3, &lgd) == SK_OK);
        CHECK(fabsf(sk_legendre_sample_cos(&lg, 0.3f) - sk_phase_sample_cos(&ray, 0.3f)) < 1e-6f);
        CHECK(fabs(sk_legendre_sample_cos_f64(&lgd, 0.7) - sk_phase_sample_cos_f64(&rayd, 0.7)) < 1e-13);
        CHECK(fabsf(sk_legendre_pdf(&lg, 0.5f) - sk_phase_pdf(&ray, 0.5f)) < 1e-7f);
        CHECK(fabs(sk_legendre_cdf_f64(&lgd, 0.0) - 0.5) < 1e-15 && sk_legendre_pdf_f64(&lgd, 1.0) > 0.0);
        CHECK(fabsf(sk_legendre_cdf(&lg, 1.0f) - 1.0f) < 1e-6f);
        CHECK(sk_legendre_check(chir, 3, &where) == SK_OK && where == 7.0f);
        CHECK(sk_legendre_new(neg, 5, &lg_bad) == SK_ERR_DOMAIN);
        CHECK(sk_legendre_check(neg, 5, &where) == SK_ERR_DOMAIN && fabsf(where) <= 1.0f);
        CHECK(sk_legendre_check_f64(chird, 3, &whered) == SK_OK);
        for (i = 0; i < NS; i++) {
            bad_chi[1] = FS[i];
            CHECK(sk_legendre_new(bad_chi, 2, &lg_bad) == (fabsf(FS[i]) <= 1.0f / 3.0f ? SK_OK : SK_ERR_DOMAIN));
            mu = sk_legendre_sample_cos(&lg, FS[i]);
            CHECK(isnan(FS[i]) ? isnan(mu) : fabsf(mu) <= 1.0f);
            CHECK(isnan(FS[i]) == isnan(sk_legendre_cdf(&lg, FS[i])));
        }
        i = 0;
        CHECK(sk_legendre_new(NULL, 3, &lg_bad) == SK_ERR_NULL && sk_legendre_new(chir, 3, NULL) == SK_ERR_NULL);
        CHECK(sk_legendre_new(chir, 0, &lg_bad) == SK_ERR_SIZE && sk_legendre_new(chir, 1025, &lg_bad) == SK_ERR_SIZE);
        CHECK(sk_legendre_check(NULL, 3, &where) == SK_ERR_NULL && sk_legendre_check(chir, 3, NULL) == SK_ERR_NULL);
        CHECK(isnan(sk_legendre_pdf(NULL, 0.0f)) && isnan(sk_legendre_sample_cos_f64(NULL, 0.5)) && isnan(sk_legendre_cdf_f64(NULL, 0.0)));
        memset(&lg_bad, 0, sizeof lg_bad); /* never built */
        CHECK(isnan(sk_legendre_sample_cos(&lg_bad, 0.5f)) && isnan(sk_legendre_pdf(&lg_bad, 0.5f)));
        memcpy(&lg_bad, &lg, sizeof lg);
        memset(&lg_bad, 0xff, 4); /* its tag overwritten */
        CHECK(isnan(sk_legendre_cdf(&lg_bad, 0.5f)));
    }
    {
        /* Spectral phase: Rayleigh, HG 0.8 and the HG table per channel. */
        sk_channel_phase ch[17];
        sk_channel_phase_f64 chd[2];
        float ratio[17], pdfs[3], c = 7.0f;
        double ratiod[2], cd;
        ch[0].phase = &ray, ch[0].table = NULL;
        ch[1].phase = &hg, ch[1].table = NULL;
        ch[2].phase = NULL, ch[2].table = &tab;
        chd[0].phase = &rayd, chd[0].table = NULL;
        chd[1].phase = NULL, chd[1].table = &tabd;
        CHECK(sk_spectral_phase_sample(ch, 3, 1, 0.3f, &c, ratio) == SK_OK && ratio[1] == 1.0f);
        CHECK(fabsf(ratio[0] - sk_phase_pdf(&ray, c) / sk_phase_pdf(&hg, c)) < 1e-5f * ratio[0]);
        CHECK(sk_spectral_phase_pdf(ch, 3, c, pdfs) == SK_OK && fabsf(pdfs[1] - sk_phase_pdf(&hg, c)) < 1e-6f);
        CHECK(sk_spectral_phase_sample_f64(chd, 2, 0, 0.6, &cd, ratiod) == SK_OK && ratiod[0] == 1.0);
        CHECK(sk_spectral_phase_pdf_f64(chd, 2, 0.1, ratiod) == SK_OK && ratiod[0] > 0.0);
        for (i = 0; i < NS; i++) {
            c = 7.0f;
            CHECK(sk_spectral_phase_sample(ch, 3, 0, FS[i], &c, ratio) == (isnan(FS[i]) ? SK_ERR_DOMAIN : SK_OK));
            CHECK(isnan(FS[i]) ? c == 7.0f : fabsf(c) <= 1.0f);
            CHECK(sk_spectral_phase_pdf(ch, 3, FS[i], pdfs) == SK_OK);
        }
        i = 0;
        CHECK(sk_spectral_phase_sample(ch, 3, 3, 0.5f, &c, ratio) == SK_ERR_SIZE);
        CHECK(sk_spectral_phase_sample(ch, 0, 0, 0.5f, &c, ratio) == SK_ERR_SIZE);
        for (i = 3; i < 17; i++) ch[i] = ch[0];
        CHECK(sk_spectral_phase_sample(ch, 16, 15, 0.5f, &c, ratio) == SK_OK);
        CHECK(sk_spectral_phase_sample(ch, 17, 0, 0.5f, &c, ratio) == SK_ERR_SIZE);
        i = 0;
        CHECK(sk_spectral_phase_sample(NULL, 3, 0, 0.5f, &c, ratio) == SK_ERR_NULL);
        CHECK(sk_spectral_phase_sample(ch, 3, 0, 0.5f, NULL, ratio) == SK_ERR_NULL);
        CHECK(sk_spectral_phase_sample(ch, 3, 0, 0.5f, &c, NULL) == SK_ERR_NULL);
        CHECK(sk_spectral_phase_pdf_f64(NULL, 2, 0.1, ratiod) == SK_ERR_NULL && sk_spectral_phase_pdf(ch, 3, 0.1f, NULL) == SK_ERR_NULL);
        ch[0].phase = NULL;
        CHECK(sk_spectral_phase_sample(ch, 3, 1, 0.5f, &c, ratio) == SK_ERR_NULL);
        ch[0].phase = &ray, ch[0].table = &tab;
        CHECK(sk_spectral_phase_pdf(ch, 3, 0.1f, pdfs) == SK_ERR_DOMAIN);
        ch[0].table = NULL, ch[0].phase = &zero_p;
        CHECK(sk_spectral_phase_sample(ch, 3, 1, 0.5f, &c, ratio) == SK_ERR_DOMAIN);
        ch[0].phase = NULL, ch[0].table = &bad_tab;
        CHECK(sk_spectral_phase_sample(ch, 3, 1, 0.5f, &c, ratio) == SK_ERR_SIZE);
    }
}
