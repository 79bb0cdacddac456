/* scatterkit_table.h: the table lookups of scatterkit, header-only.
 *
 * Written by hand (not generated), and the contract for kernels that sample
 * from a table built by the library (sk_table_new_inverse, sk_table_new_measured,
 * sk_table_new_rayleigh_cdf in scatterkit.h) without linking it: a GPU shader, a
 * CUDA or OpenCL kernel, firmware. Plain C99 that also compiles as C++,
 * CUDA and OpenCL C; no library call, no allocation. tests/c_abi/table_header.rs
 * checks every function here bit for bit against sk_table_sample_cos and
 * sk_table2d_sample_cos, over more than 10^7 lookups per table kind and
 * precision, compiled as C99 and as C++.
 *
 * Bit-identical results need IEEE arithmetic in the stated order without
 * fused multiply-add contraction (C99 mode of GCC and Clang does not
 * contract; for CUDA pass --fmad=false, for C++ with an FMA target
 * -ffp-contract=off). With contraction the results differ in the last bits
 * only.
 *
 * Memory layout (the `data` of an sk_table, `n` its resolution):
 *
 *   SK_TABLE_INVERSE and SK_TABLE_MEASURED: 2(n + 1) values, mu_i and d_i
 *   interleaved (data[2i] = mu_i, data[2i + 1] = d_i), i = 0..n. mu_i is
 *   the inverse CDF at u_i = i/n, d_i its slope per interval (dmu/du at u_i,
 *   divided by n), limited so the spline is monotone. Lookup: x = u n,
 *   i = min(floor(x), n - 1), t = x - i, and the cubic Hermite
 *     mu(t) = mu_i + t (d_i + t (c2 + t c3)),
 *     c2 = 3 (mu_{i+1} - mu_i) - 2 d_i - d_{i+1},
 *     c3 = d_i + d_{i+1} - 2 (mu_{i+1} - mu_i),
 *   held in [mu_i, mu_{i+1}] (its rounding can pass mu_{i+1} by an ulp),
 *   then clamped to [-1, 1]. Density per steradian: 1 / (2 pi n mu'(t)).
 *
 *   SK_TABLE_RAYLEIGH_CDF: n + 1 values F_i, the Rayleigh CDF at
 *   x_i = -1 + 2i/n. Lookup: the largest i < n with F_i <= u by bisection,
 *   t = (u - F_i) / (F_{i+1} - F_i), mu = (i + t)(2/n) - 1, clamped to
 *   [-1, 1]. Density per steradian: (F_{i+1} - F_i) / (2 pi (2/n)) on
 *   interval i.
 *
 *   2-D tables (sk_table2d in scatterkit.h): k slices one after the
 *   other, each 2(n + 1) values as SK_TABLE_INVERSE, at x_j = x0 + j dx.
 *   Lookup at (x, u): NaN x gives NaN; s = (x - x0) / dx clamped to
 *   [0, k - 1], j = floor(s), w = s - j; a = the Hermite lookup of slice
 *   j at u, and where w > 0, b = that of slice j + 1 and
 *   mu = a + w (b - a); else mu = a.
 *
 * u is clamped to [0, 1] first; NaN u gives NaN. n (and k) must be at
 * least 1 and data hold the values above (the library's constructors
 * guarantee both).
 */
#ifndef SCATTERKIT_TABLE_H
#define SCATTERKIT_TABLE_H

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#define SK_TABLE_OPENCL_ 1
#endif

#if !defined(SK_TABLE_OPENCL_)
#include <stddef.h>
#endif

#ifndef SK_TABLE_FN
#if defined(__CUDACC__)
#define SK_TABLE_FN static inline __host__ __device__
#elif defined(SK_TABLE_OPENCL_)
#define SK_TABLE_FN static inline
#else
#define SK_TABLE_FN static inline
#endif
#endif

/* The Hermite lookup, float (SK_TABLE_INVERSE, SK_TABLE_MEASURED). */
SK_TABLE_FN float sk_table_hermite_lookup(const float *data, size_t n, float u) {
    float x, t, y0, d0, y1, d1, dy, c2, c3, mu;
    size_t i;
    u = u > 1.0f ? 1.0f : u;
    u = u < 0.0f ? 0.0f : u;
    x = u * (float)n;
    /* floor for x >= 0; NaN and negatives give 0, as the library's
     * saturating conversion does. */
    i = x > 0.0f ? (size_t)x : (size_t)0;
    i = i > n - (size_t)1 ? n - (size_t)1 : i;
    t = x - (float)i;
    y0 = data[(size_t)2 * i];
    d0 = data[(size_t)2 * i + (size_t)1];
    y1 = data[(size_t)2 * i + (size_t)2];
    d1 = data[(size_t)2 * i + (size_t)3];
    dy = y1 - y0;
    c2 = 3.0f * dy - 2.0f * d0 - d1;
    c3 = d0 + d1 - 2.0f * dy;
    mu = y0 + t * (d0 + t * (c2 + t * c3));
    mu = mu > y1 ? y1 : mu;
    mu = mu < y0 ? y0 : mu;
    mu = mu > 1.0f ? 1.0f : mu;
    return mu < -1.0f ? -1.0f : mu;
}

