/* The direction batches agree with the scalar calls bit for bit: every phase
 * kind (float and double) through sk_phase_sample_dir_n, in place and not,
 * with and without pdf_out, at lengths across the 64-element block, and with
 * each direction's cos theta (sk_phase_sample_dir_cos_n and its twins); every
 * Rayleigh method through sk_rayleigh_sample_dir_n against n scalar calls
 * with a copy of the generator. Exits with the number of failures. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "scatterkit.h"

#define CHECK_CASE k
#include "check.h"

enum { N = 203 }; /* three full blocks and a tail */

static uint64_t splitmix(void *state) {
    uint64_t z = (*(uint64_t *)state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}
static double uniform(uint64_t *s) { return (double)(splitmix(s) >> 11) * 0x1p-53; }

static float wx[N], wy[N], wz[N], u1[N], u2[N], ox[N], oy[N], oz[N], pdf[N];
static double dx[N], dy[N], dz[N], v1[N], v2[N], px[N], py[N], pz[N], pdfd[N];

static void fill(void) {
    uint64_t s = 5;
    int i;
    for (i = 0; i < N; i++) {
        /* Unit directions: points of the cube, normalised. */
        double x = 2 * uniform(&s) - 1, y = 2 * uniform(&s) - 1, z = 2 * uniform(&s) + 0.5;
        double l = sqrt(x * x + y * y + z * z);
        dx[i] = x / l, dy[i] = y / l, dz[i] = (i % 2 ? z : -z) / l;
        wx[i] = (float)dx[i], wy[i] = (float)dy[i], wz[i] = (float)dz[i];
        v1[i] = uniform(&s), v2[i] = uniform(&s);
        u1[i] = (float)v1[i], u2[i] = (float)v2[i];
    }
    /* The ends of the uniform range. */
    u1[0] = 0.0f, u2[0] = 1.0f, v1[1] = 1.0, v2[1] = 0.0;
}

static int same(const void *a, const void *b) { return memcmp(a, b, 4) == 0; }
static int same_d(const void *a, const void *b) { return memcmp(a, b, 8) == 0; }

static void phase_batches(const sk_phase *p, const sk_phase_f64 *q, int k) {
    static const size_t lengths[4] = {1, 63, 64, N};
    size_t li, i;
    for (li = 0; li < 4; li++) {
        size_t n = lengths[li];
        int ok = 1;
        CHECK(sk_phase_sample_dir_n(p, wx, wy, wz, u1, u2, ox, oy, oz, pdf, n) == SK_OK);
        CHECK(sk_phase_sample_dir_n_f64(q, dx, dy, dz, v1, v2, px, py, pz, pdfd, n) == SK_OK);
        for (i = 0; i < n; i++) {
            float pf;
            double pd;
            sk_vec3 w = {wx[i], wy[i], wz[i]};
            sk_vec3_f64 wd = {dx[i], dy[i], dz[i]};
            sk_vec3 d = sk_phase_sample_dir(p, w, u1[i], u2[i], &pf);
            sk_vec3_f64 e = sk_phase_sample_dir_f64(q, wd, v1[i], v2[i], &pd);
            ok &= same(&d.x, &ox[i]) && same(&d.y, &oy[i]) && same(&d.z, &oz[i]) && same(&pf, &pdf[i]);
            ok &= same_d(&e.x, &px[i]) && same_d(&e.y, &py[i]) && same_d(&e.z, &pz[i]) && same_d(&pd, &pdfd[i]);
        }
        CHECK(ok);
    }
    {
        /* In place, without densities: the same directions. */
        float ix[N], iy[N], iz[N];
        int ok = 1;
        memcpy(ix, wx, sizeof wx);
        memcpy(iy, wy, sizeof wy);
        memcpy(iz, wz, sizeof wz);
        CHECK(sk_phase_sample_dir_n(p, wx, wy, wz, u1, u2, ox, oy, oz, NULL, N) == SK_OK);
        CHECK(sk_phase_sample_dir_n(p, ix, iy, iz, u1, u2, ix, iy, iz, NULL, N) == SK_OK);
        for (i = 0; i < N; i++) ok &= same(&ix[i], &ox[i]) && same(&iy[i], &oy[i]) && same(&iz[i], &oz[i]);
        CHECK(ok);
    }
}

/* The batches with cos theta: the directions and densities of
   sk_phase_sample_dir_n, bit for bit, and each cosine sk_phase_sample_cos's
   at the same u1 (the portable batch: the header's cos_theta, which is
   sk_phase_sample_cos_n_portable's); a NULL cos_out and an overlap refused. */
static void cos_batches(const sk_phase *p, const sk_phase_f64 *q, int k, int portable) {
    static float cx[N], cy[N], cz[N], cpdf[N], cosv[N], want[N];
    static double ex[N], ey[N], ez[N], epdf[N], cosd[N];
    size_t i;
    int ok = 1;
    CHECK(sk_phase_sample_dir_n(p, wx, wy, wz, u1, u2, ox, oy, oz, pdf, N) == SK_OK);
    CHECK(sk_phase_sample_dir_cos_n(p, wx, wy, wz, u1, u2, cx, cy, cz, cosv, cpdf, N) == SK_OK);
    CHECK(sk_phase_sample_dir_n_f64(q, dx, dy, dz, v1, v2, px, py, pz, pdfd, N) == SK_OK);
    CHECK(sk_phase_sample_dir_cos_n_f64(q, dx, dy, dz, v1, v2, ex, ey, ez, cosd, epdf, N) == SK_OK);
    for (i = 0; i < N; i++) {
        float c = sk_phase_sample_cos(p, u1[i]);
        double cd = sk_phase_sample_cos_f64(q, v1[i]);
        ok &= same(&cx[i], &ox[i]) && same(&cy[i], &oy[i]) && same(&cz[i], &oz[i]) && same(&cpdf[i], &pdf[i]);
        ok &= same(&c, &cosv[i]) && same_d(&cd, &cosd[i]);
        ok &= same_d(&ex[i], &px[i]) && same_d(&ey[i], &py[i]) && same_d(&ez[i], &pz[i]) && same_d(&epdf[i], &pdfd[i]);
    }
    CHECK(ok);
    CHECK(sk_phase_sample_dir_cos_n(p, wx, wy, wz, u1, u2, cx, cy, cz, NULL, cpdf, N) == SK_ERR_NULL);
    CHECK(sk_phase_sample_dir_cos_n(p, wx, wy, wz, u1, u2, cx, cy, cz, cx, NULL, N) == SK_ERR_OVERLAP);
    CHECK(sk_phase_sample_dir_cos_n(p, wx, wy, wz, u1, u2, cx, cy, cz, cosv, NULL, N) == SK_OK);
    if (portable) {
        ok = 1;
        CHECK(sk_phase_sample_dir_n_portable(p, wx, wy, wz, u1, u2, ox, oy, oz, pdf, N) == SK_OK);
        CHECK(sk_phase_sample_dir_cos_n_portable(p, wx, wy, wz, u1, u2, cx, cy, cz, cosv, cpdf, N) == SK_OK);
        CHECK(sk_phase_sample_cos_n_portable(p, u1, want, N) == SK_OK);
        for (i = 0; i < N; i++) {
            ok &= same(&cx[i], &ox[i]) && same(&cy[i], &oy[i]) && same(&cz[i], &oz[i]) && same(&cpdf[i], &pdf[i]);
            ok &= same(&want[i], &cosv[i]);
        }
        CHECK(ok);
    } else {
        CHECK(sk_phase_sample_dir_cos_n_portable(p, wx, wy, wz, u1, u2, cx, cy, cz, cosv, cpdf, N) ==
              SK_ERR_METHOD);
    }
}

static void rayleigh_batches(uint32_t m, int k) {
    uint64_t s1 = 99, s2 = 99;
    sk_rng batch = {&s1, splitmix}, scalar = {&s2, splitmix};
    size_t i;
    int ok = 1;
    CHECK(sk_rayleigh_sample_dir_n(m, wx, wy, wz, &batch, ox, oy, oz, N) == SK_OK);
    for (i = 0; i < N; i++) {
        sk_vec3 w = {wx[i], wy[i], wz[i]}, d;
        CHECK(sk_rayleigh_sample_dir(m, w, &scalar, &d) == SK_OK);
        ok &= same(&d.x, &ox[i]) && same(&d.y, &oy[i]) && same(&d.z, &oz[i]);
    }
    CHECK(ok && s1 == s2);
    ok = 1;
    CHECK(sk_rayleigh_sample_dir_n_f64(m, dx, dy, dz, &batch, px, py, pz, N) == SK_OK);
    for (i = 0; i < N; i++) {
        sk_vec3_f64 w = {dx[i], dy[i], dz[i]}, d;
        CHECK(sk_rayleigh_sample_dir_f64(m, w, &scalar, &d) == SK_OK);
        ok &= same_d(&d.x, &px[i]) && same_d(&d.y, &py[i]) && same_d(&d.z, &pz[i]);
    }
    CHECK(ok && s1 == s2);
}

int main(void) {
    int k;
    sk_phase p[10];
    sk_phase_f64 q[10];
    fill();
    sk_phase_new_isotropic(&p[0]), sk_phase_new_isotropic_f64(&q[0]);
    sk_phase_new_rayleigh(&p[1]), sk_phase_new_rayleigh_f64(&q[1]);
    sk_phase_new_hg(0.7f, &p[2]), sk_phase_new_hg_f64(0.7, &q[2]);
    sk_phase_new_hg(-0.95f, &p[3]), sk_phase_new_hg_f64(-0.95, &q[3]);
    sk_phase_new_draine(0.5f, 1.0f, &p[4]), sk_phase_new_draine_f64(0.5, 1.0, &q[4]);
    sk_phase_new_fog_diameter(2.0f, &p[5]), sk_phase_new_fog_diameter_f64(2.0, &q[5]);
    sk_phase_new_rayleigh_depolarized(0.03f, &p[6]), sk_phase_new_rayleigh_depolarized_f64(0.03, &q[6]);
    sk_phase_new_two_lobe_hg(0.8f, -0.3f, 0.9f, &p[7]), sk_phase_new_two_lobe_hg_f64(0.8, -0.3, 0.9, &q[7]);
    sk_phase_new_gegenbauer(-0.25f, 0.7f, &p[8]), sk_phase_new_gegenbauer_f64(-0.25, 0.7, &q[8]);
    sk_phase_new_fournier_forand(1.1f, 4.0f, &p[9]), sk_phase_new_fournier_forand_f64(1.1, 4.0, &q[9]);
    for (k = 0; k < 10; k++) phase_batches(&p[k], &q[k], k);
    for (k = 0; k < 10; k++) cos_batches(&p[k], &q[k], k, k < 4);
    for (k = SK_RAYLEIGH_REJECT_CUBE; k <= SK_RAYLEIGH_TABLE; k++) rayleigh_batches((uint32_t)k, k);
    printf("%d passed, %d failed\n", passed, failed);
    return failed;
}
