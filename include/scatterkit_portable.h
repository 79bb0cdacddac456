/* scatterkit_portable.h: the portable f32 tier of scatterkit, header-only,
 * for C, C++, CUDA, HIP and OpenCL C kernels alike.
 *
 * Written by hand (not generated), operation for operation the same as the
 * Rust module scatterkit::portable: every function returns that module's bits
 * wherever each operation below rounds correctly (IEEE-754 single precision,
 * round to nearest). tests/c_abi/portable.rs checks it over 2^24 inputs per
 * function, compiled as C89, C99, C11, C++11, C++17, C++20 and at
 * -O3 -march=native -ffp-contract=fast, and as OpenCL C under pocl; CUDA
 * (NVPTX) and HIP (amdgcn) device compiles are checked by clang.
 * docs/guides/portable.md is the guide.
 *
 * What it needs: float arithmetic, a 32-bit unsigned integer and the bits of
 * a float. No <math.h>, no double precision, no library call: sine, cosine
 * and logarithm are the library's own polynomials; the square root is the
 * compiler's correctly rounded one (__builtin_sqrtf, sqrt in OpenCL,
 * __fsqrt_rn under nvcc).
 *
 * Contraction. A compiler that fuses a*b + c into one fused multiply-add
 * rounds once where this tier rounds twice, and the bits differ. Here
 * nothing is left to fuse: every product that feeds a sum goes through
 * SKP_MUL: on CUDA and AMD GCN devices the multiply instruction in inline
 * assembly (mul.rn.f32, v_mul_f32), and on a CPU with FMA enabled a product
 * the optimiser cannot see through (an empty asm statement holding it in a
 * register), because GCC ignores the FP_CONTRACT pragma and Clang's
 * -ffp-contract=fast ignores its own. On the CPU it costs no instruction,
 * but a loop around these functions is not vectorised by the compiler
 * there. OpenCL C honours the pragma that opens each function body.
 *
 * OpenCL: build with -cl-fp32-correctly-rounded-divide-sqrt (OpenCL allows
 * 2.5 ulp division and 3 ulp square roots without it) and without
 * -cl-mad-enable or -cl-fast-relaxed-math. CUDA: the defaults (-prec-div=true,
 * -prec-sqrt=true, no --use_fast_math).
 *
 * Memory spaces. Every sampler takes its model's constants by value
 * (skp_hg, skp_two_lobe, skp_fog, skp_draine, skp_schlick) and returns a
 * direction as a value (skp_dir_sample: the direction, its cos theta and
 * its density), so a kernel passes a table entry from wherever it lives,
 * as it stands: skp_hg_sample_dir(media[m].hg, w, u1, u2) with media in
 * OpenCL __constant, __global or private memory (OpenCL C 1.2, 2.0 and
 * 3.0), in CUDA or HIP __constant__ or device memory, or on the host. A
 * pointer parameter would name one address space: OpenCL 1.2 has no
 * generic one, and no version converts __constant to it. Inlined, as
 * these functions are, the copy is only the loads of the fields the
 * sampler reads. The constructors (skp_*_new) write through a pointer to
 * the caller's own (private or host) variable, and the scalar outputs of
 * skp_*_sample_cos_sin go to the caller's private variables.
 *
 * Several units. The header defines nothing with external linkage in any
 * language: functions are static inline and the Rayleigh table static, so
 * translation units (C, C++) and OpenCL programs linked with
 * clLinkProgram may each include it.
 *
 * Conventions: u in [0, 1] is clamped, NaN gives NaN; cos theta = +1 is
 * forward; densities are per steradian; directions are unit vectors.
 */
#ifndef SCATTERKIT_PORTABLE_H
#define SCATTERKIT_PORTABLE_H

/* ---- qualifiers --------------------------------------------------------- */
/* OpenCL C: the runtimes define __OPENCL_VERSION__, Clang itself only
   __OPENCL_C_VERSION__. */
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#define SKP_OPENCL_ 1
#endif
#if defined(__CUDACC__) || defined(__CUDA__) || defined(__HIP__) || defined(__HIPCC__)
#if defined(__clang__)
#define SKP_QUAL __attribute__((host)) __attribute__((device))
#else
#define SKP_QUAL __host__ __device__
#endif
#define SKP_FN static inline SKP_QUAL
#elif defined(SKP_OPENCL_)
#define SKP_FN static inline
#elif defined(__cplusplus) || (defined(__STDC_VERSION__) && __STDC_VERSION__ >= 199901L)
#define SKP_FN static inline
#elif defined(__GNUC__)
#define SKP_FN static __inline__ __attribute__((unused))
#else
#define SKP_FN static
#endif

/* ---- no contraction ----------------------------------------------------- */
#if defined(__clang__)
#define SKP_BEGIN _Pragma("clang fp contract(off)")
#elif defined(SKP_OPENCL_)
#define SKP_BEGIN _Pragma("OPENCL FP_CONTRACT OFF")
#else
#define SKP_BEGIN
#endif

#if defined(__CUDA_ARCH__)
/* PTX's own rounded multiply: opaque to the optimiser, so never fused. */
SKP_FN float skp_mul_(float a, float b) {
    float p;
    asm("mul.rn.f32 %0, %1, %2;" : "=f"(p) : "f"(a), "f"(b));
    return p;
}
#define SKP_MUL(a, b) skp_mul_((a), (b))
#elif defined(__HIP_DEVICE_COMPILE__) && defined(__AMDGCN__)
/* AMD GCN's IEEE multiply, opaque to the optimiser. */
SKP_FN float skp_mul_(float a, float b) {
    float p;
    __asm__("v_mul_f32 %0, %1, %2" : "=v"(p) : "v"(a), "v"(b));
    return p;
}
#define SKP_MUL(a, b) skp_mul_((a), (b))
#elif defined(SKP_OPENCL_)
#define SKP_MUL(a, b) ((a) * (b))
#elif (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__)) && \
    (defined(__FMA__) || defined(__FMA4__) || defined(__FP_FAST_FMAF))
SKP_FN float skp_mul_(float a, float b) {
    float p = a * b;
    __asm__("" : "+x"(p));
    return p;
}
#define SKP_MUL(a, b) skp_mul_((a), (b))
#elif (defined(__GNUC__) || defined(__clang__)) && defined(__aarch64__)
SKP_FN float skp_mul_(float a, float b) {
    float p = a * b;
    __asm__("" : "+w"(p));
    return p;
}
#define SKP_MUL(a, b) skp_mul_((a), (b))
#elif defined(__GNUC__) && defined(__FP_FAST_FMAF)
SKP_FN float skp_mul_(float a, float b) {
    volatile float p = a * b;
    return p;
}
#define SKP_MUL(a, b) skp_mul_((a), (b))
#else
#define SKP_MUL(a, b) ((a) * (b))
#endif

/* ---- bits and the square root ------------------------------------------- */
#if defined(SKP_OPENCL_)
typedef uint skp_u32;
#else
typedef unsigned int skp_u32;
/* skp_u32 must hold exactly 32 bits. */
typedef char skp_u32_is_32_bits[(sizeof(skp_u32) == 4) ? 1 : -1];
#endif

SKP_FN skp_u32 skp_bits(float x) {
#if defined(SKP_OPENCL_)
    return as_uint(x);
#elif defined(__CUDACC__) && !defined(__clang__)
    return __float_as_uint(x);
#else
    union {
        float f;
        skp_u32 u;
    } v;
    v.f = x;
    return v.u;
#endif
}

SKP_FN float skp_from_bits(skp_u32 b) {
#if defined(SKP_OPENCL_)
    return as_float(b);
#elif defined(__CUDACC__) && !defined(__clang__)
    return __uint_as_float(b);
#else
    union {
        skp_u32 u;
        float f;
    } v;
    v.u = b;
    return v.f;
#endif
}

/* The correctly rounded square root; NaN for x < 0. */
SKP_FN float skp_sqrt(float x) {
#if defined(SKP_OPENCL_)
    return sqrt(x);
#elif defined(__CUDACC__) && !defined(__clang__)
    return __fsqrt_rn(x);
#elif defined(__GNUC__) || defined(__clang__)
    return __builtin_sqrtf(x);
#else
#error "scatterkit_portable.h: define skp_sqrt for this compiler"
#endif
}

/* u clamped to [0, 1], NaN kept. */
SKP_FN float skp_clamp01(float u) {
    float w = u > 1.0f ? 1.0f : u;
    return w < 0.0f ? 0.0f : w;
}

/* ---- the Rayleigh table --------------------------------------------------- */
/* BEGIN GENERATED by tests/c_abi/portable.rs from scatterkit::portable::RAYLEIGH_TABLE
   (SK_BLESS=1 cargo test --release --test c_abi portable rewrites it) */