/* Frisvad's Rayleigh CDF table lookup, float (SK_TABLE_RAYLEIGH_CDF). */
SK_TABLE_FN float sk_table_cdf_lookup(const float *data, size_t n, float u) {
    size_t lo = (size_t)0, hi = n, mid;
    float t, dx, mu;
    u = u > 1.0f ? 1.0f : u;
    u = u < 0.0f ? 0.0f : u;
    while (hi - lo > (size_t)1) {
        mid = (lo + hi) / (size_t)2;
        if (data[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    t = (u - data[lo]) / (data[hi] - data[lo]);
    dx = 2.0f / (float)n;
    mu = ((float)lo + t) * dx - 1.0f;
    mu = mu > 1.0f ? 1.0f : mu;
    return mu < -1.0f ? -1.0f : mu;
}

/* The 2-D lookup, float (sk_table2d). */
SK_TABLE_FN float sk_table2d_lookup(const float *data, size_t n, size_t k, float x0, float dx, float x, float u) {
    float s, w, top, a, b;
    size_t j, per;
    if (x != x)
        return x;
    top = (float)(k - (size_t)1);
    s = (x - x0) / dx;
    s = s > top ? top : s;
    s = s < 0.0f ? 0.0f : s;
    j = (size_t)s;
    w = s - (float)j;
    per = (size_t)2 * (n + (size_t)1);
    a = sk_table_hermite_lookup(data + j * per, n, u);
    if (w > 0.0f) {
        b = sk_table_hermite_lookup(data + (j + (size_t)1) * per, n, u);
        return a + w * (b - a);
    }
    return a;
}

#if !defined(SK_TABLE_OPENCL_) || defined(cl_khr_fp64)
/* The Hermite lookup, double. */
SK_TABLE_FN double sk_table_hermite_lookup_f64(const double *data, size_t n, double u) {
    double x, t, y0, d0, y1, d1, dy, c2, c3, mu;
    size_t i;
    u = u > 1.0 ? 1.0 : u;
    u = u < 0.0 ? 0.0 : u;
    x = u * (double)n;
    i = x > 0.0 ? (size_t)x : (size_t)0;
    i = i > n - (size_t)1 ? n - (size_t)1 : i;
    t = x - (double)i;
    y0 = data[(size_t)2 * i];
    d0 = data[(size_t)2 * i + (size_t)1];
    y1 = data[(size_t)2 * i + (size_t)2];
    d1 = data[(size_t)2 * i + (size_t)3];
    dy = y1 - y0;
    c2 = 3.0 * dy - 2.0 * d0 - d1;
    c3 = d0 + d1 - 2.0 * dy;
    mu = y0 + t * (d0 + t * (c2 + t * c3));
    mu = mu > y1 ? y1 : mu;
    mu = mu < y0 ? y0 : mu;
    mu = mu > 1.0 ? 1.0 : mu;
    return mu < -1.0 ? -1.0 : mu;
}

/* Frisvad's Rayleigh CDF table lookup, double. */
SK_TABLE_FN double sk_table_cdf_lookup_f64(const double *data, size_t n, double u) {
    size_t lo = (size_t)0, hi = n, mid;
    double t, dx, mu;
    u = u > 1.0 ? 1.0 : u;
    u = u < 0.0 ? 0.0 : u;
    while (hi - lo > (size_t)1) {
        mid = (lo + hi) / (size_t)2;
        if (data[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    t = (u - data[lo]) / (data[hi] - data[lo]);
    dx = 2.0 / (double)n;
    mu = ((double)lo + t) * dx - 1.0;
    mu = mu > 1.0 ? 1.0 : mu;
    return mu < -1.0 ? -1.0 : mu;
}

/* The 2-D lookup, double (sk_table2d_f64). */
SK_TABLE_FN double sk_table2d_lookup_f64(const double *data, size_t n, size_t k, double x0, double dx, double x, double u) {
    double s, w, top, a, b;
    size_t j, per;
    if (x != x)
        return x;
    top = (double)(k - (size_t)1);
    s = (x - x0) / dx;
    s = s > top ? top : s;
    s = s < 0.0 ? 0.0 : s;
    j = (size_t)s;
    w = s - (double)j;
    per = (size_t)2 * (n + (size_t)1);
    a = sk_table_hermite_lookup_f64(data + j * per, n, u);
    if (w > 0.0) {
        b = sk_table_hermite_lookup_f64(data + (j + (size_t)1) * per, n, u);
        return a + w * (b - a);
    }
    return a;
}
#endif

#endif /* SCATTERKIT_TABLE_H */
