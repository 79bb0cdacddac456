/* scatterkit_inline.h: cos theta of a phase function without a call into the
 * library, for the one sample a C path tracer draws per scattering event.
 *
 * Hand-written (scatterkit.h is generated). Fill an sk_phase_cos_inline once
 * with sk_phase_cos_inline_new, then call sk_phase_cos_inline_sample as often
 * as you like:
 *
 *     sk_phase hg;
 *     sk_phase_cos_inline hgi;
 *     sk_phase_new_hg(0.7f, &hg);
 *     sk_phase_cos_inline_new(&hg, &hgi);
 *     cos_theta = sk_phase_cos_inline_sample(&hgi, u);
 *
 * The result is sk_phase_sample_cos(&hg, u), bit for bit, for every u
 * (tests/c/inline.c checks every float in [0, 1], the values outside and
 * NaN). For Henyey-Greenstein on x86, x86-64 and AArch64 the function
 * evaluates the library's own double-precision formula inline; for every
 * other phase, and wherever the compiler would not evaluate that formula
 * exactly as written (double arithmetic in extended precision,
 * FLT_EVAL_METHOD != 0, or -ffast-math), it calls sk_phase_sample_cos.
 * C89 and later, and C++. */
#ifndef SCATTERKIT_INLINE_H
#define SCATTERKIT_INLINE_H

#include <float.h>

#include "scatterkit.h"

#if defined(__cplusplus) || (defined(__STDC_VERSION__) && __STDC_VERSION__ >= 199901L)
#define SK_INLINE_FN static inline
#elif defined(__GNUC__)
#define SK_INLINE_FN static __inline__ __attribute__((unused))
#else
#define SK_INLINE_FN static
#endif

/* FLT_EVAL_METHOD is C99's; before C99, GCC and Clang say the same with
   __FLT_EVAL_METHOD__. */
#if defined(__FAST_MATH__)
#define SK_INLINE_EXACT 0
#elif defined(FLT_EVAL_METHOD)
#define SK_INLINE_EXACT (FLT_EVAL_METHOD == 0)
#elif defined(__FLT_EVAL_METHOD__)
#define SK_INLINE_EXACT (__FLT_EVAL_METHOD__ == 0)
#else
#define SK_INLINE_EXACT 0
#endif

/* cos theta = F^-1(u) of the phase *c was filled from; u is clamped to [0, 1]
 * as the library clamps it, and NaN gives NaN. */
SK_INLINE_FN float sk_phase_cos_inline_sample(const sk_phase_cos_inline *c, float u) {
#if SK_INLINE_EXACT
    if (c->kab[2] != 0.0) {
        double v, t;
        float w = u > 1.0f ? 1.0f : u;
        w = w < 0.0f ? 0.0f : w;
        /* The library's operations, in its order: u' = u or 1 - u, exact in
           double; t = u' + k; cos theta = A - B / t^2, rounded once. */
        v = c->mirror ? 1.0 - (double)w : (double)w;
        t = v + c->kab[0];
        return (float)(c->kab[1] - c->kab[2] / (t * t));
    }
#endif
    return sk_phase_sample_cos(&c->phase, u);
}

#endif /* SCATTERKIT_INLINE_H */