#define SKP_RAYLEIGH_TABLE_DATA \
    -1.0f, 0.010416667f, 5.4251e-5f, 3.8169637e-7f, \
    -0.9895287f, 0.010526313f, 5.539605e-5f, 3.9170752e-7f, \
    -0.9789466f, 0.010638281f, 5.6571134e-5f, 4.0190918e-7f, \
    -0.96825135f, 0.010752629f, 5.777683e-5f, 4.1228927e-7f, \
    -0.95744056f, 0.010869419f, 5.9013666e-5f, 4.2283276e-7f, \
    -0.9465117f, 0.010988715f, 6.0282135e-5f, 4.3352148e-7f, \
    -0.93546224f, 0.0111105805f, 6.158268e-5f, 4.443336e-7f, \
    -0.92428964f, 0.011235079f, 6.2915664e-5f, 4.5524317e-7f, \
    -0.91299117f, 0.011362275f, 6.428138e-5f, 4.662195e-7f, \
    -0.9015642f, 0.011492237f, 6.568004e-5f, 4.772266e-7f, \
    -0.89000577f, 0.011625029f, 6.711172e-5f, 4.8822255e-7f, \
    -0.8783131f, 0.011760717f, 6.857641e-5f, 4.9915866e-7f, \
    -0.86648333f, 0.011899367f, 7.007392e-5f, 5.099788e-7f, \
    -0.8545134f, 0.012041045f, 7.160389e-5f, 5.206183e-7f, \
    -0.84240025f, 0.012185815f, 7.316581e-5f, 5.3100314e-7f, \
    -0.8301407f, 0.01233374f, 7.475889e-5f, 5.4104856e-7f, \
    -0.8177317f, 0.01248488f, 7.638214e-5f, 5.506583e-7f, \
    -0.8051699f, 0.012639296f, 7.803423e-5f, 5.59723e-7f, \
    -0.792452f, 0.012797044f, 7.971355e-5f, 5.681188e-7f, \
    -0.77957463f, 0.0129581755f, 8.141808e-5f, 5.757062e-7f, \
    -0.76653445f, 0.013122738f, 8.314541e-5f, 5.82328e-7f, \
    -0.753328f, 0.013290777f, 8.489264e-5f, 5.878081e-7f, \
    -0.7399517f, 0.013462326f, 8.665636e-5f, 5.9194934e-7f, \
    -0.72640216f, 0.013637414f, 8.843254e-5f, 5.9453214e-7f, \
    -0.71267575f, 0.013816062f, 9.021652e-5f, 5.953126e-7f, \
    -0.69876885f, 0.013998281f, 9.2002905e-5f, 5.9402066e-7f, \
    -0.68467796f, 0.01418407f, 9.378547e-5f, 5.903586e-7f, \
    -0.67039955f, 0.014373411f, 9.555712e-5f, 5.839996e-7f, \
    -0.65593f, 0.014566278f, 9.730977e-5f, 5.745864e-7f, \
    -0.6412658f, 0.014762621f, 9.903426e-5f, 5.6173064e-7f, \
    -0.6264036f, 0.014962374f, 0.000100720266f, 5.450125e-7f, \
    -0.61134f, 0.01516545f, 0.000102356214f, 5.239808e-7f, \
    -0.59607166f, 0.015371734f, 0.00010392916f, 4.9815486e-7f, \
    -0.5805955f, 0.015581087f, 0.00010542474f, 4.6702615e-7f, \
    -0.5649085f, 0.015793338f, 0.00010682704f, 4.300623e-7f, \
    -0.5490079f, 0.016008282f, 0.00010811856f, 3.8671234e-7f, \
    -0.5328911f, 0.016225679f, 0.00010928015f, 3.3641382e-7f, \
    -0.51655585f, 0.01644525f, 0.000110290945f, 2.786023e-7f, \
    -0.5f, 0.016666668f, 0.00011112842f, 2.127232e-7f, \
    -0.48322198f, 0.016889561f, 0.00011176836f, 1.3824659e-7f, \
    -0.46622053f, 0.017113512f, 0.000112184964f, 5.4684875e-8f, \
    -0.4489948f, 0.017338047f, 0.00011235096f, -3.8386275e-8f, \
    -0.43154442f, 0.017562633f, 0.000112237794f, -1.413039e-7f, \
    -0.41386968f, 0.017786685f, 0.000111815905f, -2.5429074e-7f, \
    -0.39597145f, 0.018009555f, 0.000111055066f, -3.774256e-7f, \
    -0.3778512f, 0.018230533f, 0.000109924775f, -5.1061187e-7f, \
    -0.35951126f, 0.01844885f, 0.000108394845f, -6.5354527e-7f, \
    -0.34095466f, 0.018663678f, 0.000106435975f, -8.05682e-7f, \
    -0.32218537f, 0.018874135f, 0.00010402051f, -9.662094e-7f, \
    -0.30320817f, 0.019079277f, 0.00010112321f, -1.1340207e-6f, \
    -0.2840289f, 0.01927812f, 9.772216e-5f, -1.3076974e-6f, \
    -0.26465437f, 0.019469641f, 9.3799696e-5f, -1.4855e-6f, \
    -0.2450924f, 0.019652786f, 8.934338e-5f, -1.6653725e-6f, \
    -0.22535194f, 0.019826476f, 8.434696e-5f, -1.8449595e-6f, \
    -0.20544297f, 0.019989634f, 7.881122e-5f, -2.0216412e-6f, \
    -0.18537654f, 0.020141192f, 7.274486e-5f, -2.1925853e-6f, \
    -0.1651648f, 0.020280104f, 6.6165056e-5f, -2.3548157e-6f, \
    -0.14482088f, 0.020405369f, 5.9097954e-5f, -2.5052984e-6f, \
    -0.12435892f, 0.02051605f, 5.157882e-5f, -2.6410394e-6f, \
    -0.103793934f, 0.020611284f, 4.365191e-5f, -2.7591918e-6f, \
    -0.08314176f, 0.02069031f, 3.5370063e-5f, -2.8571667e-6f, \
    -0.062418938f, 0.020752478f, 2.6793889e-5f, -2.9327389e-6f, \
    -0.041642595f, 0.02079727f, 1.7990695e-5f, -2.9841449e-6f, \
    -0.02083032f, 0.020824298f, 9.033096e-6f, -3.010161e-6f, \
    0.0f, 0.020833334f, -2.6133653e-9f, -3.010161e-6f, \
    0.02083032f, 0.020824298f, -9.03826e-6f, -2.9841449e-6f, \
    0.041642595f, 0.02079727f, -1.7995671e-5f, -2.9327389e-6f, \
    0.062418938f, 0.020752478f, -2.6798563e-5f, -2.8571667e-6f, \
    0.08314176f, 0.02069031f, -3.5374338e-5f, -2.7591918e-6f, \
    0.103793934f, 0.020611284f, -4.3655702e-5f, -2.6410394e-6f, \
    0.12435892f, 0.02051605f, -5.158206e-5f, -2.5052984e-6f, \
    0.14482088f, 0.020405369f, -5.9100606e-5f, -2.3548157e-6f, \
    0.1651648f, 0.020280104f, -6.61671e-5f, -2.1925853e-6f, \
    0.18537654f, 0.020141192f, -7.27463e-5f, -2.0216412e-6f, \
    0.20544297f, 0.019989634f, -7.881208e-5f, -1.8449595e-6f, \
    0.22535194f, 0.019826476f, -8.4347266e-5f, -1.6653725e-6f, \
    0.2450924f, 0.019652786f, -8.934319e-5f, -1.4855e-6f, \
    0.26465437f, 0.019469641f, -9.379906e-5f, -1.3076974e-6f, \
    0.2840289f, 0.01927812f, -9.7721146e-5f, -1.1340207e-6f, \
    0.30320817f, 0.019079277f, -0.000101121885f, -9.662094e-7f, \
    0.32218537f, 0.018874135f, -0.00010401893f, -8.05682e-7f, \
    0.34095466f, 0.018663678f, -0.00010643421f, -6.5354527e-7f, \
    0.35951126f, 0.01844885f, -0.00010839294f, -5.1061187e-7f, \
    0.3778512f, 0.018230533f, -0.00010992279f, -3.774256e-7f, \
    0.39597145f, 0.018009555f, -0.000111053036f, -2.5429074e-7f, \
    0.41386968f, 0.017786685f, -0.00011181388f, -1.413039e-7f, \
    0.43154442f, 0.017562633f, -0.00011223579f, -3.8386275e-8f, \
    0.4489948f, 0.017338047f, -0.000112349015f, 5.4684875e-8f, \
    0.46622053f, 0.017113512f, -0.0001121831f, 1.3824659e-7f, \
    0.48322198f, 0.016889561f, -0.00011176659f, 2.127232e-7f, \
    0.5f, 0.016666668f, -0.00011112675f, 2.786023e-7f, \
    0.51655585f, 0.01644525f, -0.00011028939f, 3.3641382e-7f, \
    0.5328911f, 0.016225679f, -0.0001092787f, 3.8671234e-7f, \
    0.5490079f, 0.016008282f, -0.00010811723f, 4.300623e-7f, \
    0.5649085f, 0.015793338f, -0.00010682582f, 4.6702615e-7f, \
    0.5805955f, 0.015581087f, -0.00010542363f, 4.9815486e-7f, \
    0.59607166f, 0.015371734f, -0.000103928156f, 5.239808e-7f, \
    0.61134f, 0.01516545f, -0.000102355305f, 5.450125e-7f, \
    0.6264036f, 0.014962374f, -0.00010071945f, 5.6173064e-7f, \
    0.6412658f, 0.014762621f, -9.9033525e-5f, 5.745864e-7f, \
    0.65593f, 0.014566278f, -9.730912e-5f, 5.839996e-7f, \
    0.67039955f, 0.014373411f, -9.555655e-5f, 5.903586e-7f, \
    0.68467796f, 0.01418407f, -9.378496e-5f, 5.9402066e-7f, \
    0.69876885f, 0.013998281f, -9.200246e-5f, 5.953126e-7f, \
    0.71267575f, 0.013816062f, -9.0216134e-5f, 5.9453214e-7f, \
    0.72640216f, 0.013637414f, -8.843221e-5f, 5.9194934e-7f, \
    0.7399517f, 0.013462326f, -8.6656066e-5f, 5.878081e-7f, \
    0.753328f, 0.013290777f, -8.4892396e-5f, 5.82328e-7f, \
    0.76653445f, 0.013122738f, -8.3145205e-5f, 5.757062e-7f, \
    0.77957463f, 0.0129581755f, -8.141791e-5f, 5.681188e-7f, \
    0.792452f, 0.012797044f, -7.9713405e-5f, 5.59723e-7f, \
    0.8051699f, 0.012639296f, -7.8034114e-5f, 5.506583e-7f, \
    0.8177317f, 0.01248488f, -7.638204e-5f, 5.4104856e-7f, \
    0.8301407f, 0.01233374f, -7.475882e-5f, 5.3100314e-7f, \
    0.84240025f, 0.012185815f, -7.316575e-5f, 5.206183e-7f, \
    0.8545134f, 0.012041045f, -7.160385e-5f, 5.099788e-7f, \
    0.86648333f, 0.011899367f, -7.007389e-5f, 4.9915866e-7f, \
    0.8783131f, 0.011760717f, -6.8576395e-5f, 4.8822255e-7f, \
    0.89000577f, 0.011625029f, -6.7111716e-5f, 4.772266e-7f, \
    0.9015642f, 0.011492237f, -6.568004e-5f, 4.662195e-7f, \
    0.91299117f, 0.011362275f, -6.428139e-5f, 4.5524317e-7f, \
    0.92428964f, 0.011235079f, -6.291568e-5f, 4.443336e-7f, \
    0.93546224f, 0.0111105805f, -6.15827e-5f, 4.3352148e-7f, \
    0.9465117f, 0.010988715f, -6.0282164e-5f, 4.2283276e-7f, \
    0.95744056f, 0.010869419f, -5.9013695e-5f, 4.1228927e-7f, \
    0.96825135f, 0.010752629f, -5.7776862e-5f, 4.0190918e-7f, \
    0.9789466f, 0.010638281f, -5.657117e-5f, 3.9170752e-7f, \
    0.9895287f, 0.010526313f, -5.539609e-5f, 3.8169637e-7f
