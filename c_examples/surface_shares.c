/* A glass/silicon-like interface, the way a solar-cell ray tracer uses it.
 *
 * Rays in a medium of index 1.5 meet a material of index 3.9 at 0 and 60
 * degrees incidence. The surface scatters by Phong (alpha = 1000) with the
 * scalar-scattering share for 50 nm RMS roughness at 600 nm. For 10^6 rays
 * each, prints the reflected, transmitted and scattered shares beside the
 * closed forms (Fresnel; 1 - exp(-x^2)) and the mean angle between scattered
 * rays and the specular direction beside its small-angle limit: with
 * P(cos dtheta <= c) = c^(alpha+1), dtheta is Rayleigh-distributed with
 * variance 1/(alpha+1), so its mean is sqrt(pi / (2 (alpha + 1))). Exits 0
 * when every share is within 4 standard deviations of its closed form and the
 * mean deviation within 1% of its limit.
 *
 *   cc -std=c99 -I include c_examples/surface_shares.c \
 *      -lm target/release/libscatterkit.a -lpthread -ldl -lm
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "scatterkit.h"

static uint64_t xorshift64(void *state) {
    uint64_t *s = (uint64_t *)state;
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

static int within(double share, double p, long n) {
    return fabs(share - p) <= 4.0 * sqrt(p * (1.0 - p) / (double)n) + 1e-12;
}

int main(void) {
    enum { N = 1000000 };
    const double pi = 3.14159265358979323846;
    const float n_i = 1.5f, n_t = 3.9f, lambda = 600e-9f, sigma = 50e-9f;
    const float angles[2] = {0.0f, 60.0f};
    const sk_vec3 normal = {0.0f, 0.0f, 1.0f};
    uint64_t seed = 0x2545f4914f6cdd1dULL;
    sk_rng rng = {&seed, xorshift64};
    sk_surface s;
    int k, ok = 1;

    if (sk_surface_new(SK_SURFACE_PHONG, 1000.0f, SK_FRACTION_SCALAR, 0.0f, sigma, SK_CROSSING_FOLD, &s) != SK_OK)
        return 1;
    printf("n_i = %.1f -> n_t = %.1f, Phong alpha = 1000, sigma_rms = 50 nm, lambda = 600 nm\n", n_i, n_t);
    for (k = 0; k < 2; k++) {
        float th = angles[k] * (float)pi / 180.0f;
        sk_vec3 d = {sinf(th), 0.0f, -cosf(th)}, spec_r = sk_reflect(d, normal), spec_t;
        float ci = cosf(th), st = n_i / n_t * sinf(th), ct = sqrtf(1.0f - st * st);
        double R = sk_fresnel_dielectric(ci, n_i, n_t);
        double Lr = sk_scatter_fraction_reflect(lambda, sigma, n_i, ci);
        double Lt = sk_scatter_fraction_transmit(lambda, sigma, n_i, ci, n_t, ct);
        long refl = 0, refl_scat = 0, trans_scat = 0;
        double dev_sum = 0.0;
        int i;
        if (sk_refract(d, normal, n_i, n_t, &spec_t) != SK_OK) return 1;
        for (i = 0; i < N; i++) {
            sk_vec3 out;
            uint32_t ev;
            const sk_vec3 *spec;
            if (sk_surface_interact(&s, d, normal, n_i, n_t, lambda, &rng, &out, &ev) != SK_OK) return 1;
            spec = (ev & SK_EVENT_TRANSMITTED) ? &spec_t : &spec_r;
            if (!(ev & SK_EVENT_TRANSMITTED)) refl++;
            if (ev & SK_EVENT_SCATTERED) {
                double c = out.x * spec->x + out.y * spec->y + out.z * spec->z;
                dev_sum += acos(c > 1.0 ? 1.0 : c);
                if (ev & SK_EVENT_TRANSMITTED) trans_scat++; else refl_scat++;
            }
        }
        printf("\nincidence %4.1f deg:\n", angles[k]);
        printf("  reflected    %.5f   (Fresnel %.5f)\n", (double)refl / N, R);
        printf("  transmitted  %.5f   (1 - R   %.5f)\n", 1.0 - (double)refl / N, 1.0 - R);
        printf("  scattered on reflection   %.5f   (Lambda_r %.5f)\n", (double)refl_scat / refl, Lr);
        printf("  scattered on transmission %.5f   (Lambda_t %.5f)\n", (double)trans_scat / (N - refl), Lt);
        {
            double mean_dev = dev_sum / (double)(refl_scat + trans_scat) * 180.0 / pi;
            double limit = sqrt(pi / (2.0 * 1001.0)) * 180.0 / pi;
            printf("  mean deviation of scattered rays from specular: %.3f deg (limit %.3f)\n", mean_dev, limit);
            ok &= fabs(mean_dev / limit - 1.0) < 0.01;
        }
        ok &= within((double)refl / N, R, N);
        ok &= within((double)refl_scat / refl, Lr, refl);
        ok &= within((double)trans_scat / (N - refl), Lt, N - refl);
    }
    printf("\nshares within 4 sigma of the closed forms, deviation within 1%%: %s\n", ok ? "yes" : "no");
    return ok ? 0 : 2;
}
