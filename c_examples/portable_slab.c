/* A photon random walk through a conservative slab with nothing but
 * include/scatterkit_portable.h: the header-only f32 tier a GPU kernel or a
 * renderer compiles inline (no library to link, no <math.h> needed). The
 * same loop body compiles as CUDA, HIP or OpenCL C.
 *
 * Photons enter a slab of optical thickness 2 at normal incidence; free
 * paths from skp_free_path, directions from skp_hg_sample_dir (g = 0.7).
 * With no absorption every photon leaves through one face, so R + T = 1
 * exactly; the mean cosine of the sampled scattering angles must be g
 * within 4 standard errors. Exits 0 when both hold.
 *
 *   cc -std=c99 -I include c_examples/portable_slab.c -lm
 * (-lm only for the square root's errno path; -fno-math-errno removes it.)
 */
#include <stdio.h>

#include "scatterkit_portable.h"

/* xorshift32: a float in [0, 1) from the top 24 bits. */
static float next(skp_u32 *s) {
    *s ^= *s << 13;
    *s ^= *s >> 17;
    *s ^= *s << 5;
    return (float)(*s >> 8) * 5.9604645e-08f;
}

int main(void) {
    enum { PHOTONS = 200000 };
    const float g = 0.7f, tau = 2.0f;
    skp_hg hg;
    skp_u32 rng = 2463534242u;
    long reflected = 0, transmitted = 0, events = 0;
    double sum_cos = 0.0, sum_cos2 = 0.0, mean, se;
    int i;

    if (!skp_hg_new(g, &hg)) return 1;
    for (i = 0; i < PHOTONS; i++) {
        skp_vec3 dir = {0.0f, 0.0f, 1.0f};
        float z = 0.0f; /* optical depth into the slab */
        for (;;) {
            skp_dir_sample out;
            z += dir.z * skp_free_path(1.0f, next(&rng));
            if (z < 0.0f) { reflected++; break; }
            if (z > tau) { transmitted++; break; }
            out = skp_hg_sample_dir(hg, dir, next(&rng), next(&rng));
            /* The scattering angle's cosine comes with the direction. */
            sum_cos += out.cos_theta;
            sum_cos2 += (double)out.cos_theta * out.cos_theta;
            events++;
            dir = out.dir;
        }
    }
    mean = sum_cos / events;
    /* The standard error, with the header's square root (no <math.h>). */
    se = skp_sqrt((float)((sum_cos2 / events - mean * mean) / events));
    printf("slab tau = %.1f, HG g = %.1f, %d photons: R = %.4f, T = %.4f, R + T = %.4f\n",
           tau, g, PHOTONS, (double)reflected / PHOTONS, (double)transmitted / PHOTONS,
           (double)(reflected + transmitted) / PHOTONS);
    printf("mean cosine of %ld scatterings: %.5f (g = %.1f, standard error %.5f)\n", events, mean,
           g, se);
    return reflected + transmitted == PHOTONS && (mean - g) < 4 * se && (g - mean) < 4 * se ? 0 : 1;
}