/* END GENERATED */

/* Where the table lives: constant memory on GPUs (a CUDA or HIP device
   reads its own copy, the host its), read-only data on a CPU. */
#if defined(SKP_OPENCL_)
#define SKP_TABLE_SPACE __constant
/* static: each program that includes the header has its own copy, so
   programs compiled apart link (clLinkProgram) without a clash. */
static __constant float skp_rayleigh_table_[512] = {SKP_RAYLEIGH_TABLE_DATA};
#define SKP_RAYLEIGH_TABLE skp_rayleigh_table_
#else
#define SKP_TABLE_SPACE
#if defined(__GNUC__) || defined(__clang__)
#define SKP_UNUSED_ __attribute__((unused))
#else
#define SKP_UNUSED_
#endif
static const float skp_rayleigh_table_[512] SKP_UNUSED_ = {SKP_RAYLEIGH_TABLE_DATA};
#if defined(__CUDACC__) || defined(__CUDA__) || defined(__HIP__) || defined(__HIPCC__)
#if defined(__clang__)
static __attribute__((constant)) const float skp_rayleigh_table_dev_[512] SKP_UNUSED_ = {
    SKP_RAYLEIGH_TABLE_DATA};
#else
static __constant__ const float skp_rayleigh_table_dev_[512] SKP_UNUSED_ = {
    SKP_RAYLEIGH_TABLE_DATA};
#endif
#endif
#if defined(__CUDA_ARCH__) || defined(__HIP_DEVICE_COMPILE__)
#define SKP_RAYLEIGH_TABLE skp_rayleigh_table_dev_
#else
#define SKP_RAYLEIGH_TABLE skp_rayleigh_table_
#endif
#endif

/* ---- types --------------------------------------------------------------- */
/* A vector (direction or point). */
typedef struct skp_vec3 {
    float x, y, z;
} skp_vec3;

/* What a direction sampler returns: the unit direction, the cosine of its
   angle to w_in (the sampled cos theta, exactly) and its density per
   steradian. Returned by value, so a kernel may store it anywhere. */
typedef struct skp_dir_sample {
    skp_vec3 dir;
    float cos_theta;
    float pdf;
} skp_dir_sample;

/* Henyey-Greenstein's constants for one asymmetry g (fill with skp_hg_new):
   the Rust scatterkit::portable::Hg, field for field. */
typedef struct skp_hg {
    float a;    /* g' = |g| */
    float sign; /* +1 for g > 0, -1 for g <= 0 */
    float omg;  /* 1 - g' */
    float c1;   /* 2 (1 + g')^2 (1 - g') */
    float c2;   /* 2 g' (1 + g')^2 */
    float c3;   /* 2 (1 - g')^2 */
    float c4;   /* 2 g' (1 - g')^2 */
    float kd;   /* 1 / (4 pi (1 - g^2)^2) */
    float k2;   /* (1 - g')^2 */
    float kp;   /* (1 - g^2) / (4 pi) */
} skp_hg;

#define SKP_INV_4PI 0.07957747f
#define SKP_RAYLEIGH_K 0.059683103f

/* ---- azimuth and frame --------------------------------------------------- */
/* (sin 2 pi u, cos 2 pi u) for u in [0, 1], reduced exactly in turns: within
   1.65 ulp of each. */
SKP_FN void skp_sin_cos_2pi(float u, float *s_out, float *c_out) {
    SKP_BEGIN
    const float magic = 12582912.0f; /* 1.5 * 2^23 */
    float x = SKP_MUL(4.0f, u);
    float shifted = x + magic;
    skp_u32 q = skp_bits(shifted);
    float r = x - (shifted - magic);
    float t = r * r;
    float t2 = t * t;
    float s = SKP_MUL(r, 1.5707964f) +
              SKP_MUL(r, (-4.8797943e-8f + SKP_MUL(t, -0.64596346f)) +
                             SKP_MUL(t2, 0.07968003f + SKP_MUL(t, -0.004601658f)));
    float c = 1.0f + SKP_MUL(t, (-1.2337005f + SKP_MUL(t, 0.25366918f)) +
                                    SKP_MUL(t2, -0.020859936f + SKP_MUL(t, 0.000903363f)));
    float sw = s;
    if (q & 1u) {
        s = c;
        c = sw;
    }
    *s_out = skp_from_bits(skp_bits(s) ^ ((q & 2u) << 30));
    *c_out = skp_from_bits(skp_bits(c) ^ (((q + 1u) & 2u) << 30));
}

/* (b1, b2) completing the unit n to a right-handed orthonormal basis (Duff et
   al., JCGT 6(1), 2017; -0 in n.z counts as negative). */
SKP_FN void skp_frame(skp_vec3 n, skp_vec3 *b1, skp_vec3 *b2) {
    SKP_BEGIN
    float sign = skp_from_bits(0x3f800000u | (skp_bits(n.z) & 0x80000000u));
    float a = -1.0f / (sign + n.z);
    float b = n.x * n.y * a;
    b1->x = 1.0f + SKP_MUL(sign * n.x * n.x, a);
    b1->y = sign * b;
    b1->z = -(sign * n.x);
    b2->x = b;
    b2->y = sign + SKP_MUL(n.y * n.y, a);
    b2->z = -n.y;
}

/* The unit direction at cos theta = mu, sin theta = sin_theta and azimuth
   2 pi turns about the unit axis. */
SKP_FN skp_vec3 skp_direction_about(skp_vec3 axis, float mu, float sin_theta, float turns) {
    SKP_BEGIN
    float sp, cp, lx, ly;
    skp_vec3 b1, b2, o;
    skp_sin_cos_2pi(turns, &sp, &cp);
    skp_frame(axis, &b1, &b2);
    lx = sin_theta * cp;
    ly = sin_theta * sp;
    o.x = SKP_MUL(b1.x, lx) + SKP_MUL(b2.x, ly) + SKP_MUL(axis.x, mu);
    o.y = SKP_MUL(b1.y, lx) + SKP_MUL(b2.y, ly) + SKP_MUL(axis.y, mu);
    o.z = SKP_MUL(b1.z, lx) + SKP_MUL(b2.z, ly) + SKP_MUL(axis.z, mu);
    return o;
}

