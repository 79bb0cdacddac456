/* The edge sweep: valid calls at the edges of each documented domain, from C,
 * checking what every answer must satisfy, never a value fixed in advance.
 * A call returns SK_OK with an answer inside its range (a distance inside the
 * segment, a transmittance in [0, 1], a unit direction on the documented
 * side, a reflectance in [0, 1], finite efficiencies and densities), or the
 * status its documentation gives (SK_ERR_DOMAIN, SK_ERR_BUDGET); never NaN
 * with SK_OK. The edges: origins at the box's faces and corners and at
 * +-DBL_MAX, subnormal, huge and axis-aligned directions, empty, infinite,
 * tiny and huge segments; grazing and normal incidence on matched and
 * mismatched interfaces; rays through the point an equiangular sampler aims
 * at; vacuum and DBL_MAX channels; dark, tiny, huge and fully polarised
 * Stokes vectors; Mie spheres at the ends of x and m; the portable header's
 * majorant walk (skp_walk_begin and skp_walk_step) through seven boxes, from
 * a unit cube to one spanning -FLT_MAX to FLT_MAX, each collision in its
 * cell with its cell's majorant.
 * Written with the faults it found: a matched Fresnel interface gave NaN at
 * grazing incidence and bent the refracted ray, refraction at an index
 * ratio of 1e17 gave NaN with SK_OK, polarised Rayleigh a NaN direction
 * for fully polarised light at u1 = 1/2 and a density of -1.8e-17 at the
 * dipole's null, and Mie gave NaN with SK_OK at m = 1 and at tiny |m|
 * (820 failed checks against the library before those fixes), and the walk
 * returned 0 (a miss) for a ray beyond float range in cell units when an
 * earlier axis missed, -1 when none did (6412 failed checks). The sweep
 * also found two that tests/c/matrix.c now checks
 * by value: an escape through a grid without majorants reported t_max,
 * and a march too long for any budget SK_ERR_DOMAIN. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scatterkit.h"
#include "scatterkit_portable.h"

static int i;
#define CHECK_CASE i
#include "check.h"

#define PI 3.14159265358979323846

static uint64_t counter(void *state) {
    uint64_t *s = (uint64_t *)state;
    return *s += 0x9e3779b97f4a7c15ULL;
}

/* ---- tracking ---------------------------------------------------------- */

static sk_coefficients_f64 flat64(void *ctx, sk_vec3_f64 p) {
    sk_coefficients_f64 c = {0.25, 0.5};
    (void)ctx, (void)p;
    return c;
}
static sk_coefficients_f64 wave64(void *ctx, sk_vec3_f64 p) {
    sk_coefficients_f64 c;
    (void)ctx;
    c.sigma_a = 0.0, c.sigma_s = 0.5 + 0.25 * sin(p.z);
    return c;
}
static sk_coefficients flat32(void *ctx, sk_vec3 p) {
    sk_coefficients c = {0.25f, 0.5f};
    (void)ctx, (void)p;
    return c;
}
static sk_coefficients wave32(void *ctx, sk_vec3 p) {
    sk_coefficients c;
    (void)ctx;
    c.sigma_a = 0.0f, c.sigma_s = 0.5f + 0.25f * sinf(p.z);
    return c;
}

typedef sk_status (*track64)(const sk_track_args_f64 *, sk_track_result_f64 *);
typedef sk_status (*track32)(const sk_track_args *, sk_track_result *);
enum { DELTA, RATIO, RESIDUAL, MARCH, TELESCOPING, EMISSION, ESTIMATORS };
static const track64 EST64[ESTIMATORS] = {sk_delta_track_f64,  sk_ratio_track_f64,       sk_residual_ratio_track_f64,
                                          sk_ray_march_f64,    sk_telescoping_march_f64, sk_emission_track_f64};
static const track32 EST32[ESTIMATORS] = {sk_delta_track, sk_ratio_track,       sk_residual_ratio_track,
                                          sk_ray_march,   sk_telescoping_march, sk_emission_track};

/* The media: 0 a grid, 1 the grid with majorants, 2 a callback with one
   majorant, 3 a varying callback with majorants (and minorants), 4 the grid
   with majorants and emission, 5 the varying callback with one majorant.
   Whether estimator e takes medium m at all (emission needs a source,
   residual ratio tracking minorants). */
static int takes(int e, int m) {
    if (e == EMISSION) return m == 4;
    if (e == RESIDUAL) return m == 1 || m == 3 || m == 4;
    return 1;
}

/* What an SK_OK answer must satisfy. */
static int answer_ok(int e, double t_min, double t_max, double t, double tr, double radiance, sk_track_event ev) {
    switch (e) {
    case DELTA: return t >= t_min && t <= t_max && ev <= SK_TRACK_COLLIDED;
    case RATIO:
    case RESIDUAL: return tr >= 0.0 && tr <= 1.0;
    case EMISSION: return tr >= 0.0 && tr <= 1.0 && radiance >= 0.0 && isfinite(radiance);
    default: return isfinite(tr); /* marches may leave [0, 1] */
    }
}

