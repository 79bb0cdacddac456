/* sk_phase_sample_cos_n_portable and sk_phase_sample_dir_n_portable (the
 * library's batches, chosen at load time) against
 * include/scatterkit_portable.h inline, bit for bit: every u = k 2^-24,
 * k = 0 .. 2^24, for HG at several g, Rayleigh and isotropic; directions at
 * those u1 with scrambled u2 and eight incoming directions. Prints "N
 * compared, M mismatched". */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scatterkit.h"
#include "scatterkit_portable.h"

#define CHUNK 4096u

int main(void) {
    static const float gs[6] = {0.7f, -0.3f, 0.0f, 0.999f, -0.999999f, 0.2f};
    static float u[CHUNK], out[CHUNK], u2[CHUNK], wx[CHUNK], wy[CHUNK], wz[CHUNK];
    static float ox[CHUNK], oy[CHUNK], oz[CHUNK], pdf[CHUNK];
    static const float DIRS[8][3] = {{0.0f, 0.0f, 1.0f},   {0.0f, 0.0f, -1.0f}, {1.0f, 0.0f, 0.0f},
                                     {0.0f, -1.0f, 0.0f},  {0.6f, 0.0f, 0.8f},  {0.0f, 0.8f, -0.6f},
                                     {0.48f, 0.6f, 0.64f}, {-0.36f, 0.48f, -0.8f}};
    unsigned long compared = 0, bad = 0;
    int m;
    for (m = 0; m < 8; m++) {
        sk_phase ph;
        skp_hg h;
        unsigned k0, i;
        if (m < 6) {
            if (sk_phase_new_hg(gs[m], &ph) != SK_OK || !skp_hg_new(gs[m], &h)) return 1;
        } else if (m == 6) {
            if (sk_phase_new_rayleigh(&ph) != SK_OK) return 1;
        } else if (sk_phase_new_isotropic(&ph) != SK_OK) {
            return 1;
        }
        for (k0 = 0; k0 <= (1u << 24); k0 += CHUNK) {
            unsigned n = k0 == (1u << 24) ? 1u : CHUNK;
            for (i = 0; i < n; i++) u[i] = (float)(k0 + i) * 5.9604645e-08f;
            if (sk_phase_sample_cos_n_portable(&ph, u, out, n) != SK_OK) return 2;
            for (i = 0; i < n; i++) {
                skp_u32 h = (k0 + i) * 2654435761u;
                u2[i] = (float)(h >> 8) * 5.9604645e-08f;
                wx[i] = DIRS[(k0 + i) & 7u][0];
                wy[i] = DIRS[(k0 + i) & 7u][1];
                wz[i] = DIRS[(k0 + i) & 7u][2];
            }
            if (sk_phase_sample_dir_n_portable(&ph, wx, wy, wz, u, u2, ox, oy, oz, pdf, n) != SK_OK) return 2;
            for (i = 0; i < n; i++) {
                skp_vec3 w, d;
                skp_dir_sample r;
                float q, s, mu;
                w.x = wx[i];
                w.y = wy[i];
                w.z = wz[i];
                if (m < 6) {
                    r = skp_hg_sample_dir(h, w, u[i], u2[i]);
                    d = r.dir;
                    q = r.pdf;
                } else if (m == 6) {
                    r = skp_rayleigh_sample_dir(w, u[i], u2[i]);
                    d = r.dir;
                    q = r.pdf;
                } else {
                    mu = skp_isotropic_sample_cos_sin(u[i], &s);
                    d = skp_direction_about(w, mu, s, u2[i]);
                    q = SKP_INV_4PI;
                }
                compared++;
                if (memcmp(&d.x, &ox[i], 4) || memcmp(&d.y, &oy[i], 4) || memcmp(&d.z, &oz[i], 4) ||
                    memcmp(&q, &pdf[i], 4)) {
                    if (bad < 5) printf("direction, model %d, u %.9g: %.9g vs %.9g\n", m, u[i], d.x, ox[i]);
                    bad++;
                }
            }
            for (i = 0; i < n; i++) {
                float s, want = m < 6 ? skp_hg_sample_cos(h, u[i])
                                      : (m == 6 ? skp_rayleigh_sample_cos(u[i])
                                                : skp_isotropic_sample_cos_sin(u[i], &s));
                compared++;
                if (memcmp(&want, &out[i], sizeof want) != 0) {
                    if (bad < 5) printf("model %d, u %.9g: %.9g vs %.9g\n", m, u[i], want, out[i]);
                    bad++;
                }
            }
        }
    }
    printf("%lu compared, %lu mismatched\n", compared, bad);
    return bad != 0;
}