/* ---- isotropic ----------------------------------------------------------- */
/* cos theta = 2u - 1 (u = 0 gives -1) and sin theta = 2 sqrt(u (1 - u)). */
SKP_FN float skp_isotropic_sample_cos_sin(float u, float *sin_out) {
    SKP_BEGIN
    float w = skp_clamp01(u);
    *sin_out = 2.0f * skp_sqrt(w * (1.0f - w));
    return SKP_MUL(2.0f, w) - 1.0f;
}

/* A direction sample from cos theta, sin theta and the density, the
   azimuth 2 pi turns about the unit w_in. */
SKP_FN skp_dir_sample skp_dir_sample_(skp_vec3 w_in, float mu, float sin_theta, float turns, float pdf) {
    skp_dir_sample r;
    r.dir = skp_direction_about(w_in, mu, sin_theta, turns);
    r.cos_theta = mu;
    r.pdf = pdf;
    return r;
}

/* An isotropic direction from two uniforms (cos theta from u1 about +z,
   azimuth 2 pi u2), density 1/(4 pi). */
SKP_FN skp_dir_sample skp_isotropic_sample_dir(float u1, float u2) {
    SKP_BEGIN
    float s;
    float mu = skp_isotropic_sample_cos_sin(u1, &s);
    skp_vec3 z;
    z.x = 0.0f;
    z.y = 0.0f;
    z.z = 1.0f;
    return skp_dir_sample_(z, mu, s, u2, SKP_INV_4PI);
}

/* ---- error-free transformations (for the constructors) ---------------- */
/* s + e = a + b exactly, s = fl(a + b) (TwoSum). */
SKP_FN void skp_two_sum_(float a, float b, float *s, float *e) {
    SKP_BEGIN
    float x = a + b;
    float bb = x - a;
    *s = x;
    *e = (a - (x - bb)) + (b - bb);
}

/* p + e = a b exactly, p = fl(a b) (Dekker's TwoProduct, Veltkamp's split
   with 2^12 + 1, no fused multiply-add). */
SKP_FN void skp_two_prod_(float a, float b, float *p, float *e) {
    SKP_BEGIN
    float ca = SKP_MUL(4097.0f, a), cb = SKP_MUL(4097.0f, b);
    float ah = ca - (ca - a), bh = cb - (cb - b);
    float al = a - ah, bl = b - bh;
    float x = SKP_MUL(a, b);
    *p = x;
    *e = ((SKP_MUL(ah, bh) - x) + SKP_MUL(ah, bl) + SKP_MUL(al, bh)) + SKP_MUL(al, bl);
}

/* (h, l) = x y for pairs x = (xh, xl), y = (yh, yl), renormalised. */
SKP_FN void skp_dd_mul_(float xh, float xl, float yh, float yl, float *h, float *l) {
    SKP_BEGIN
    float p, e, s;
    skp_two_prod_(xh, yh, &p, &e);
    e = e + (SKP_MUL(xh, yl) + SKP_MUL(xl, yh));
    s = p + e;
    *h = s;
    *l = e - (s - p);
}

/* ---- Henyey-Greenstein --------------------------------------------------- */
/* The constants for g: 1 for -1 <= g <= 1, else 0 with every field NaN (so a
   sampler given them returns NaN). c1 ... c4 are rounded once from their
   exact values (error-free transformations in float).
   |g| = 1 is the Dirac limit, which transport codes give a background
   medium: every sampler returns cos theta = g (sin theta 0), the density is
   +inf at cos theta = g and 0 elsewhere (HG's density as |g| -> 1, point by
   point), and a sampler's density is +inf. A caller that weighs a sample by
   value over density takes that ratio as 1, as for any sample of a phase
   function's own distribution. */
SKP_FN int skp_hg_new(float g, skp_hg *p) {
    SKP_BEGIN
    float a, ph, pl, mh, ml, p2h, p2l, m2h, m2l, h, l, c;
    a = skp_from_bits(skp_bits(g) & 0x7fffffffu); /* |g| */
    if (!(a <= 1.0f)) {
        float nan = skp_from_bits(0x7fc00000u);
        p->a = nan;
        p->sign = nan;
        p->omg = nan;
        p->c1 = nan;
        p->c2 = nan;
        p->c3 = nan;
        p->c4 = nan;
        p->kd = nan;
        p->k2 = nan;
        p->kp = nan;
        return 0;
    }
    skp_two_sum_(1.0f, a, &ph, &pl);
    skp_two_sum_(1.0f, -a, &mh, &ml);
    skp_dd_mul_(ph, pl, ph, pl, &p2h, &p2l);
    skp_dd_mul_(mh, ml, mh, ml, &m2h, &m2l);
    c = mh * ph;
    p->a = a;
    p->sign = g > 0.0f ? 1.0f : -1.0f;
    p->omg = mh;
    skp_dd_mul_(p2h, p2l, mh, ml, &h, &l);
    p->c1 = SKP_MUL(2.0f, h + l);
    skp_dd_mul_(p2h, p2l, a, 0.0f, &h, &l);
    p->c2 = SKP_MUL(2.0f, h + l);
    p->c3 = SKP_MUL(2.0f, m2h + m2l);
    skp_dd_mul_(m2h, m2l, a, 0.0f, &h, &l);
    p->c4 = SKP_MUL(2.0f, h + l);
    p->kd = SKP_INV_4PI / (c * c); /* +inf for |g| = 1 */
    p->k2 = SKP_MUL(mh, mh);
    p->kp = SKP_INV_4PI * c;
    return 1;
}

/* P and M at u in [0, 1], and g' u' (the Rust module documents them):
   1 + mu' = P/d^2, 1 - mu' = M/d^2, u' = u (g > 0) or 1 - u, v' = 1 - u'. */
SKP_FN float skp_hg_pm_(skp_hg p, float u, float *mm, float *gu) {
    SKP_BEGIN
    float u1, v1;
    if (p.sign > 0.0f) {
        u1 = u;
        v1 = 1.0f - u;
    } else {
        u1 = 1.0f - u;
        v1 = u;
    }
    *mm = SKP_MUL(v1, p.c3 + SKP_MUL(p.c4, u1));
    *gu = SKP_MUL(p.a, u1);
    return SKP_MUL(u1, p.c1 + SKP_MUL(p.c2, u1));
}

/* cos theta = F^-1(u) = +-(P - M)/(P + M) (u clamped to [0, 1], NaN gives
   NaN): within 1.6e-7 for every |g| < 1; g itself for |g| = 1. */
SKP_FN float skp_hg_sample_cos(skp_hg p, float u) {
    SKP_BEGIN
    float mm, gu, pp;
    if (p.a == 1.0f) {
        return u != u ? u : p.sign; /* the Dirac limit */
    }
    pp = skp_hg_pm_(p, skp_clamp01(u), &mm, &gu);
    return p.sign * ((pp - mm) / (pp + mm));
}

/* cos theta at u, with *sin_out = sin theta = 2 sqrt(P M)/(P + M) and *pdf
   the density there, d^3/(4 pi (1 - g^2)^2) (|g| = 1: sin theta 0, density
   +inf). */
SKP_FN float skp_hg_sample_cos_sin(skp_hg p, float u, float *sin_out, float *pdf) {
    SKP_BEGIN
    float mm, gu, sum, d, pp;
    if (p.a == 1.0f) {
        *sin_out = u != u ? u : 0.0f;
        *pdf = u != u ? u : p.kd;
        return u != u ? u : p.sign;
    }
    pp = skp_hg_pm_(p, skp_clamp01(u), &mm, &gu);
    sum = pp + mm;
    d = p.omg + SKP_MUL(2.0f, gu); /* gu + gu, exactly */
    *sin_out = 2.0f * skp_sqrt(pp * mm) / sum;
    *pdf = p.kd * (d * d * d);
    return p.sign * ((pp - mm) / sum);
}

/* The scattered direction about the unit w_in (cos theta from u1, azimuth
   2 pi u2), its cos theta and its density per steradian. */
SKP_FN skp_dir_sample skp_hg_sample_dir(skp_hg p, skp_vec3 w_in, float u1, float u2) {
    float s, pdf;
    float mu = skp_hg_sample_cos_sin(p, u1, &s, &pdf);
    return skp_dir_sample_(w_in, mu, s, u2, pdf);
}

/* The density per steradian at cos theta = mu in [-1, 1] (|g| = 1: +inf at
   mu = g, 0 elsewhere). */
SKP_FN float skp_hg_pdf(skp_hg p, float mu) {
    SKP_BEGIN
    float q = p.k2 + SKP_MUL(2.0f * p.a, 1.0f - SKP_MUL(p.sign, mu));
    if (p.a == 1.0f) {
        return q > 0.0f ? 0.0f : (q == 0.0f ? p.kd : skp_from_bits(0x7fc00000u));
    }
    return p.kp / (q * skp_sqrt(q));
}

/* ---- two-lobe Henyey-Greenstein ------------------------------------------ */
/* Two HG lobes mixed with weight w on the first (fill with skp_two_lobe_new):
   p = w p_1 + (1 - w) p_2. */