static void tracking_f64(void) {
    static double dens[64], mx[8], mn[8], em[64], cm[8], zero[8];
    sk_grid_f64 grid, emg;
    sk_majorants_f64 maj, cmaj;
    uint64_t st = 1;
    sk_rng rng = {&st, counter};
    const double T = DBL_MAX, S = 4.9406564584124654e-324, N = DBL_MIN;
    const sk_vec3_f64 os[10] = {{.5, .5, .5}, {0, .5, .5}, {1, 1, 1},     {-1e300, .5, .5}, {.5, .5, -1e15},
                                {S, S, S},    {.5, .5, 1e-300}, {-T, -T, -T}, {2, 2, 2},  {.5, .5, -1}};
    const sk_vec3_f64 ds[10] = {{0, 0, 1},  {1, 1, 1},       {S, 0, 0}, {T, T, 0}, {0, 0, -1},
                                {1e-200, 1, 0}, {N, N, N}, {-1, 1e-300, 0}, {.6, .8, 0}, {T, T, T}};
    const double seg[10][2] = {{0, INFINITY}, {0, T},  {0, 0},   {1e300, INFINITY}, {.5, .5},
                               {0, 1e-300},   {0, 1},  {T, T},   {0, 1e16},         {1e-320, 3}};
    const sk_vec3_f64 lo = {-2, -2, -2}, hi = {2, 2, 2};
    int k, m, o, d, s, e;
    for (k = 0; k < 64; k++) dens[k] = (k % 7) / 7.0, em[k] = 1.0;
    for (k = 0; k < 8; k++) cm[k] = 0.75;
    CHECK(sk_grid_new_f64(dens, 4, 4, 4, 0.3, 0.7, &grid) == SK_OK && sk_grid_new_f64(em, 4, 4, 4, 0, 1, &emg) == SK_OK);
    CHECK(sk_majorants_new_from_grid_f64(&grid, 2, 2, 2, mx, mn, 8, &maj) == SK_OK);
    /* The callback's majorants, with minorants of 0 for residual ratio tracking. */
    CHECK(sk_majorants_new_f64(cm, zero, 2, 2, 2, lo, hi, &cmaj) == SK_OK);
    for (m = 0; m < 6; m++)
        for (e = 0; e < ESTIMATORS; e++)
            for (o = 0; o < 10; o++)
                for (d = 0; d < 10; d++)
                    for (s = 0; s < 10; s++) {
                        sk_track_args_f64 a;
                        sk_track_result_f64 r;
                        sk_status q;
                        if (!takes(e, m)) continue;
                        memset(&a, 0, sizeof a);
                        a.rng = &rng, a.o = os[o], a.d = ds[d], a.t_min = seg[s][0], a.t_max = seg[s][1];
                        a.budget = 100000;
                        if (m == 0 || m == 1 || m == 4) a.medium.grid = &grid;
                        if (m == 1 || m == 4) a.medium.majorants = &maj;
                        if (m == 4) a.medium.emission = &emg;
                        if (m == 2) a.medium.coefficients = flat64, a.medium.sigma_maj = 0.75;
                        if (m == 3) a.medium.coefficients = wave64, a.medium.majorants = &cmaj;
                        if (m == 5) a.medium.coefficients = wave64, a.medium.sigma_maj = 0.75;
                        i = ((m * ESTIMATORS + e) * 10 + o) * 100 + d * 10 + s;
                        q = EST64[e](&a, &r);
                        CHECK(q == SK_OK || q == SK_ERR_DOMAIN || q == SK_ERR_BUDGET);
                        if (q == SK_OK) CHECK(answer_ok(e, a.t_min, a.t_max, r.t, r.tr, r.radiance, r.event));
                    }
    i = 0;
}

