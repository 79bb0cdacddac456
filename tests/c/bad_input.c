/* Bad input through the C ABI: every documented error of the foundation
 * functions, and that out-pointers stay untouched on error. Prints one line per
 * failed check and a summary; exits with the number of failures. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scatterkit.h"

#include "check.h"

static uint64_t counter(void *state) {
    uint64_t *s = (uint64_t *)state;
    *s += 0x9e3779b97f4a7c15ULL;
    return *s;
}

static uint64_t constant_zero(void *state) {
    (void)state;
    return 0; /* a broken generator: rejection loops must still end */
}

static int untouched_phase(const sk_phase *p) {
    size_t i;
    for (i = 0; i < sizeof p->opaque / sizeof p->opaque[0]; i++)
        if (p->opaque[i] != 0xdeadbeefu) return 0;
    return 1;
}

static void phase_constructors(void) {
    /* |g| = 1 is HG's Dirac limit (accepted); just past it is not. */
    const float bad_g[] = {1.0000001f, -1.0000001f, 1.5f, -7.0f, NAN, INFINITY, -INFINITY};
    const double bad_g64[] = {1.0000000000000002, -1.0000000000000002, 2.0, NAN, INFINITY, -INFINITY};
    const float bad_rho[] = {-0.001f, 1.0f, 2.0f, NAN, INFINITY, -INFINITY};
    sk_phase p;
    sk_phase_f64 p64;
    size_t i;

    for (i = 0; i < sizeof bad_g / sizeof bad_g[0]; i++) {
        size_t k;
        for (k = 0; k < sizeof p.opaque / sizeof p.opaque[0]; k++) p.opaque[k] = 0xdeadbeefu;
        CHECK(sk_phase_new_hg(bad_g[i], &p) == SK_ERR_DOMAIN);
        CHECK(untouched_phase(&p));
    }
    for (i = 0; i < sizeof bad_g64 / sizeof bad_g64[0]; i++)
        CHECK(sk_phase_new_hg_f64(bad_g64[i], &p64) == SK_ERR_DOMAIN);
    for (i = 0; i < sizeof bad_rho / sizeof bad_rho[0]; i++) {
        CHECK(sk_phase_new_rayleigh_depolarized(bad_rho[i], &p) == SK_ERR_DOMAIN);
        CHECK(sk_phase_new_rayleigh_depolarized_f64(bad_rho[i], &p64) == SK_ERR_DOMAIN);
    }
    CHECK(sk_phase_new_hg(0.5f, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_hg_f64(0.5, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_isotropic(NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_isotropic_f64(NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_rayleigh(NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_rayleigh_f64(NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_rayleigh_depolarized(0.1f, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_rayleigh_depolarized_f64(0.1, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_hg(-0.999999f, &p) == SK_OK);
    CHECK(sk_phase_new_rayleigh_depolarized(0.0f, &p) == SK_OK);
}

static void scattering_phases(void) {
    const float bad_alpha[] = {-1e-30f, -1.0f, NAN, INFINITY};
    sk_phase p;
    sk_phase_f64 p64;
    float cosines[4] = {-1.0f, -0.5f, 0.5f, 1.0f}, pdf[4] = {1.0f, 2.0f, 3.0f, 4.0f};
    float buf[2 * 33];
    sk_table t;
    size_t i;

    for (i = 0; i < 4; i++) {
        CHECK(sk_phase_new_draine(0.5f, bad_alpha[i], &p) == SK_ERR_DOMAIN);
        CHECK(sk_phase_new_fog(0.5f, 0.5f, bad_alpha[i], 0.5f, &p) == SK_ERR_DOMAIN);
    }
    CHECK(sk_phase_new_draine(1.0f, 1.0f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_draine(NAN, 1.0f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_draine_f64(-1.0, 1.0, &p64) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_cornette_shanks(-1.5f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_cornette_shanks_f64(INFINITY, &p64) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog(1.0000001f, 0.5f, 1.0f, 0.5f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog(0.5f, 1.0f, 1.0f, 0.5f, &p) == SK_ERR_DOMAIN); /* a Draine lobe at 1 */
    CHECK(sk_phase_new_fog(0.5f, 0.5f, 1.0f, 1.5f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog(0.5f, 0.5f, 1.0f, -0.1f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog_f64(0.5, 0.5, 1.0, NAN, &p64) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog_diameter(0.0f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog_diameter(-2.0f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog_diameter(50.5f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog_diameter(NAN, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_fog_diameter_f64(INFINITY, &p64) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_particle(2.0f, 0.0f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_particle(2.0f, 1.0f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_particle(2.0f, NAN, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_particle(60.0f, 0.1f, &p) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_particle_f64(0.0, 0.1, &p64) == SK_ERR_DOMAIN);
    CHECK(sk_phase_new_draine(0.5f, 1.0f, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_cornette_shanks(0.5f, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_fog(0.5f, 0.5f, 1.0f, 0.5f, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_fog_diameter(2.0f, NULL) == SK_ERR_NULL);
    CHECK(sk_phase_new_particle(2.0f, 0.1f, NULL) == SK_ERR_NULL);
    CHECK(isnan(sk_phase_sample_cos_by_lobe(NULL, 0.5f)));
    /* Valid extremes: no NaN, nothing outside [-1, 1]. */
    CHECK(sk_phase_new_draine(0.0f, 0.0f, &p) == SK_OK);
    CHECK(fabsf(sk_phase_sample_cos(&p, 0.3f)) <= 1.0f);
    CHECK(sk_phase_new_draine(-0.999f, 1e4f, &p) == SK_OK);
    CHECK(sk_phase_sample_cos(&p, 1.0f) == 1.0f && sk_phase_sample_cos(&p, 0.0f) == -1.0f);
    CHECK(sk_phase_new_fog_diameter(50.0f, &p) == SK_OK);
    CHECK(fabsf(sk_phase_sample_cos_by_lobe(&p, 0.999f)) <= 1.0f);
    CHECK(sk_phase_new_particle(0.01f, 0.01f, &p) == SK_OK);

    /* Tables: sizes, NULLs, measured data. */
    CHECK(sk_table_len(SK_TABLE_INVERSE, 32) == 66 && sk_table_len(SK_TABLE_MEASURED, 32) == 66);
    CHECK(sk_phase_new_hg(0.5f, &p) == SK_OK);
    CHECK(sk_table_new_inverse(&p, buf, 65, 32, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_inverse(&p, buf, 66, 0, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_inverse(NULL, buf, 66, 32, &t) == SK_ERR_NULL);
    CHECK(sk_table_new_inverse(&p, NULL, 66, 32, &t) == SK_ERR_NULL);
    CHECK(sk_table_new_inverse(&p, buf, 66, 32, NULL) == SK_ERR_NULL);
    {
        sk_phase zero;
        memset(&zero, 0, sizeof zero);
        CHECK(sk_table_new_inverse(&zero, buf, 66, 32, &t) == SK_ERR_DOMAIN);
    }
    CHECK(sk_table_new_inverse(&p, buf, 66, 32, &t) == SK_OK);
    CHECK(sk_table_sample_cos(&t, 0.0f) == -1.0f && sk_table_sample_cos(&t, 1.0f) == 1.0f);
    CHECK(sk_table_new_measured(cosines, pdf, 4, buf, 66, 32, &t) == SK_OK);
    CHECK(sk_table_new_measured(cosines, pdf, 1, buf, 66, 32, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_measured(cosines, pdf, 4, buf, 10, 32, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_measured(NULL, pdf, 4, buf, 66, 32, &t) == SK_ERR_NULL);
    CHECK(sk_table_new_measured(cosines, NULL, 4, buf, 66, 32, &t) == SK_ERR_NULL);
    pdf[2] = -1.0f;
    CHECK(sk_table_new_measured(cosines, pdf, 4, buf, 66, 32, &t) == SK_ERR_DOMAIN);
    pdf[2] = NAN;
    CHECK(sk_table_new_measured(cosines, pdf, 4, buf, 66, 32, &t) == SK_ERR_DOMAIN);
    pdf[2] = 3.0f;
    cosines[2] = -0.7f; /* unsorted */
    CHECK(sk_table_new_measured(cosines, pdf, 4, buf, 66, 32, &t) == SK_ERR_DOMAIN);
    cosines[2] = 0.5f;
    pdf[0] = pdf[1] = pdf[2] = pdf[3] = 0.0f; /* no mass */
    CHECK(sk_table_new_measured(cosines, pdf, 4, buf, 66, 32, &t) == SK_ERR_DOMAIN);
}

static void phase_queries(void) {
    sk_phase zero, hg;
    sk_phase_f64 zero64;
    float u[3] = {0.25f, 0.5f, 0.75f}, out[3] = {7.0f, 7.0f, 7.0f}, pdf = 7.0f;
    sk_vec3 w = {0.0f, 0.0f, 1.0f}, d;
    memset(&zero, 0, sizeof zero);
    memset(&zero64, 0, sizeof zero64);

    /* NULL or never-constructed objects: NaN from float functions. */
    CHECK(isnan(sk_phase_pdf(NULL, 0.0f)));
    CHECK(isnan(sk_phase_cdf(NULL, 0.0f)));
    CHECK(isnan(sk_phase_sample_cos(NULL, 0.5f)));
    CHECK(isnan(sk_phase_mean_cosine(NULL)));
    CHECK(isnan(sk_phase_pdf(&zero, 0.0f)));
    CHECK(isnan(sk_phase_pdf_f64(&zero64, 0.0)));
    CHECK(isnan(sk_phase_mean_cosine_f64(NULL)));
    d = sk_phase_sample_dir(NULL, w, 0.5f, 0.5f, &pdf);
    CHECK(isnan(d.x) && isnan(d.y) && isnan(d.z) && isnan(pdf));
    CHECK(sk_phase_sample_cos_n(NULL, u, out, 3) == SK_ERR_NULL);
    CHECK(sk_phase_sample_cos_n(&zero, u, out, 3) == SK_ERR_DOMAIN);

    /* Scalar u is clamped; NaN propagates. */
    CHECK(sk_phase_new_hg(0.6f, &hg) == SK_OK);
    CHECK(sk_phase_sample_cos(&hg, -3.0f) == sk_phase_sample_cos(&hg, 0.0f));
    CHECK(sk_phase_sample_cos(&hg, 5.0f) == sk_phase_sample_cos(&hg, 1.0f));
    CHECK(isnan(sk_phase_sample_cos(&hg, NAN)));
    d = sk_phase_sample_dir(&hg, w, 0.3f, 0.2f, NULL); /* pdf_out may be NULL */
    CHECK(fabsf(d.x * d.x + d.y * d.y + d.z * d.z - 1.0f) < 1e-6f);

    /* Batches: NULL arrays with n > 0, n = 0, bad u, overlap. */
    CHECK(sk_phase_sample_cos_n(&hg, NULL, out, 3) == SK_ERR_NULL);
    CHECK(sk_phase_sample_cos_n(&hg, u, NULL, 3) == SK_ERR_NULL);
    CHECK(sk_phase_sample_cos_n(&hg, NULL, NULL, 0) == SK_OK);
    CHECK(sk_phase_sample_cos_n(&hg, u, out, 0) == SK_OK);
    CHECK(sk_phase_sample_cos_n(&hg, u, out, SIZE_MAX) == SK_ERR_SIZE);
    u[1] = NAN;
    CHECK(sk_phase_sample_cos_n(&hg, u, out, 3) == SK_ERR_DOMAIN);
    u[1] = 1.5f;
    CHECK(sk_phase_sample_cos_n(&hg, u, out, 3) == SK_ERR_DOMAIN);
    u[1] = -0.0f;
    CHECK(sk_phase_sample_cos_n(&hg, u, out, 3) == SK_OK);
    CHECK(out[1] == -1.0f);
    out[0] = out[1] = out[2] = 7.0f;
    u[1] = -1e-30f;
    CHECK(sk_phase_sample_cos_n(&hg, u, out, 3) == SK_ERR_DOMAIN);
    CHECK(out[0] == 7.0f && out[1] == 7.0f && out[2] == 7.0f);
    u[1] = 0.5f;
    CHECK(sk_phase_sample_cos_n(&hg, u, u + 1, 2) == SK_ERR_OVERLAP); /* partial overlap */
    CHECK(sk_phase_sample_cos_n(&hg, u, u, 3) == SK_OK);            /* in place */
}

static void rayleigh_methods(void) {
    uint64_t state = 1;
    sk_rng rng = {&state, counter}, no_fn = {&state, NULL}, broken = {NULL, constant_zero};
    sk_vec3 w = {0.0f, 0.0f, 1.0f}, d = {7.0f, 7.0f, 7.0f};
    sk_vec3_f64 w64 = {0.0, 0.0, 1.0}, d64;
    float c[4] = {7.0f, 7.0f, 7.0f, 7.0f};
    double c64[4];
    uint32_t m;

    CHECK(sk_rayleigh_sample_dir(8, w, &rng, &d) == SK_ERR_METHOD);
    CHECK(sk_rayleigh_sample_dir(UINT32_MAX, w, &rng, &d) == SK_ERR_METHOD);
    CHECK(d.x == 7.0f);
    CHECK(sk_rayleigh_sample_dir_f64(8, w64, &rng, &d64) == SK_ERR_METHOD);
    CHECK(sk_rayleigh_sample_cos_n(8, &rng, c, 4) == SK_ERR_METHOD);
    CHECK(sk_rayleigh_sample_cos_n_f64(99, &rng, c64, 4) == SK_ERR_METHOD);
    CHECK(sk_rayleigh_sample_dir(SK_RAYLEIGH_DIRECT, w, NULL, &d) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir(SK_RAYLEIGH_DIRECT, w, &no_fn, &d) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_dir(SK_RAYLEIGH_DIRECT, w, &rng, NULL) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_DIRECT, NULL, c, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_DIRECT, &no_fn, c, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_DIRECT, &rng, NULL, 4) == SK_ERR_NULL);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_DIRECT, &rng, NULL, 0) == SK_OK);
    CHECK(sk_rayleigh_sample_cos_n(SK_RAYLEIGH_DIRECT, &rng, c, SIZE_MAX) == SK_ERR_SIZE);
    CHECK(c[0] == 7.0f);
    /* A generator stuck at zero must not hang any method. */
    for (m = SK_RAYLEIGH_REJECT_CUBE; m <= SK_RAYLEIGH_TABLE; m++) {
        CHECK(sk_rayleigh_sample_dir(m, w, &broken, &d) == SK_OK);
        CHECK(fabsf(d.x * d.x + d.y * d.y + d.z * d.z - 1.0f) < 1e-6f);
        CHECK(sk_rayleigh_sample_cos_n(m, &rng, c, 4) == SK_OK);
        CHECK(c[0] >= -1.0f && c[0] <= 1.0f);
    }
}

static void tables(void) {
    float buf[33];
    double buf64[33];
    sk_table t = {NULL, 0, 0};
    sk_table_f64 t64;
    sk_table bogus = {NULL, 32, SK_TABLE_RAYLEIGH_CDF};

    CHECK(sk_table_len(SK_TABLE_RAYLEIGH_CDF, 32) == 33);
    CHECK(sk_table_len(SK_TABLE_RAYLEIGH_CDF, 0) == 0);
    CHECK(sk_table_len(SK_TABLE_RAYLEIGH_CDF, SIZE_MAX) == 0);
    CHECK(sk_table_len(77, 32) == 0);
    CHECK(sk_table_len(SK_TABLE_INVERSE, SIZE_MAX) == 0);
    CHECK(sk_table_new_rayleigh_cdf(buf, 32, 32, &t) == SK_ERR_SIZE); /* one float short */
    CHECK(t.data == NULL);
    CHECK(sk_table_new_rayleigh_cdf(buf, 33, 0, &t) == SK_ERR_SIZE);
    CHECK(sk_table_new_rayleigh_cdf(NULL, 33, 32, &t) == SK_ERR_NULL);
    CHECK(sk_table_new_rayleigh_cdf(buf, 33, 32, NULL) == SK_ERR_NULL);
    CHECK(sk_table_new_rayleigh_cdf_f64(buf64, 10, 32, &t64) == SK_ERR_SIZE);
    CHECK(sk_table_new_rayleigh_cdf(buf, 33, 32, &t) == SK_OK);
    CHECK(sk_table_sample_cos(&t, 0.0f) == -1.0f && sk_table_sample_cos(&t, 1.0f) == 1.0f);
    CHECK(isnan(sk_table_sample_cos(&t, NAN)));
    CHECK(isnan(sk_table_sample_cos(NULL, 0.5f)));
    CHECK(isnan(sk_table_sample_cos(&bogus, 0.5f)));
    bogus.data = buf;
    bogus.kind = 9;
    CHECK(isnan(sk_table_sample_cos(&bogus, 0.5f)));
    bogus.kind = SK_TABLE_RAYLEIGH_CDF;
    bogus.n = 0;
    CHECK(isnan(sk_table_sample_cos(&bogus, 0.5f)));
}

static void coefficients_and_cbrt(void) {
    const double bad[] = {0.0, -1.0, NAN, INFINITY};
    size_t i;
    for (i = 0; i < 4; i++) {
        CHECK(isnan(sk_rayleigh_cross_section_f64(bad[i], 1e-9, 1.5)));
        CHECK(isnan(sk_rayleigh_cross_section_f64(500e-9, bad[i], 1.5)));
        CHECK(isnan(sk_rayleigh_cross_section_f64(500e-9, 1e-9, bad[i])));
        CHECK(isnan(sk_rayleigh_scattering_coeff_f64(1e20, bad[i], 1e-9, 1.5)));
    }
    CHECK(isnan(sk_rayleigh_scattering_coeff_f64(-1.0, 500e-9, 1e-9, 1.5)));
    CHECK(sk_rayleigh_cross_section_f64(500e-9, 1e-9, 1.5) > 0.0);
    CHECK(sk_cbrt(27.0f) == 3.0f && sk_cbrt_f64(-8.0) == -2.0);
    CHECK(isnan(sk_cbrt(NAN)) && isinf(sk_cbrt_f64(-INFINITY)) && sk_cbrt_f64(-INFINITY) < 0);
    CHECK(sk_cbrt(-0.0f) == 0.0f && signbit(sk_cbrt(-0.0f)));
}

static void surfaces(void) {
    uint64_t state = 3;
    sk_rng rng = {&state, counter}, no_fn = {&state, NULL};
    sk_surface s, bad;
    sk_vec3 d = {0.0f, 0.0f, -1.0f}, n = {0.0f, 0.0f, 1.0f}, zero = {0.0f, 0.0f, 0.0f};
    sk_vec3 nanv = {NAN, 0.0f, 1.0f}, out = {7.0f, 7.0f, 7.0f}, r;
    sk_vec3 grazing = {0.9f, 0.0f, 0.3f};
    uint32_t ev = 77;

    CHECK(sk_surface_new(3, 10.0f, SK_FRACTION_CONSTANT, 0.5f, 0.0f, SK_CROSSING_FOLD, &s) == SK_ERR_METHOD);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 10.0f, 2, 0.5f, 0.0f, SK_CROSSING_FOLD, &s) == SK_ERR_METHOD);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 10.0f, SK_FRACTION_CONSTANT, 0.5f, 0.0f, 3, &s) == SK_ERR_METHOD);
    CHECK(sk_surface_new(SK_SURFACE_PHONG, 0.5f, SK_FRACTION_CONSTANT, 0.5f, 0.0f, SK_CROSSING_FOLD, &s) == SK_ERR_DOMAIN);
    CHECK(sk_surface_new(SK_SURFACE_PHONG, 2e6f, SK_FRACTION_CONSTANT, 0.5f, 0.0f, SK_CROSSING_FOLD, &s) == SK_ERR_DOMAIN);
    CHECK(sk_surface_new(SK_SURFACE_PHONG, NAN, SK_FRACTION_CONSTANT, 0.5f, 0.0f, SK_CROSSING_FOLD, &s) == SK_ERR_DOMAIN);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 1.0f, SK_FRACTION_CONSTANT, 1.5f, 0.0f, SK_CROSSING_FOLD, &s) == SK_ERR_DOMAIN);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 1.0f, SK_FRACTION_CONSTANT, -0.1f, 0.0f, SK_CROSSING_FOLD, &s) == SK_ERR_DOMAIN);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 1.0f, SK_FRACTION_SCALAR, 0.0f, -1e-9f, SK_CROSSING_FOLD, &s) == SK_ERR_DOMAIN);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 1.0f, SK_FRACTION_SCALAR, 0.0f, INFINITY, SK_CROSSING_FOLD, &s) == SK_ERR_DOMAIN);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 1.0f, SK_FRACTION_SCALAR, 0.0f, 1e-9f, SK_CROSSING_FOLD, NULL) == SK_ERR_NULL);
    CHECK(sk_surface_new(SK_SURFACE_LAMBERT, 0.0f, SK_FRACTION_SCALAR, 0.0f, 50e-9f, SK_CROSSING_FOLD, &s) == SK_OK);

    CHECK(sk_surface_interact(NULL, d, n, 1.0f, 1.5f, 600e-9f, &rng, &out, &ev) == SK_ERR_NULL);
    CHECK(sk_surface_interact(&s, d, n, 1.0f, 1.5f, 600e-9f, NULL, &out, &ev) == SK_ERR_NULL);
    CHECK(sk_surface_interact(&s, d, n, 1.0f, 1.5f, 600e-9f, &no_fn, &out, &ev) == SK_ERR_NULL);
    CHECK(sk_surface_interact(&s, d, n, 1.0f, 1.5f, 600e-9f, &rng, NULL, &ev) == SK_ERR_NULL);
    CHECK(sk_surface_interact(&s, d, n, 1.0f, 1.5f, 600e-9f, &rng, &out, NULL) == SK_ERR_NULL);
    CHECK(sk_surface_interact(&s, zero, n, 1.0f, 1.5f, 600e-9f, &rng, &out, &ev) == SK_ERR_DOMAIN);
    CHECK(sk_surface_interact(&s, d, nanv, 1.0f, 1.5f, 600e-9f, &rng, &out, &ev) == SK_ERR_DOMAIN);
    CHECK(sk_surface_interact(&s, d, n, 0.0f, 1.5f, 600e-9f, &rng, &out, &ev) == SK_ERR_DOMAIN);
    CHECK(sk_surface_interact(&s, d, n, 1.0f, NAN, 600e-9f, &rng, &out, &ev) == SK_ERR_DOMAIN);
    CHECK(sk_surface_interact(&s, d, n, 1.0f, 1.5f, -1.0f, &rng, &out, &ev) == SK_ERR_DOMAIN);
    CHECK(out.x == 7.0f && ev == 77);
    bad = s;
    bad.model = 7;
    CHECK(sk_surface_interact(&bad, d, n, 1.0f, 1.5f, 600e-9f, &rng, &out, &ev) == SK_ERR_METHOD);
    bad = s;
    bad.fraction = -1.0f;
    CHECK(sk_surface_interact(&bad, d, n, 1.0f, 1.5f, 600e-9f, &rng, &out, &ev) == SK_ERR_DOMAIN);
    CHECK(sk_surface_interact(&s, d, n, 1.0f, 1.5f, 600e-9f, &rng, &out, &ev) == SK_OK);
    CHECK(ev <= (SK_EVENT_TRANSMITTED | SK_EVENT_SCATTERED));

    CHECK(sk_refract(grazing, n, 1.5f, 1.0f, &r) == SK_ERR_DOMAIN); /* total internal reflection */
    CHECK(sk_refract(d, n, 1.0f, 1.5f, NULL) == SK_ERR_NULL);
    CHECK(sk_refract(d, n, -1.0f, 1.5f, &r) == SK_ERR_DOMAIN);
    CHECK(sk_refract(zero, n, 1.0f, 1.5f, &r) == SK_ERR_DOMAIN);
    CHECK(sk_refract(d, nanv, 1.0f, 1.5f, &r) == SK_ERR_DOMAIN);
    r = sk_reflect(zero, n);
    CHECK(isnan(r.x));
    CHECK(isnan(sk_fresnel_dielectric(0.5f, 0.0f, 1.5f)) && isnan(sk_fresnel_dielectric(2.0f, 1.0f, 1.5f)));
    CHECK(sk_fresnel_dielectric(0.1f, 1.5f, 1.0f) == 1.0f);
    r = sk_lambert_sample(zero, 0.5f, 0.5f);
    CHECK(isnan(r.x));
    r = sk_phong_sample(n, n, 0.5f, SK_CROSSING_FOLD, 0.5f, 0.5f);
    CHECK(isnan(r.x));
    r = sk_phong_sample(n, n, 2e6f, SK_CROSSING_FOLD, 0.5f, 0.5f);
    CHECK(isnan(r.x));
    r = sk_phong_sample(n, n, 10.0f, 9, 0.5f, 0.5f);
    CHECK(isnan(r.x));
    r = sk_phong_sample(grazing, n, 1.0f, SK_CROSSING_RESAMPLE, 0.999f, 0.5f);
    CHECK(r.z >= 0.0f);
    CHECK(isnan(sk_scatter_fraction_reflect(0.0f, 1e-9f, 1.5f, 1.0f)));
    CHECK(isnan(sk_scatter_fraction_reflect(600e-9f, -1e-9f, 1.5f, 1.0f)));
    CHECK(isnan(sk_scatter_fraction_transmit(600e-9f, 1e-9f, 1.5f, 1.0f, 0.0f, 1.0f)));
    CHECK(isnan(sk_scatter_fraction_transmit(600e-9f, 1e-9f, 1.5f, 1.0f, 3.9f, 1.5f)));
}

static sk_coefficients dense(void *ctx, sk_vec3 p) {
    sk_coefficients c = {2.5f, 2.5f}; /* above the majorant the caller claims */
    (void)ctx;
    (void)p;
    return c;
}

/* Tracking arguments through grid g or coefficients f (one majorant 1). */
static sk_track_args track_args(const sk_grid *g, sk_medium_fn f, sk_vec3 o, sk_vec3 d, float t_min, float t_max, sk_rng *rng) {
    sk_track_args a;
    memset(&a, 0, sizeof a);
    a.medium.grid = g;
    a.medium.coefficients = f;
    a.medium.sigma_maj = 1.0f;
    a.o = o;
    a.d = d;
    a.t_min = t_min;
    a.t_max = t_max;
    a.rng = rng;
    return a;
}

static void media(void) {
    uint64_t state = 5;
    sk_rng rng = {&state, counter}, no_fn = {&state, NULL};
    const float st[2] = {1.0f, 2.0f}, ss[2] = {0.5f, 1.0f}, bad_ss[2] = {1.5f, 1.0f};
    const float values[8] = {1, 1, 1, 1, 1, 1, 1, 1}, negative[2] = {1.0f, -1.0f}, nan_values[2] = {1.0f, NAN};
    float w[2] = {7.0f, 7.0f}, t = 7.0f, overlap[4] = {1.0f, 2.0f, 0.5f, 1.0f};
    uint32_t ev = 77;
    sk_grid g, bogus;
    sk_track_args a;
    sk_track_result r;
    sk_vec3 o = {-1.0f, 0.5f, 0.5f}, d = {1.0f, 0.0f, 0.0f}, zero = {0.0f, 0.0f, 0.0f}, nanv = {NAN, 0.0f, 0.0f};

    CHECK(isnan(sk_free_path(-1.0f, 0.5f)) && isnan(sk_free_path(NAN, 0.5f)) && isnan(sk_free_path(INFINITY, 0.5f)));
    CHECK(isinf(sk_free_path(0.0f, 0.5f)) && isinf(sk_free_path(1.0f, 1.0f)) && sk_free_path(1.0f, -5.0f) == 0.0f);
    CHECK(isnan(sk_free_path(1.0f, NAN)));
    CHECK(isnan(sk_transmittance(-1.0f, 1.0f)) && isnan(sk_transmittance(1.0f, -1.0f)) && isnan(sk_transmittance(NAN, 1.0f)));
    CHECK(sk_transmittance(0.0f, INFINITY) == 1.0f && sk_transmittance(1.0f, INFINITY) == 0.0f);

    CHECK(sk_homogeneous_sample(st, ss, 0, 1.0f, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_SIZE);
    CHECK(sk_homogeneous_sample(NULL, ss, 2, 1.0f, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_NULL);
    CHECK(sk_homogeneous_sample(st, NULL, 2, 1.0f, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_NULL);
    CHECK(sk_homogeneous_sample(st, ss, 2, 1.0f, 0.5f, 0.5f, NULL, &ev, w) == SK_ERR_NULL);
    CHECK(sk_homogeneous_sample(st, ss, 2, 1.0f, 0.5f, 0.5f, &t, NULL, w) == SK_ERR_NULL);
    CHECK(sk_homogeneous_sample(st, ss, 2, 1.0f, 0.5f, 0.5f, &t, &ev, NULL) == SK_ERR_NULL);
    CHECK(sk_homogeneous_sample(st, bad_ss, 2, 1.0f, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_DOMAIN);
    CHECK(sk_homogeneous_sample(st, ss, 2, -1.0f, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_DOMAIN);
    CHECK(sk_homogeneous_sample(st, ss, 2, NAN, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_DOMAIN);
    CHECK(sk_homogeneous_sample(st, ss, SIZE_MAX, 1.0f, 0.5f, 0.5f, &t, &ev, w) == SK_ERR_SIZE);
    CHECK(sk_homogeneous_sample(overlap, overlap + 2, 2, 1.0f, 0.5f, 0.5f, &t, &ev, overlap + 1) == SK_ERR_OVERLAP);
    CHECK(w[0] == 7.0f && t == 7.0f && ev == 77);
    CHECK(sk_homogeneous_sample(st, ss, 2, INFINITY, 0.5f, 0.5f, &t, &ev, w) == SK_OK && ev == 1);

    CHECK(sk_grid_new(values, 0, 2, 2, 1.0f, 1.0f, &g) == SK_ERR_SIZE);
    CHECK(sk_grid_new(values, 2, 0, 2, 1.0f, 1.0f, &g) == SK_ERR_SIZE);
    CHECK(sk_grid_new(values, UINT32_MAX, UINT32_MAX, UINT32_MAX, 1.0f, 1.0f, &g) == SK_ERR_SIZE);
    CHECK(sk_grid_new(NULL, 2, 2, 2, 1.0f, 1.0f, &g) == SK_ERR_NULL);
    CHECK(sk_grid_new(values, 2, 2, 2, 1.0f, 1.0f, NULL) == SK_ERR_NULL);
    CHECK(sk_grid_new(negative, 2, 1, 1, 1.0f, 1.0f, &g) == SK_ERR_DOMAIN);
    CHECK(sk_grid_new(nan_values, 2, 1, 1, 1.0f, 1.0f, &g) == SK_ERR_DOMAIN);
    CHECK(sk_grid_new(values, 2, 2, 2, -1.0f, 1.0f, &g) == SK_ERR_DOMAIN);
    CHECK(sk_grid_new(values, 2, 2, 2, 1.0f, INFINITY, &g) == SK_ERR_DOMAIN);
    CHECK(sk_grid_new(values, 2, 2, 2, 1.0f, 1.0f, &g) == SK_OK);
    CHECK(sk_grid_density(&g, o) == 0.0f && sk_grid_coefficients(&g, d).sigma_s == 1.0f);
    CHECK(isnan(sk_grid_density(NULL, o)));

    a = track_args(&g, NULL, o, d, 0.0f, 3.0f, &rng);
    CHECK(sk_delta_track(NULL, &r) == SK_ERR_NULL && sk_delta_track(&a, NULL) == SK_ERR_NULL);
    a.medium.grid = NULL;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_NULL);
    a = track_args(&g, NULL, o, d, 0.0f, 3.0f, NULL);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_NULL);
    a.rng = &no_fn;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_NULL);
    r.t = 7.0f;
    a = track_args(&g, NULL, o, zero, 0.0f, 3.0f, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN && r.t == 7.0f);
    a = track_args(&g, NULL, nanv, d, 0.0f, 3.0f, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN);
    a = track_args(&g, NULL, o, d, 0.0f, -1.0f, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN);
    a = track_args(&g, NULL, o, d, 0.0f, NAN, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN);
    /* A grid sk_grid_new never built. */
    memset(&bogus, 0, sizeof bogus);
    a = track_args(&bogus, NULL, o, d, 0.0f, 3.0f, &rng);
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN && sk_ratio_track(&a, &r) == SK_ERR_DOMAIN);
    a = track_args(&g, NULL, o, zero, 0.0f, 3.0f, &rng);
    CHECK(sk_ratio_track(&a, &r) == SK_ERR_DOMAIN);
    {
        sk_vec3 away = {5.0f, 5.0f, 5.0f};
        a = track_args(&g, NULL, away, d, 0.0f, 3.0f, &rng);
        CHECK(sk_delta_track(&a, &r) == SK_OK && r.event == SK_TRACK_ESCAPED && r.t == 0.0f); /* t_min */
        CHECK(sk_ratio_track(&a, &r) == SK_OK && r.tr == 1.0f && r.steps == 0);
    }

    a = track_args(NULL, dense, o, d, 0.0f, 1.0f, &rng);
    a.rng = NULL;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_NULL);
    a.rng = &rng;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN); /* above the majorant */
    CHECK(sk_ratio_track(&a, &r) == SK_ERR_DOMAIN);
    a.medium.sigma_maj = 10.0f, a.t_min = 2.0f; /* t_max < t_min */
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN);
    a.medium.sigma_maj = -1.0f, a.t_min = 0.0f;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN);
    a.medium.sigma_maj = 10.0f, a.d = zero;
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN);
    a.d = d, a.t_max = INFINITY; /* one majorant and no box: nowhere to escape to */
    CHECK(sk_delta_track(&a, &r) == SK_ERR_DOMAIN && sk_ratio_track(&a, &r) == SK_ERR_DOMAIN);
    a.t_max = 1.0f, a.medium.sigma_maj = 0.0f;
    CHECK(sk_delta_track(&a, &r) == SK_OK && r.event == SK_TRACK_ESCAPED);
    a.medium.sigma_maj = 10.0f;
    CHECK(sk_delta_track(&a, &r) == SK_OK);
}

static void basis_and_version(void) {
    sk_vec3 n = {0.0f, 0.0f, -1.0f}, b1 = {7, 7, 7}, b2 = {7, 7, 7};
    char expected[64];
    sk_onb(n, NULL, &b2); /* NULL out: writes nothing */
    CHECK(b2.x == 7.0f);
    sk_onb(n, &b1, &b2);
    CHECK(b1.x == 1.0f && b1.y == 0.0f && b2.y == -1.0f);
    snprintf(expected, sizeof expected, "%d.%d.%d", SK_VERSION_MAJOR, SK_VERSION_MINOR,
             SK_VERSION_PATCH);
    CHECK(strcmp(sk_version(), expected) == 0);
}

int main(void) {
    phase_constructors();
    scattering_phases();
    phase_queries();
    rayleigh_methods();
    tables();
    coefficients_and_cbrt();
    surfaces();
    media();
    basis_and_version();
    printf("bad_input: %d checks passed, %d failed\n", passed, failed);
    return failed;
}