typedef struct skp_two_lobe {
    skp_hg first, second;
    float w;
} skp_two_lobe;

/* The lobes g1, g2 (each in [-1, 1]; |g| = 1 is the Dirac limit, see
   skp_hg_new) with weight w in [0, 1] on the first: 1, else 0 with every
   field NaN. */
SKP_FN int skp_two_lobe_new(float g1, float g2, float w, skp_two_lobe *p) {
    int ok = w >= 0.0f && w <= 1.0f;
    ok = skp_hg_new(g1, &p->first) & ok;
    ok = skp_hg_new(g2, &p->second) & ok;
    p->w = w;
    if (!ok) {
        skp_hg_new(skp_from_bits(0x7fc00000u), &p->first);
        p->second = p->first;
        p->w = skp_from_bits(0x7fc00000u);
    }
    return ok;
}

/* The lobe one uniform picks and the uniform rescaled inside it. */
SKP_FN skp_hg skp_two_lobe_pick_(skp_two_lobe p, float u, float *v) {
    float w = skp_clamp01(u);
    if (w < p.w) {
        *v = w / p.w;
        return p.first;
    }
    if (p.w < 1.0f) {
        *v = (w - p.w) / (1.0f - p.w);
        return p.second;
    }
    *v = 1.0f;
    return p.first;
}

/* cos theta for u (clamped; NaN gives NaN), the lobe chosen by u itself:
   exact in distribution, not monotone across the lobes. */
SKP_FN float skp_two_lobe_sample_cos(skp_two_lobe p, float u) {
    float v;
    skp_hg lobe = skp_two_lobe_pick_(p, u, &v);
    return skp_hg_sample_cos(lobe, v);
}

/* The density per steradian at cos theta = mu, w p_1 + (1 - w) p_2 (a lobe
   of weight 0 adds nothing, even where a Dirac lobe's density is +inf). */
SKP_FN float skp_two_lobe_pdf(skp_two_lobe p, float mu) {
    SKP_BEGIN
    float a = p.w > 0.0f ? SKP_MUL(p.w, skp_hg_pdf(p.first, mu)) : 0.0f;
    float b = p.w < 1.0f ? SKP_MUL(1.0f - p.w, skp_hg_pdf(p.second, mu)) : 0.0f;
    return a + b;
}

/* A direction about the unit w_in (cos theta and the lobe from u1, azimuth
   2 pi u2), its cos theta and the mixture's density there. */
SKP_FN skp_dir_sample skp_two_lobe_sample_dir(skp_two_lobe p, skp_vec3 w_in, float u1, float u2) {
    float v, s, lobe_pdf, mu;
    skp_hg lobe = skp_two_lobe_pick_(p, u1, &v);
    mu = skp_hg_sample_cos_sin(lobe, v, &s, &lobe_pdf);
    return skp_dir_sample_(w_in, mu, s, u2, skp_two_lobe_pdf(p, mu));
}

/* ---- Schlick ------------------------------------------------------------- */
/* Schlick's phase function (Blasi, Le Saec & Schlick 1993, eq. 3),
   p = (1 - k^2)/(4 pi (1 - k mu)^2), -1 < k < 1, with the library's
   cancellation-free inverse. Fill with skp_schlick_new. */
typedef struct skp_schlick {
    float k;
    float omk;  /* 1 - k */
    float opk;  /* 1 + k */
    float norm; /* (1 - k)(1 + k)/(4 pi) */
} skp_schlick;

/* 1 for -1 < k < 1; 0 otherwise (NaN included), the constants then NaN. */
SKP_FN int skp_schlick_new(float k, skp_schlick *p) {
    SKP_BEGIN
    if (!(k > -1.0f && k < 1.0f)) {
        float nan = skp_from_bits(0x7fc00000u);
        p->k = nan;
        p->omk = nan;
        p->opk = nan;
        p->norm = nan;
        return 0;
    }
    p->k = k;
    p->omk = 1.0f - k;
    p->opk = 1.0f + k;
    p->norm = p->omk * p->opk * SKP_INV_4PI;
    return 1;
}

/* cos theta at u (clamped; NaN gives NaN), monotone in u. */
SKP_FN float skp_schlick_sample_cos(skp_schlick p, float u) {
    SKP_BEGIN
    float v = skp_clamp01(u), d, mu;
    if (p.k >= 0.0f) {
        d = p.omk + SKP_MUL(2.0f * p.k, v);
    } else {
        d = p.opk - SKP_MUL(2.0f * p.k, 1.0f - v);
    }
    if (2.0f * v <= p.omk) {
        mu = (2.0f * v) * p.opk / d - 1.0f;
    } else {
        mu = 1.0f - (2.0f * p.omk) * (1.0f - v) / d;
    }
    return mu > 1.0f ? 1.0f : (mu < -1.0f ? -1.0f : mu);
}

/* The density per steradian at cos theta = mu. */
SKP_FN float skp_schlick_pdf(skp_schlick p, float mu) {
    SKP_BEGIN
    float d;
    if (p.k >= 0.0f) {
        d = p.omk + SKP_MUL(p.k, 1.0f - mu);
    } else {
        d = p.opk - SKP_MUL(p.k, 1.0f + mu);
    }
    return p.norm / (d * d);
}

/* A direction about the unit w_in, its cos theta and its density. */
SKP_FN skp_dir_sample skp_schlick_sample_dir(skp_schlick p, skp_vec3 w_in, float u1, float u2) {
    SKP_BEGIN
    float mu = skp_schlick_sample_cos(p, u1);
    float s = skp_sqrt((1.0f - mu) * (1.0f + mu));
    return skp_dir_sample_(w_in, mu, s, u2, skp_schlick_pdf(p, mu));
}

/* ---- Rayleigh ------------------------------------------------------------ */
/* cos theta = F^-1(u) from the built-in table: x = 128 u, i = min(floor(x),
   127), t = x - i, the interval's cubic by Horner, clamped to [-1, 1]
   (u clamped to [0, 1], NaN gives NaN). Within 6e-8 of the exact inverse. */
SKP_FN float skp_rayleigh_sample_cos(float u) {
    SKP_BEGIN
    float x = SKP_MUL(skp_clamp01(u), 128.0f), t, mu;
    int i = x >= 1.0f ? (int)x : 0; /* x >= 1 excludes NaN */
    const SKP_TABLE_SPACE float *c;
    i = i > 127 ? 127 : i;
    t = x - (float)i;
    c = SKP_RAYLEIGH_TABLE + 4 * i;
    mu = c[0] + SKP_MUL(t, c[1] + SKP_MUL(t, c[2] + SKP_MUL(t, c[3])));
    return mu > 1.0f ? 1.0f : (mu < -1.0f ? -1.0f : mu);
}

/* Rayleigh's density per steradian, 3 (1 + mu^2) / (16 pi). */
SKP_FN float skp_rayleigh_pdf(float mu) {
    SKP_BEGIN
    return SKP_RAYLEIGH_K * (1.0f + SKP_MUL(mu, mu));
}

/* A Rayleigh direction about the unit w_in, its cos theta and density. */
SKP_FN skp_dir_sample skp_rayleigh_sample_dir(skp_vec3 w_in, float u1, float u2) {
    SKP_BEGIN
    float mu = skp_rayleigh_sample_cos(u1);
    float s = skp_sqrt((1.0f - mu) * (1.0f + mu));
    return skp_dir_sample_(w_in, mu, s, u2, skp_rayleigh_pdf(mu));
}

/* ---- Draine and Cornette-Shanks ------------------------------------------ */
/* Eq. 6's constants for one orientation (the Rust DraineSide, field for
   field). */
typedef struct skp_draine_side {
    float d, q, r, t0, t1, t6, t6_3, two_inv_t0, eight_inv_t0, k, half_g, inv_2g;
} skp_draine_side;

/* Draine's sampler constants (fill with skp_draine_new): both orientations
   and the density's constant. */
typedef struct skp_draine {
    skp_draine_side lower; /* u <= 1/2 */
    skp_draine_side upper; /* u > 1/2: the mirror (-g, 1 - u) */
    float g, alpha, kp;
} skp_draine;