static void tracking_f32(void) {
    static float dens[64], mx[8], mn[8], em[64], cm[8], zero[8];
    sk_grid grid, emg;
    sk_majorants maj, cmaj;
    uint64_t st = 2;
    sk_rng rng = {&st, counter};
    const float T = FLT_MAX, S = 1.40129846e-45f, N = FLT_MIN;
    const sk_vec3 os[10] = {{.5f, .5f, .5f}, {0, .5f, .5f}, {1, 1, 1},   {-1e30f, .5f, .5f}, {.5f, .5f, -1e7f},
                            {S, S, S},       {.5f, .5f, 1e-30f}, {-T, -T, -T}, {2, 2, 2}, {.5f, .5f, -1}};
    const sk_vec3 ds[10] = {{0, 0, 1},     {1, 1, 1}, {S, 0, 0},      {T, T, 0},     {0, 0, -1},
                            {1e-20f, 1, 0}, {N, N, N}, {-1, 1e-30f, 0}, {.6f, .8f, 0}, {T, T, T}};
    const float seg[10][2] = {{0, INFINITY}, {0, T}, {0, 0}, {1e30f, INFINITY}, {.5f, .5f},
                              {0, 1e-30f},   {0, 1}, {T, T}, {0, 1e8f},         {1e-40f, 3}};
    const sk_vec3 lo = {-2, -2, -2}, hi = {2, 2, 2};
    int k, m, o, d, s, e;
    for (k = 0; k < 64; k++) dens[k] = (float)(k % 7) / 7.0f, em[k] = 1.0f;
    for (k = 0; k < 8; k++) cm[k] = 0.75f;
    CHECK(sk_grid_new(dens, 4, 4, 4, 0.3f, 0.7f, &grid) == SK_OK && sk_grid_new(em, 4, 4, 4, 0, 1, &emg) == SK_OK);
    CHECK(sk_majorants_new_from_grid(&grid, 2, 2, 2, mx, mn, 8, &maj) == SK_OK);
    CHECK(sk_majorants_new(cm, zero, 2, 2, 2, lo, hi, &cmaj) == SK_OK);
    for (m = 0; m < 6; m++)
        for (e = 0; e < ESTIMATORS; e++)
            for (o = 0; o < 10; o++)
                for (d = 0; d < 10; d++)
                    for (s = 0; s < 10; s++) {
                        sk_track_args a;
                        sk_track_result r;
                        sk_status q;
                        if (!takes(e, m)) continue;
                        memset(&a, 0, sizeof a);
                        a.rng = &rng, a.o = os[o], a.d = ds[d], a.t_min = seg[s][0], a.t_max = seg[s][1];
                        a.budget = 100000;
                        if (m == 0 || m == 1 || m == 4) a.medium.grid = &grid;
                        if (m == 1 || m == 4) a.medium.majorants = &maj;
                        if (m == 4) a.medium.emission = &emg;
                        if (m == 2) a.medium.coefficients = flat32, a.medium.sigma_maj = 0.75f;
                        if (m == 3) a.medium.coefficients = wave32, a.medium.majorants = &cmaj;
                        if (m == 5) a.medium.coefficients = wave32, a.medium.sigma_maj = 0.75f;
                        i = 1000000 + ((m * ESTIMATORS + e) * 10 + o) * 100 + d * 10 + s;
                        q = EST32[e](&a, &r);
                        CHECK(q == SK_OK || q == SK_ERR_DOMAIN || q == SK_ERR_BUDGET);
                        if (q == SK_OK) CHECK(answer_ok(e, a.t_min, a.t_max, r.t, r.tr, r.radiance, r.event));
                    }
    i = 0;
}

/* ---- surfaces ---------------------------------------------------------- */

typedef sk_vec3_f64 V;
static double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static double len3(V a) { return sqrt(dot(a, a)); }
static V along(V a, double k) {
    V r;
    r.x = a.x * k, r.y = a.y * k, r.z = a.z * k;
    return r;
}
static V plus(V a, V b) {
    V r;
    r.x = a.x + b.x, r.y = a.y + b.y, r.z = a.z + b.z;
    return r;
}
static int unit(V a) { return fabs(len3(a) - 1.0) < 1e-12; }

/* A unit direction at cosine c to unit n (c < 0: against it), turned by
   `turn` eighths of a circle about it. */
static V at_cosine(V n, double c, int turn) {
    V t1, t2;
    double sn = sqrt((1.0 - c) * (1.0 + c)), phi = turn * PI / 4.0;
    t1.x = fabs(n.x) < 0.9 ? 1.0 : 0.0, t1.y = fabs(n.x) < 0.9 ? 0.0 : 1.0, t1.z = 0.0;
    t1 = plus(t1, along(n, -dot(t1, n)));
    t1 = along(t1, 1.0 / len3(t1));
    t2.x = n.y * t1.z - n.z * t1.y, t2.y = n.z * t1.x - n.x * t1.z, t2.z = n.x * t1.y - n.y * t1.x;
    return plus(along(n, c), plus(along(t1, sn * cos(phi)), along(t2, sn * sin(phi))));
}