SKP_FN void skp_draine_side_(float g, float a, skp_draine_side *e) {
    SKP_BEGIN
    float g2 = SKP_MUL(g, g);
    float omg = 1.0f - g;
    float omg2 = omg * (1.0f + g);
    float opg2 = 1.0f + g2;
    float t0 = a * omg2;
    float t6 = -4.0f * t0 * g2 * omg2;
    float p = SKP_MUL(omg, SKP_MUL(3.0f, g2) +
                               SKP_MUL(a, 2.0f + SKP_MUL(g, 2.0f + SKP_MUL(g, 3.0f + SKP_MUL(g, 2.0f + SKP_MUL(2.0f, g))))));
    float q = 2.0f * g * g2 * (3.0f + SKP_MUL(a, 1.0f + SKP_MUL(2.0f, g2)));
    float r = skp_sqrt(4.0f * a * (omg2 * omg2) * opg2 * (SKP_MUL(3.0f, g2) + SKP_MUL(a * opg2, opg2)));
    float b = SKP_MUL(a, SKP_MUL(a, SKP_MUL(4.0f, g2) - g + 4.0f) + SKP_MUL(6.0f, SKP_MUL(2.0f, g2) + g + 2.0f)) -
              SKP_MUL(9.0f, g);
    e->d = -(g * g2) * (omg * omg) * b / (p + r);
    e->q = q;
    e->r = r;
    e->t0 = t0;
    e->t1 = SKP_MUL(-a * omg2, opg2);
    e->t6 = t6;
    e->t6_3 = SKP_MUL(t6 * t6, t6);
    e->two_inv_t0 = 2.0f / t0;
    e->eight_inv_t0 = 8.0f / t0;
    e->k = SKP_MUL(6.0f, opg2);
    e->half_g = SKP_MUL(0.5f, g);
    e->inv_2g = 0.5f / g;
}

/* The constants for g and alpha: 1 within the reach 1e-3 <= |g| < 1,
   1 <= alpha <= 1e4, else 0 with every field NaN. */
SKP_FN int skp_draine_new(float g, float alpha, skp_draine *p) {
    SKP_BEGIN
    float ga = skp_from_bits(skp_bits(g) & 0x7fffffffu), norm;
    if (!(ga >= 1e-3f && ga < 1.0f && alpha >= 1.0f && alpha <= 1e4f)) {
        float nan = skp_from_bits(0x7fc00000u);
        skp_draine_side_(nan, nan, &p->lower);
        p->upper = p->lower;
        p->g = nan;
        p->alpha = nan;
        p->kp = nan;
        return 0;
    }
    norm = 1.0f + alpha * (1.0f + SKP_MUL(2.0f * g, g)) / 3.0f;
    skp_draine_side_(g, alpha, &p->lower);
    skp_draine_side_(-g, alpha, &p->upper);
    p->g = g;
    p->alpha = alpha;
    p->kp = SKP_INV_4PI * ((1.0f - g) * (1.0f + g)) / norm;
    return 1;
}

/* cbrt(x) in float alone: Kahan's seed and two Halley steps. */
SKP_FN float skp_cbrt_(float x) {
    SKP_BEGIN
    skp_u32 sign = skp_bits(x) & 0x80000000u;
    float a = skp_from_bits(skp_bits(x) & 0x7fffffffu);
    float t = skp_from_bits(skp_bits(a) / 3u + 709958130u), t3;
    int i;
    for (i = 0; i < 2; i++) {
        t3 = SKP_MUL(t * t, t);
        t = t * (t3 + SKP_MUL(2.0f, a)) / (SKP_MUL(2.0f, t3) + a);
    }
    return skp_from_bits(skp_bits(t) | sign);
}

/* Eq. 6 for one orientation at u in [0, 1/2]. */
SKP_FN float skp_draine_side_sample_(skp_draine_side e, float u) {
    SKP_BEGIN
    float lo = e.d + SKP_MUL(e.q, u);
    float t4 = lo + e.r;
    float t5 = SKP_MUL(e.t0, lo * (lo + SKP_MUL(2.0f, e.r)));
    float root = skp_sqrt(SKP_MUL(t5, t5) - e.t6_3);
    float m = t5 + skp_from_bits(skp_bits(root) | (skp_bits(t5) & 0x80000000u));
    float c = skp_cbrt_(m);
    float t8 = SKP_MUL(e.t1 + c + e.t6 / c, e.two_inv_t0);
    float t9 = skp_sqrt(e.k + t8);
    float d = skp_sqrt(e.k - t8 + t4 * e.eight_inv_t0 / t9) - t9;
    /* Rounded, the last step lands up to a few ulp past +-1, where sin
       theta would be NaN: clamped, NaN kept. */
    float mu = e.half_g + SKP_MUL(1.0f - SKP_MUL(0.25f * d, d), e.inv_2g);
    return mu > 1.0f ? 1.0f : (mu < -1.0f ? -1.0f : mu);
}

/* Draine's cos theta = F^-1(u) (u clamped to [0, 1], NaN gives NaN): eq. 6
   of Jendersie and d'Eon (2023) rearranged without its cancellations, in
   float; never further from the exact inverse than eq. 6 as published. */
SKP_FN float skp_draine_sample_cos(skp_draine p, float u) {
    SKP_BEGIN
    float w = skp_clamp01(u);
    return w > 0.5f ? -skp_draine_side_sample_(p.upper, 1.0f - w) : skp_draine_side_sample_(p.lower, w);
}

/* Draine's density per steradian at cos theta = mu. */
SKP_FN float skp_draine_pdf(skp_draine p, float mu) {
    SKP_BEGIN
    float q = 1.0f + SKP_MUL(p.g, p.g) - SKP_MUL(2.0f * p.g, mu);
    return p.kp * (1.0f + SKP_MUL(p.alpha * mu, mu)) / (q * skp_sqrt(q));
}

/* A Draine direction about the unit w_in (cos theta from u1, azimuth
   2 pi u2), its cos theta and its density. */
SKP_FN skp_dir_sample skp_draine_sample_dir(skp_draine p, skp_vec3 w_in, float u1, float u2) {
    SKP_BEGIN
    float mu = skp_draine_sample_cos(p, u1);
    float s = skp_sqrt((1.0f - mu) * (1.0f + mu));
    return skp_dir_sample_(w_in, mu, s, u2, skp_draine_pdf(p, mu));
}

/* ---- the fog (Jendersie and d'Eon 2023) ---------------------------------- */
/* A Henyey-Greenstein lobe and a Draine lobe, p = (1 - w_d) p_HG + w_d p_D
   (fill with skp_fog_new from the fit's parameters, which the library's
   sk_phase params give for a droplet diameter). */
typedef struct skp_fog {
    skp_hg hg;
    skp_draine draine;
    float w_d;
} skp_fog;

/* 1 for g_hg in [-1, 1] (|g_hg| = 1: a Dirac lobe, see skp_hg_new), the Draine lobe within skp_draine_new's reach and
   w_d in [0, 1]; else 0 with every field NaN. */
SKP_FN int skp_fog_new(float g_hg, float g_d, float alpha, float w_d, skp_fog *p) {
    int ok = w_d >= 0.0f && w_d <= 1.0f;
    ok = skp_hg_new(g_hg, &p->hg) & ok;
    ok = skp_draine_new(g_d, alpha, &p->draine) & ok;
    p->w_d = w_d;
    if (!ok) {
        skp_hg_new(skp_from_bits(0x7fc00000u), &p->hg);
        skp_draine_new(skp_from_bits(0x7fc00000u), 1.0f, &p->draine);
        p->w_d = skp_from_bits(0x7fc00000u);
    }
    return ok;
}

/* cos theta for u (clamped; NaN gives NaN) by the paper's lobe choice: u <
   w_d picks the Draine lobe with u / w_d, else HG with (u - w_d)/(1 - w_d). */
SKP_FN float skp_fog_sample_cos(skp_fog p, float u) {
    float w = skp_clamp01(u);
    if (w < p.w_d) return skp_draine_sample_cos(p.draine, w / p.w_d);
    if (p.w_d < 1.0f) return skp_hg_sample_cos(p.hg, (w - p.w_d) / (1.0f - p.w_d));
    return skp_draine_sample_cos(p.draine, 1.0f);
}

/* The fog's density per steradian at cos theta = mu (an HG lobe of weight
   0 adds nothing, even a Dirac one). */
SKP_FN float skp_fog_pdf(skp_fog p, float mu) {
    SKP_BEGIN
    float h = p.w_d < 1.0f ? SKP_MUL(1.0f - p.w_d, skp_hg_pdf(p.hg, mu)) : 0.0f;
    return h + SKP_MUL(p.w_d, skp_draine_pdf(p.draine, mu));
}

/* A fog direction about the unit w_in (cos theta and the lobe from u1 as
   skp_fog_sample_cos, azimuth 2 pi u2), its cos theta and the fog's
   density there. */
SKP_FN skp_dir_sample skp_fog_sample_dir(skp_fog p, skp_vec3 w_in, float u1, float u2) {
    SKP_BEGIN
    float mu = skp_fog_sample_cos(p, u1);
    float s = skp_sqrt((1.0f - mu) * (1.0f + mu));
    return skp_dir_sample_(w_in, mu, s, u2, skp_fog_pdf(p, mu));
}

/* ---- free flight --------------------------------------------------------- */
/* The natural logarithm, within an ulp: ln 0 = -inf, ln inf = inf, NaN for
   negative x or NaN (the fdlibm logf scheme). */