static void surfaces(void) {
    const double r3 = 1.0 / sqrt(3.0);
    const V ns[5] = {{0, 0, 1}, {0, 0, -1}, {r3, r3, r3}, {0.6, 0, 0.8}, {0, 1, 0}};
    /* Incidence cosines (of the travel direction against the normal). */
    const double cs[12] = {-1, -0.9999999999, -0.7, -0.5, -1e-8, -1e-300, 0, 1e-300, 1e-8, 0.5, 0.9999999999, 1};
    /* Index pairs: matched, near-matched, each way, silicon-air, extremes. */
    const double idx[12][2] = {{1, 1.5}, {1.5, 1}, {1, 1},    {1.33, 1.33}, {3.5, 1},
                               {1, 3.5}, {1.33, 1.3300001}, {1.3300001, 1.33}, {1e6, 1}, {1, 1e6},
                               {67108864.0, 1}, {1e17, 1}};
    const double us[5] = {0, 1e-300, 0.5, 1 - 1e-16, 1};
    int a, b, c, k, p, q;
    for (a = 0; a < 5; a++)
        for (b = 0; b < 12; b++)
            for (c = 0; c < 12; c++)
                for (k = 0; k < 8; k++) {
                    const V n = ns[a];
                    const double ni = idx[c][0], nt = idx[c][1], ci = cs[b], eta = ni / nt;
                    V d = at_cosine(n, ci, k), r, out;
                    double f = sk_fresnel_dielectric_f64(ci, ni, nt), sin2_t = eta * eta * (1 - ci) * (1 + ci);
                    sk_status s = sk_refract_f64(d, n, ni, nt, &out);
                    i = ((a * 12 + b) * 12 + c) * 8 + k;
                    r = sk_reflect_f64(d, n);
                    CHECK(unit(r) && fabs(dot(r, n) + dot(d, n)) < 1e-12);
                    CHECK(f >= 0.0 && f <= 1.0);
                    if (ni == nt) CHECK(f == 0.0 && s == SK_OK && len3(plus(out, along(d, -1.0))) < 1e-12);
                    if (sin2_t > 1.0 + 1e-9) CHECK(f == 1.0 && s == SK_ERR_DOMAIN);
                    if (eta > 67108864.0) {
                        CHECK(s == SK_ERR_DOMAIN);
                        continue;
                    }
                    if (sin2_t < 1.0 - 1e-9 && ci != 0.0) {
                        /* Snell: the tangential parts, n_i sin_i = n_t sin_t. */
                        V tan_in = plus(d, along(n, -dot(d, n))), tan_out;
                        /* The side the ray goes on to: that of d.n (below 1e-15 the rounding of d
                           and of the dot product decides the side, not the c asked for). */
                        CHECK(s == SK_OK && unit(out));
                        if (fabs(dot(d, n)) > 1e-15) CHECK((dot(out, n) > 0.0) == (dot(d, n) > 0.0));
                        tan_out = plus(out, along(n, -dot(out, n)));
                        CHECK(fabs(ni * len3(tan_in) - nt * len3(tan_out)) <= 1e-6 * ni * len3(tan_in) + 1e-9 * ni);
                    }
                }
    for (a = 0; a < 5; a++)
        for (p = 0; p < 5; p++)
            for (q = 0; q < 5; q++) {
                const V n = ns[a], axis = sk_reflect_f64(at_cosine(n, -0.8, 1), n);
                const double alphas[3] = {1, 10, 1e6};
                int al, pol;
                V l = sk_lambert_sample_f64(n, us[p], us[q]);
                i = (a * 5 + p) * 5 + q;
                /* On the normal's side, to the rounding of an orthonormal basis. */
                CHECK(unit(l) && dot(l, n) >= -1e-15);
                for (al = 0; al < 3; al++)
                    for (pol = 0; pol < 3; pol++) {
                        V ph = sk_phong_sample_f64(axis, n, alphas[al], (sk_crossing_policy)pol, us[p], us[q]);
                        CHECK(unit(ph) && dot(ph, n) >= -1e-15);
                    }
            }
    i = 0;
}

/* ---- equiangular sampling, homogeneous spectral sampling --------------- */

static void equiangular(void) {
    const sk_vec3_f64 os[5] = {{0, 0, 0}, {1e300, 0, 0}, {0, 0, -1e10}, {1e-300, 0, 0}, {3, 4, 5}};
    const sk_vec3_f64 ds[5] = {{0, 0, 1}, {1, 1, 1}, {1e-300, 0, 1e-300}, {1e300, 0, 0}, {0, 1, 0}};
    const sk_vec3_f64 ps[8] = {{1, 0, .5}, {1e-150, 0, .5}, {1e150, 0, .5}, {0, 1e-100, 1e10},
                               {1, 1, 1},  {0, 1e-300, 0},  {5, 5, -1e300}, {1e-5, 0, 1e5}};
    const double seg[9][2] = {{0, 1},     {0, INFINITY}, {0, DBL_MAX},  {.5, .5 + 1e-12},     {1e-300, 2e-300},
                              {1e10, 1e10 + 1}, {0, 1e300}, {.25, .75}, {1e5 - 1e-6, 1e5 + 1e-6}};
    int o, d, p, s, k;
    for (o = 0; o < 5; o++)
        for (d = 0; d < 5; d++)
            for (p = 0; p < 8; p++)
                for (s = 0; s < 9; s++) {
                    sk_equiangular_f64 e;
                    sk_status q = sk_equiangular_new_f64(os[o], ds[d], seg[s][0], seg[s][1], ps[p], &e);
                    double prev = -1.0;
                    i = ((o * 5 + d) * 8 + p) * 9 + s;
                    CHECK(q == SK_OK || q == SK_ERR_DOMAIN);
                    if (q != SK_OK) continue;
                    for (k = 0; k <= 64; k++) {
                        double u = k / 64.0, t = sk_equiangular_sample_f64(&e, u), pdf = sk_equiangular_pdf_f64(&e, t);
                        CHECK(t >= seg[s][0] && t <= seg[s][1] && t >= prev);
                        CHECK(isfinite(pdf) && pdf >= 0.0);
                        prev = t;
                    }
                }
    i = 0;
}

static void homogeneous(void) {
    const double vals[10] = {0, 1e-300, 4.9406564584124654e-324, 1e-10, 0.5, 1, 3, 1e10, 1e300, DBL_MAX};
    const double tms[7] = {0, 1e-300, 1, 1e10, 1e300, DBL_MAX, INFINITY};
    const double us[6] = {0, 1e-17, 0.3, 0.5, 1 - 1e-16, 1};
    int a, b, c, t, p, q;
    for (a = 0; a < 10; a++)
        for (b = 0; b < 10; b++)
            for (c = 0; c < 10; c++)
                for (t = 0; t < 7; t++)
                    for (p = 0; p < 6; p += 2)
                        for (q = 0; q < 6; q++) {
                            double st[3], ss[3], w[3], tt;
                            uint32_t sc;
                            sk_status s;
                            st[0] = vals[a], st[1] = vals[b], st[2] = vals[c];
                            ss[0] = vals[a] * 0.5, ss[1] = vals[b], ss[2] = 0.0;
                            s = sk_homogeneous_sample_f64(st, ss, 3, tms[t], us[p], us[q], &tt, &sc, w);
                            i = ((((a * 10 + b) * 10 + c) * 7 + t) * 6 + p) * 6 + q;
                            CHECK(s == SK_OK && tt >= 0.0 && tt <= tms[t] && (sc == 1 || tt == tms[t]));
                            CHECK(isfinite(w[0]) && isfinite(w[1]) && isfinite(w[2]) && w[0] >= 0 && w[1] >= 0 && w[2] >= 0);
                        }
    i = 0;
}

/* ---- polarised Rayleigh ------------------------------------------------ */

/* |(Q, U, V)| <= I (to rounding), scaled so that huge and tiny I do not
   overflow or underflow the check itself. */
static int physical(const sk_stokes_f64 *s) {
    double q, u, v;
    if (!(s->i >= 0.0) || !isfinite(s->i)) return 0;
    if (s->i == 0.0) return s->q == 0.0 && s->u == 0.0 && s->v == 0.0;
    q = s->q / s->i, u = s->u / s->i, v = s->v / s->i;
    return q * q + u * u + v * v <= 1.0 + 1e-12;
}

static void polarization(void) {
    const double rhos[4] = {0, 0.03, 0.5, 1 - 1e-9}, r2 = 0.70710678118654752;
    const V ks[7] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {r2, r2, 0}, {0.6, 0, 0.8}, {1e-9, 0, 1}, {0, 1e-17, -1}};
    /* Unpolarised; fully polarised along Q (both signs), U and V; dark;
       tiny; huge; partly. */
    const double st[10][4] = {{1, 0, 0, 0}, {1, 1, 0, 0},       {1, -1, 0, 0},      {1, 0, 1, 0},     {1, 0, 0, 1},
                              {0, 0, 0, 0}, {1e-300, 1e-300, 0, 0}, {1e300, 0, 1e300, 0}, {1, 0.6, 0.8, 0}, {1, 0.3, 0, 0.4}};
    const double us[6] = {0, 1e-300, 0.25, 0.5, 1 - 1e-16, 1};
    int a, b, c, p, q;
    for (a = 0; a < 4; a++) {
        sk_rayleigh_polarized_f64 r;
        CHECK(sk_rayleigh_polarized_new_f64(rhos[a], &r) == SK_OK);
        for (b = 0; b < 7; b++)
            for (c = 0; c < 10; c++)
                for (p = 0; p < 6; p++)
                    for (q = 0; q < 6; q++) {
                        const V k = along(ks[b], 1.0 / len3(ks[b]));
                        sk_stokes_f64 s;
                        sk_stokes_sample_f64 o, o2;
                        s.i = st[c][0], s.q = st[c][1], s.u = st[c][2], s.v = st[c][3];
                        s.reference = sk_meridian_reference_f64(k, 0.3);
                        i = (((a * 7 + b) * 10 + c) * 6 + p) * 6 + q;
                        CHECK(sk_rayleigh_polarized_sample_f64(&r, k, &s, us[p], us[q], &o) == SK_OK);
                        CHECK(unit(o.dir) && isfinite(o.pdf) && o.pdf >= 0.0 && physical(&o.stokes));
                        CHECK(fabs(len3(o.stokes.reference) - 1.0) < 1e-9 && fabs(dot(o.stokes.reference, o.dir)) < 1e-9);
                        {
                            /* The density of the sampled direction, as eval and pdf give it. */
                            sk_stokes_f64 e;
                            double pdf = sk_rayleigh_polarized_pdf_f64(&r, k, &s, o.dir);
                            CHECK(sk_rayleigh_polarized_eval_f64(&r, k, &s, o.dir, sk_meridian_reference_f64(o.dir, 0.1), &e) ==
                                  SK_OK);
                            CHECK(physical(&e) && fabs(pdf - o.pdf) <= 1e-9 * o.pdf);
                        }
                        CHECK(sk_rayleigh_polarized_sample_scalar_f64(&r, k, &s, us[p], us[q], &o2) == SK_OK);
                        CHECK(unit(o2.dir) && isfinite(o2.pdf) && o2.pdf >= 0.0 && physical(&o2.stokes));
                    }
    }
    i = 0;
}