SKP_FN float skp_ln(float x) {
    SKP_BEGIN
    skp_u32 ix;
    int k0 = 0, k;
    float m, f, s, z, w, r, hfsq, dk;
    if (!(x > 0.0f)) {
        return x == 0.0f ? -skp_from_bits(0x7f800000u) : skp_from_bits(0x7fc00000u);
    }
    if (x == skp_from_bits(0x7f800000u)) {
        return x;
    }
    if (x < 1.17549435e-38f) {
        x = x * 33554432.0f;
        k0 = -25;
    }
    ix = skp_bits(x) + (0x3f800000u - 0x3f3504f3u);
    k = k0 + (int)(ix >> 23) - 127;
    m = skp_from_bits((ix & 0x007fffffu) + 0x3f3504f3u);
    f = m - 1.0f;
    s = f / (2.0f + f);
    z = s * s;
    w = z * z;
    r = SKP_MUL(z, 0.6666666f + SKP_MUL(w, 0.28498787f)) +
        SKP_MUL(w, 0.40000972f + SKP_MUL(w, 0.24279079f));
    hfsq = SKP_MUL(0.5f * f, f);
    dk = (float)k;
    return SKP_MUL(dk, 0.6931381f) -
           ((hfsq - (SKP_MUL(s, hfsq + r) + SKP_MUL(dk, 9.058001e-06f))) - f);
}

/* A free-flight distance -ln(1 - u)/sigma_t in a homogeneous medium
   (sigma_t > 0 per length unit; u clamped, u = 1 gives +inf), small u kept
   to their relative precision. */
SKP_FN float skp_free_path(float sigma_t, float u) {
    SKP_BEGIN
    float v = skp_clamp01(u);
    float w = 1.0f - v;
    float l = w == 0.0f ? -skp_from_bits(0x7f800000u) : skp_ln(w) + ((1.0f - w) - v) / w;
    return -l / sigma_t;
}

/* e^x within an ulp (fdlibm's expf scheme: x = k ln 2 + r, |r| <= ln 2 / 2,
   a rational form in r, then the exact scaling by 2^k): +inf from
   x >= 88.722839, 0 below -103.972084, subnormal between; NaN gives NaN. */
SKP_FN float skp_exp(float x) {
    SKP_BEGIN
    int k;
    float kf, hi, lo, r, t, c, y;
    if (x != x) {
        return x;
    }
    if (x >= skp_from_bits(0x42b17218u)) {
        return skp_from_bits(0x7f800000u);
    }
    if (x < -103.972084f) {
        return 0.0f;
    }
    k = (int)(SKP_MUL(1.44269502f, x) + (x < 0.0f ? -0.5f : 0.5f));
    kf = (float)k;
    hi = x - SKP_MUL(kf, 0.69314575f);
    lo = SKP_MUL(kf, 1.4286068e-06f);
    r = hi - lo;
    t = r * r;
    c = r - SKP_MUL(t, 0.16666625f + SKP_MUL(t, -2.7667333e-03f));
    if (k == 0) {
        return 1.0f - ((r * c) / (c - 2.0f) - r);
    }
    y = 1.0f - ((lo - (r * c) / (2.0f - c)) - hi);
    if (k >= -125) {
        if (k == 128) {
            return y * 2.0f * skp_from_bits(0x7f000000u);
        }
        return y * skp_from_bits((skp_u32)(127 + k) << 23);
    }
    return y * skp_from_bits((skp_u32)(127 + k + 100) << 23) * skp_from_bits(0x0d800000u);
}

/* The transmittance e^(-sigma_t d) of a homogeneous medium (sigma_t >= 0 per
   length unit, d >= 0). */
SKP_FN float skp_transmittance(float sigma_t, float d) {
    return skp_exp(-SKP_MUL(sigma_t, d));
}

/* Free flight in a spectral medium (hero-wavelength sampling): the distance
   drawn at sigma_t[hero], t = -ln(1 - u)/sigma_t[hero], returned (+inf for
   u = 1); ratio[c] receives channel c's density of the same event over the
   hero's: (sigma_c/sigma_h) e^(-(sigma_c - sigma_h) t) for a collision
   (t < t_max), e^(-(sigma_c - sigma_h) t_max) for an escape (t >= t_max).
   Their mean is the balance heuristic's denominator over a uniformly drawn
   hero. NaN, with ratio untouched, for a NaN u, hero >= n or
   sigma_t[hero] not finite and > 0. sigma_t: n finite values >= 0; ratio:
   n values. */
SKP_FN float skp_spectral_free_path(const float *sigma_t, skp_u32 n, skp_u32 hero, float u,
                                    float t_max, float *ratio) {
    SKP_BEGIN
    float sh, t, at, d, e;
    skp_u32 c;
    int escaped;
    if (hero >= n || !(sigma_t[hero] > 0.0f && sigma_t[hero] < skp_from_bits(0x7f800000u))) {
        return skp_from_bits(0x7fc00000u);
    }
    sh = sigma_t[hero];
    t = skp_free_path(sh, u);
    if (t != t) {
        return t;
    }
    escaped = !(t < t_max);
    at = escaped ? t_max : t;
    for (c = 0u; c < n; ++c) {
        d = sigma_t[c] - sh;
        e = d == 0.0f ? 1.0f : skp_exp(-SKP_MUL(d, at));
        ratio[c] = escaped ? e : sigma_t[c] / sh * e;
    }
    return t;
}

/* ---- tables the library built ------------------------------------------ */
/* The data of an sk_table or sk_table2d (layouts in scatterkit_table.h),
   copied to the device as it is. SKP_GLOBAL is the address space the data
   lives in: __global in OpenCL unless defined before this header (say
   __constant), nothing elsewhere. cos theta is the library's lookup, bit for
   bit; the density comes from the interval the sample fell in, so a kernel
   needs no root-finding. n = 0 gives NaN. */
#ifndef SKP_GLOBAL
#if defined(SKP_OPENCL_)
#define SKP_GLOBAL __global
#else
#define SKP_GLOBAL
#endif
#endif

#define SKP_INV_2PI 0.15915494f

/* The Hermite cubic at u in [0, 1] (not clamped here): cos theta, held in
   [y0, y1] (its rounding can pass y1 by an ulp) and then in [-1, 1], and
   the cubic's slope in t at *dmu. */
SKP_FN float skp_table_hermite_(const SKP_GLOBAL float *data, skp_u32 n, float u, float *dmu) {
    SKP_BEGIN
    float x, t, y0, d0, y1, d1, dy, c2, c3, mu;
    skp_u32 i;
    if (n == 0u) {
        *dmu = skp_from_bits(0x7fc00000u);
        return *dmu;
    }
    x = SKP_MUL(u, (float)n);
    i = x >= 1.0f ? (skp_u32)x : 0u; /* x >= 1 excludes NaN */
    i = i > n - 1u ? n - 1u : i;
    t = x - (float)i;
    y0 = data[2u * i];
    d0 = data[2u * i + 1u];
    y1 = data[2u * i + 2u];
    d1 = data[2u * i + 3u];
    dy = y1 - y0;
    c2 = SKP_MUL(3.0f, dy) - SKP_MUL(2.0f, d0) - d1;
    c3 = d0 + d1 - SKP_MUL(2.0f, dy);
    mu = y0 + SKP_MUL(t, d0 + SKP_MUL(t, c2 + SKP_MUL(t, c3)));
    *dmu = d0 + SKP_MUL(t, SKP_MUL(2.0f, c2) + SKP_MUL(SKP_MUL(3.0f, t), c3));
    mu = mu > y1 ? y1 : mu;
    mu = mu < y0 ? y0 : mu;
    return mu > 1.0f ? 1.0f : (mu < -1.0f ? -1.0f : mu);
}

/* cos theta of a Hermite table (SK_TABLE_INVERSE or SK_TABLE_MEASURED, n
   intervals, 2(n + 1) values) at u (clamped; NaN gives NaN). */
SKP_FN float skp_table_sample_cos(const SKP_GLOBAL float *data, skp_u32 n, float u) {
    float dmu;
    return skp_table_hermite_(data, n, skp_clamp01(u), &dmu);
}

/* cos theta of a Hermite table at u, with *pdf the density per steradian
   there: 1/(2 pi n mu'(t)) of the interval's cubic (+inf where flat). */
SKP_FN float skp_table_sample_cos_pdf(const SKP_GLOBAL float *data, skp_u32 n, float u, float *pdf) {
    SKP_BEGIN
    float dmu;
    float mu = skp_table_hermite_(data, n, skp_clamp01(u), &dmu);
    *pdf = SKP_INV_2PI / ((float)n * dmu);
    return mu;
}

/* cos theta of Frisvad's Rayleigh CDF table (SK_TABLE_RAYLEIGH_CDF, n + 1
   values) at u (clamped; NaN gives NaN), with *pdf the interval's density,
   (F[i+1] - F[i]) / (2 pi 2/n). */
SKP_FN float skp_table_cdf_sample_cos_pdf(const SKP_GLOBAL float *data, skp_u32 n, float u, float *pdf) {
    SKP_BEGIN
    skp_u32 lo = 0u, hi = n, mid;
    float w, step, t, dx, mu;
    if (n == 0u) {
        *pdf = skp_from_bits(0x7fc00000u);
        return *pdf;
    }
    w = skp_clamp01(u);
    while (hi - lo > 1u) {
        mid = (lo + hi) / 2u;
        if (data[mid] <= w)
            lo = mid;
        else
            hi = mid;
    }
    step = data[hi] - data[lo];
    t = (w - data[lo]) / step;
    dx = 2.0f / (float)n;
    mu = SKP_MUL((float)lo + t, dx) - 1.0f;
    *pdf = SKP_INV_2PI * step / dx;
    return mu > 1.0f ? 1.0f : (mu < -1.0f ? -1.0f : mu);
}