/* The float twin, where the fault is likeliest: a float generator gives
   u1 = 1/2 once in 2^24 draws. */
static int physical32(const sk_stokes *s) {
    double q, u, v;
    if (!(s->i >= 0.0f) || !isfinite(s->i)) return 0;
    if (s->i == 0.0f) return s->q == 0.0f && s->u == 0.0f && s->v == 0.0f;
    q = (double)s->q / s->i, u = (double)s->u / s->i, v = (double)s->v / s->i;
    return q * q + u * u + v * v <= 1.0 + 1e-5;
}

static double len32(sk_vec3 a) { return sqrt((double)a.x * a.x + (double)a.y * a.y + (double)a.z * a.z); }

static void polarization_f32(void) {
    const float rhos[4] = {0, 0.03f, 0.5f, 0.9999f}, r2 = 0.70710678f;
    const sk_vec3 ks[5] = {{0, 0, 1}, {1, 0, 0}, {r2, r2, 0}, {0.6f, 0, 0.8f}, {0, 1e-30f, -1}};
    const float st[6][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, -1, 0, 0}, {1, 0, 1, 0}, {1e30f, 0, 1e30f, 0}, {1, 0.3f, 0, 0.4f}};
    const float us[9] = {0, 1e-30f, 0.125f, 0.25f, 0.375f, 0.5f, 0.75f, 1 - 6e-8f, 1};
    int a, b, c, p, q;
    for (a = 0; a < 4; a++) {
        sk_rayleigh_polarized r;
        CHECK(sk_rayleigh_polarized_new(rhos[a], &r) == SK_OK);
        for (b = 0; b < 5; b++)
            for (c = 0; c < 6; c++)
                for (p = 0; p < 9; p++)
                    for (q = 0; q < 9; q++) {
                        sk_vec3 k = ks[b];
                        const float l = (float)len32(k);
                        sk_stokes s, e;
                        sk_stokes_sample o;
                        float pdf;
                        k.x /= l, k.y /= l, k.z /= l;
                        s.i = st[c][0], s.q = st[c][1], s.u = st[c][2], s.v = st[c][3];
                        s.reference = sk_meridian_reference(k, 0.3f);
                        i = 2000000 + (((a * 5 + b) * 6 + c) * 9 + p) * 9 + q;
                        CHECK(sk_rayleigh_polarized_sample(&r, k, &s, us[p], us[q], &o) == SK_OK);
                        CHECK(fabs(len32(o.dir) - 1.0) < 1e-5 && isfinite(o.pdf) && o.pdf >= 0.0f && physical32(&o.stokes));
                        pdf = sk_rayleigh_polarized_pdf(&r, k, &s, o.dir);
                        CHECK(sk_rayleigh_polarized_eval(&r, k, &s, o.dir, sk_meridian_reference(o.dir, 0.1f), &e) == SK_OK);
                        CHECK(physical32(&e) && pdf >= 0.0f && fabs(pdf - o.pdf) <= 1e-4 * o.pdf + 1e-6);
                    }
    }
    i = 0;
}

/* ---- the portable tier's majorant walk ---------------------------------- */

/* A box of n cells over [lo, hi], the walk's grid. */
typedef struct {
    float lo[3], hi[3];
    unsigned n[3];
} walk_box;

static float walk_maj[1000];

/* The largest of the box's extent and the ray's origin and direction in
   cell units over the axes, in double: the walk's -1 for a finite ray and
   box above FLT_MAX, and no rounding can take it there below FLT_MAX / 2. */
static double cell_extent(const walk_box *b, const float o[3], const float d[3]) {
    int a;
    double most = 0.0;
    for (a = 0; a < 3; a++) {
        double span = (double)b->hi[a] - b->lo[a], scale = b->n[a] / span;
        double o_cells = fabs(((double)o[a] - b->lo[a]) * scale), d_cells = fabs((double)d[a] * scale);
        most = fmax(most, fmax(span, fmax(o_cells, d_cells)));
    }
    return most;
}

/* Each collision of a walk lies in its cell (within the rounding of the
   ray's position in float), with that cell's majorant, in order along the
   segment; the walk ends at t_end with majorant 0. */
static void walk_steps(const walk_box *b, const skp_walk *start, const float o[3], const float d[3]) {
    static const float us[6] = {0.1f, 0.5f, 0.9f, 0.999f, 0.99999994f, 1.0f};
    int k, a, steps, r = 1;
    for (k = 0; k < 6; k++) {
        skp_walk w = *start;
        float prev = w.t, t = 0.0f, maj = 0.0f;
        for (steps = 0; steps < 40 && (r = skp_walk_step(&w, walk_maj, us[k], &t, &maj)) == 1; steps++) {
            unsigned c = skp_walk_cell(&w), in = 1;
            CHECK(c < b->n[0] * b->n[1] * b->n[2] && maj == walk_maj[c]);
            CHECK(t >= prev && t <= start->t_end);
            for (a = 0; a < 3; a++) {
                unsigned ca = a == 0 ? c % b->n[0] : (a == 1 ? c / b->n[0] % b->n[1] : c / (b->n[0] * b->n[1]));
                double h = ((double)b->hi[a] - b->lo[a]) / b->n[a], lo = b->lo[a] + ca * h;
                double p = (double)o[a] + (double)t * d[a];
                double tol = 1e-4 * h + 1e-6 * (fabs(p) + fabs((double)b->lo[a]) + fabs((double)b->hi[a]));
                in &= p >= lo - tol && p <= lo + h + tol;
            }
            CHECK(in);
            prev = t;
        }
        if (r == 1) continue; /* 40 collisions on a long ray, each checked */
        CHECK(r == 0 && t == start->t_end && maj == 0.0f);
    }
}

/* One ray: the walk's status against the documented conditions, the
   segment it walks against the clip in double, then its collisions. */
static void walk_ray(const walk_box *b, const float o[3], const float d[3], float t_min, float t_max) {
    skp_vec3 org, dir, lo, hi;
    skp_walk w;
    double t0 = t_min, t1 = t_max;
    int a, r, miss = 0;
    int bad = !(t_min >= 0.0f && t_min <= FLT_MAX && t_max >= t_min) || (d[0] == 0.0f && d[1] == 0.0f && d[2] == 0.0f);
    org.x = o[0], org.y = o[1], org.z = o[2];
    dir.x = d[0], dir.y = d[1], dir.z = d[2];
    lo.x = b->lo[0], lo.y = b->lo[1], lo.z = b->lo[2];
    hi.x = b->hi[0], hi.y = b->hi[1], hi.z = b->hi[2];
    r = skp_walk_begin(&w, org, dir, lo, hi, b->n[0], b->n[1], b->n[2], t_min, t_max);
    if (bad || cell_extent(b, o, d) > FLT_MAX) {
        CHECK(r == -1);
        return;
    }
    CHECK(r == 0 || r == 1 || (r == -1 && cell_extent(b, o, d) >= FLT_MAX / 2));
    for (a = 0; a < 3; a++) {
        double ta, tb;
        if (d[a] == 0.0f) {
            miss |= o[a] < b->lo[a] || o[a] > b->hi[a];
            continue;
        }
        ta = ((double)b->lo[a] - o[a]) / d[a], tb = ((double)b->hi[a] - o[a]) / d[a];
        if (ta > tb) {
            double x = ta;
            ta = tb, tb = x;
        }
        t0 = ta > t0 ? ta : t0, t1 = tb < t1 ? tb : t1;
    }
    miss |= !(t0 < t1);
    if (r == 0) {
        /* a miss, or a segment the float clip rounds to a point */
        CHECK(miss || t1 - t0 <= 1e-5 * (fabs(t0) + fabs(t1)));
    } else if (r == 1) {
        CHECK(w.t >= t_min && w.t_end <= t_max && w.t < w.t_end && w.t < FLT_MAX);
        walk_steps(b, &w, o, d);
    }
}