/* A 2-D table (k Hermite slices of n intervals at x_j = x0 + j dx, one after
   the other): cos theta at (x, u), with *pdf the blend's density. NaN x or u
   gives NaN. */
SKP_FN float skp_table2d_sample_cos_pdf(const SKP_GLOBAL float *data, skp_u32 n, skp_u32 k, float x0,
                                        float dx, float x, float u, float *pdf) {
    SKP_BEGIN
    float top, s, w, a, da, mu, dmu, v;
    skp_u32 j, per;
    if (x != x || k == 0u) {
        *pdf = skp_from_bits(0x7fc00000u);
        return *pdf;
    }
    top = (float)(k - 1u);
    s = (x - x0) / dx;
    s = s > top ? top : s;
    s = s < 0.0f ? 0.0f : s;
    j = s >= 1.0f ? (skp_u32)s : 0u;
    w = s - (float)j;
    per = 2u * (n + 1u);
    v = skp_clamp01(u);
    a = skp_table_hermite_(data + j * per, n, v, &da);
    if (w > 0.0f) {
        float db, b = skp_table_hermite_(data + (j + 1u) * per, n, v, &db);
        mu = a + SKP_MUL(w, b - a);
        dmu = da + SKP_MUL(w, db - da);
    } else {
        mu = a;
        dmu = da;
    }
    *pdf = SKP_INV_2PI / ((float)n * dmu);
    return mu;
}

/* ---- tracking through a majorant grid ------------------------------------ */
/* A walk along one ray through a grid of nx ny nz majorants (x fastest,
   i + nx (j + ny k); each bounds sigma_t per length unit over its cell; the
   cells divide the box [lo, hi] evenly: the layout of sk_majorants). One
   skp_walk_step draws one tentative collision with one uniform, spending the
   optical depth -ln(1 - u) cell by cell; delta, ratio and residual tracking
   are loops around it. Plain data: fill with skp_walk_begin. */
typedef struct skp_walk {
    float o[3];    /* the origin in cell units */
    float d[3];    /* the direction in cell units per ray parameter */
    float next[3]; /* the ray parameter at the next face per axis */
    float t;       /* the ray parameter reached */
    float t_end;   /* where the walk ends */
    skp_u32 cell[3];
    skp_u32 dims[3];
} skp_walk;

SKP_FN float skp_walk_face_(const skp_walk *w, int a) {
    if (w->d[a] == 0.0f) {
        return skp_from_bits(0x7f800000u);
    }
    return ((float)(w->cell[a] + (w->d[a] > 0.0f ? 1u : 0u)) - w->o[a]) / w->d[a];
}

/* Starts a walk along origin + t dir, t in [t_min, t_max], through the grid
   of nx ny nz cells over [lo, hi] (the ray parameter is a length where dir
   is a unit vector). 1: the walk is ready; 0: the segment misses the box
   (or touches it in one point); -1: bad input (origin or dir not finite,
   dir = 0, not lo < hi, a dimension 0 or >= 2^24, nx ny nz >= 2^32,
   t_min < 0 or not finite, t_max < t_min), or a ray or box beyond float
   range in cell units: hi - lo, (origin - lo) n/(hi - lo) or dir n/(hi - lo)
   on some axis overflows (a box from -FLT_MAX to FLT_MAX, an origin near
   FLT_MAX from a small box, a direction of length near FLT_MAX). */
SKP_FN int skp_walk_begin(skp_walk *w, skp_vec3 origin, skp_vec3 dir, skp_vec3 lo, skp_vec3 hi,
                          skp_u32 nx, skp_u32 ny, skp_u32 nz, float t_min, float t_max) {
    SKP_BEGIN
    float org[3], dv[3], lov[3], hiv[3];
    float span, scale, o, d, t0, t1, p, inf = skp_from_bits(0x7f800000u);
    skp_u32 c;
    int a, miss = 0;
    if (!(t_min >= 0.0f && t_min < inf && t_max >= t_min)) {
        return -1;
    }
    if ((dir.x == 0.0f && dir.y == 0.0f && dir.z == 0.0f) || nx == 0u || ny == 0u || nz == 0u ||
        ny > 0xffffffffu / nx || nz > 0xffffffffu / (nx * ny)) {
        return -1;
    }
    org[0] = origin.x; org[1] = origin.y; org[2] = origin.z;
    dv[0] = dir.x; dv[1] = dir.y; dv[2] = dir.z;
    lov[0] = lo.x; lov[1] = lo.y; lov[2] = lo.z;
    hiv[0] = hi.x; hiv[1] = hi.y; hiv[2] = hi.z;
    w->dims[0] = nx; w->dims[1] = ny; w->dims[2] = nz;
    w->t = t_min;
    w->t_end = t_max;
    for (a = 0; a < 3; ++a) {
        skp_u32 n = w->dims[a];
        span = hiv[a] - lov[a];
        if (!(n < 16777216u && span > 0.0f && span < inf)) {
            return -1;
        }
        scale = (float)n / span;
        o = SKP_MUL(org[a] - lov[a], scale);
        d = SKP_MUL(dv[a], scale);
        if (!(o > -inf && o < inf && d > -inf && d < inf)) {
            return -1;
        }
        w->o[a] = o;
        w->d[a] = d;
        w->next[a] = inf;
        w->cell[a] = 0u;
        if (d == 0.0f) {
            /* a miss, reported once every axis is checked (a ray beyond
               float range on a later axis is refused whichever it misses on) */
            miss |= o < 0.0f || o > (float)n;
            continue;
        }
        t0 = (0.0f - o) / d;
        t1 = ((float)n - o) / d;
        if (t0 < t1) {
            if (t0 > w->t) w->t = t0;
            if (t1 < w->t_end) w->t_end = t1;
        } else {
            if (t1 > w->t) w->t = t1;
            if (t0 < w->t_end) w->t_end = t0;
        }
    }
    if (miss || !(w->t < w->t_end)) {
        return 0;
    }
    for (a = 0; a < 3; ++a) {
        p = w->o[a] + SKP_MUL(w->d[a], w->t);
        c = p > 0.0f ? (skp_u32)p : 0u;
        w->cell[a] = c < w->dims[a] - 1u ? c : w->dims[a] - 1u;
        w->next[a] = skp_walk_face_(w, a);
    }
    return 1;
}

/* The flat index of the walk's cell. */
SKP_FN skp_u32 skp_walk_cell(const skp_walk *w) {
    return w->cell[0] + w->dims[0] * (w->cell[1] + w->dims[1] * w->cell[2]);
}

/* The next tentative collision, with one uniform u (clamped; NaN and u = 1
   walk to the end). 1: a collision at *t in a cell of majorant *sigma_maj
   (index skp_walk_cell(w)); the walk waits there for the next step.
   0: the walk reached t_end (*t = t_end, *sigma_maj = 0); every later step
   returns 0. -1: a majorant on the way is negative, NaN or infinite.
   majorants: nx ny nz values. Reads at most nx + ny + nz of them. */
SKP_FN int skp_walk_step(skp_walk *w, const SKP_GLOBAL float *majorants, float u, float *t,
                         float *sigma_maj) {
    SKP_BEGIN
    float tau = skp_free_path(1.0f, u), t_face, sigma, depth, tc;
    skp_u32 k = 0u, crossings = w->dims[0] + w->dims[1] + w->dims[2], c;
    int a;
    if (tau != tau) {
        tau = skp_from_bits(0x7f800000u);
    }
    while (w->t < w->t_end && k < crossings) {
        ++k;
        a = 0;
        if (w->next[1] < w->next[a]) a = 1;
        if (w->next[2] < w->next[a]) a = 2;
        t_face = w->next[a] < w->t_end ? w->next[a] : w->t_end;
        if (t_face < w->t) t_face = w->t;
        sigma = majorants[skp_walk_cell(w)];
        if (!(sigma >= 0.0f && sigma < skp_from_bits(0x7f800000u))) {
            return -1;
        }
        depth = SKP_MUL(sigma, t_face - w->t);
        if (tau < depth) {
            tc = w->t + tau / sigma;
            w->t = tc < t_face ? tc : t_face;
            *t = w->t;
            *sigma_maj = sigma;
            return 1;
        }
        tau = tau - depth;
        if (!(t_face < w->t_end)) {
            break;
        }
        c = w->cell[a];
        if (w->d[a] > 0.0f) {
            if (c + 1u >= w->dims[a]) break;
            w->cell[a] = c + 1u;
        } else {
            if (c == 0u) break;
            w->cell[a] = c - 1u;
        }
        w->next[a] = skp_walk_face_(w, a);
        w->t = t_face;
    }
    w->t = w->t_end;
    *t = w->t_end;
    *sigma_maj = 0.0f;
    return 0;
}

#endif /* SCATTERKIT_PORTABLE_H */