static void portable_walk(void) {
    static const walk_box boxes[7] = {
        {{0, 0, 0}, {1, 1, 1}, {1, 1, 1}},
        {{-1, -0.5f, 0}, {1.5f, 0.5f, 2}, {5, 3, 4}},
        {{0, 0, 0}, {1, 1, 1}, {1, 1, 64}},
        {{-1e30f, -1e30f, -1e30f}, {1e30f, 1e30f, 1e30f}, {4, 4, 4}},
        {{1e6f, 1e6f, 1e6f}, {1e6f + 1, 1e6f + 1, 1e6f + 1}, {3, 3, 3}},
        {{0, 0, 0}, {1e-30f, 1e-30f, 1e-30f}, {2, 2, 2}},
        {{-FLT_MAX, -1, -1}, {FLT_MAX, 1, 1}, {2, 1, 1}},
    };
    static const float vals[12] = {0, -0.0f, 1, -1, 0.5f, 1.4e-45f, FLT_MAX, -FLT_MAX, 1e30f, -1e30f, 1e6f, 1.5f};
    static const float dirs[11][3] = {{0, 0, 1},          {0, 0, -1},         {1, 0, 0},
                                      {0.6f, 0, -0.8f},   {0.57735f, 0.57735f, 0.57735f},
                                      {-0.6f, 0.8f, 0},   {1.4e-45f, 0, 1},   {1e-40f, -1e-40f, -1},
                                      {1e30f, 1e30f, 0},  {1e-30f, 0, 1e-30f}, {FLT_MAX, 0, 0}};
    static const float segs[8][2] = {{0, 0}, {0, 1}, {0.5f, 4}, {0, FLT_MAX}, {1.4e-45f, 1e-44f}, {3, 3}, {0, 1e-30f}, {-1, 1}};
    int bi, x, y, z, k, s;
    for (k = 0; k < 1000; k++) walk_maj[k] = (float)(k * 7 % 5) * 0.75f + 0.5f;
    for (bi = 0; bi < 7; bi++) {
        const walk_box *b = &boxes[bi];
        for (x = 0; x < 12 + 27; x++)
            for (y = 0; y < 12; y += 5)
                for (z = 0; z < 12; z += 3) {
                    float o[3];
                    i = ((bi * 39 + x) * 12 + y) * 12 + z;
                    if (x < 12) {
                        o[0] = vals[x], o[1] = vals[y], o[2] = vals[z];
                    } else { /* the box's faces, edges, corners and centre */
                        int f = x - 12;
                        o[0] = f % 3 == 0 ? b->lo[0] : (f % 3 == 1 ? b->hi[0] : 0.5f * b->lo[0] + 0.5f * b->hi[0]);
                        o[1] = f / 3 % 3 == 0 ? b->lo[1] : (f / 3 % 3 == 1 ? b->hi[1] : 0.5f * b->lo[1] + 0.5f * b->hi[1]);
                        o[2] = f / 9 == 0 ? b->lo[2] : (f / 9 == 1 ? b->hi[2] : 0.5f * b->lo[2] + 0.5f * b->hi[2]);
                        if (y > 0 || z > 0) continue;
                    }
                    for (k = 0; k < 11; k++)
                        for (s = 0; s < 8; s++) {
                            walk_ray(b, o, dirs[k], segs[s][0], segs[s][1]);
                            walk_ray(b, o, dirs[k], segs[s][0], segs[s][1] == 0 ? (float)INFINITY : segs[s][1] * 1e3f);
                        }
                }
    }
    i = 0;
}

/* ---- Mie --------------------------------------------------------------- */

static void mie(void) {
    const double xs[9] = {1e-20, 1e-12, 1e-3, 1, 7.99, 8, 300, 2e4, 1e5};
    const sk_complex_f64 ms[16] = {{1, 0},      {1 + 2.2e-16, 0}, {1.0001, 0}, {1.33, 0},   {1.33, 1e-9}, {1.5, 0.01},
                                   {2, 1},      {10, 10},         {0.5, 0},    {1e-3, 0},   {1000, 0},    {0.2, 3},
                                   {1000, 1000}, {1, 1000},       {1e-100, 0}, {1.2e-100, 1.6e-100}};
    const double mus[5] = {-1, -0.3, 0, 0.9, 1};
    int a, b, k;
    size_t cap = 0;
    sk_complex_f64 *buf = NULL;
    for (a = 0; a < 9; a++)
        for (b = 0; b < 16; b++) {
            size_t n = sk_mie_len_f64(xs[a], ms[b]);
            sk_mie_f64 s;
            sk_status q;
            i = a * 16 + b;
            if (n == 0) continue;
            if (n > cap) {
                free(buf);
                buf = (sk_complex_f64 *)malloc(n * sizeof *buf);
                cap = buf ? n : 0;
                if (!buf) {
                    CHECK(!"allocation");
                    return;
                }
            }
            q = sk_mie_new_f64(xs[a], ms[b], buf, n, &s);
            CHECK(q == SK_OK || q == SK_ERR_DOMAIN);
            if (q != SK_OK) continue;
            CHECK(isfinite(s.efficiencies.q_ext) && s.efficiencies.q_sca > 0.0 && isfinite(s.efficiencies.q_sca));
            CHECK(s.efficiencies.q_sca <= s.efficiencies.q_ext * (1.0 + 1e-9) && fabs(s.efficiencies.g) <= 1.0);
            for (k = 0; k < 5; k++) {
                double pdf = sk_mie_pdf_f64(&s, mus[k]);
                CHECK(isfinite(pdf) && pdf >= 0.0);
            }
        }
    free(buf);
    i = 0;
}

int main(void) {
    tracking_f64();
    tracking_f32();
    surfaces();
    equiangular();
    homogeneous();
    polarization();
    polarization_f32();
    mie();
    portable_walk();
    printf("edges: %d checks passed, %d failed\n", passed, failed);
    return failed != 0;
}
