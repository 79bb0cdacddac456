/* Tables built by the library on the host, looked up by the portable
 * header (include/scatterkit_portable.h): on the CPU, and in an OpenCL
 * kernel with the table data copied into a device buffer. cos theta must be
 * the library's (sk_table_sample_cos, sk_table2d_sample_cos) bit for bit,
 * and the kernel's cos theta and density the CPU header's, over 2^24 + 1
 * values of u per 1-D table and 4097 x 4097 values of (x, u) per 2-D table.
 * One line per table and place: "<table> <cpu|opencl>: N compared, M
 * mismatched"; "SKIPPED: <why>" where no OpenCL platform or device answers.
 * For the Rust module's side (tests/c_abi/portable.rs), a line "hash <table>
 * <hex>" per table (FNV-1a over the CPU header's cos theta and density
 * bits) and the tables' data written to the file named by the second
 * argument: n, k (1 for 1-D), length, then the values, per table.
 * Arguments: the include directory (for the kernel's #include), the file. */
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scatterkit.h"
#include "scatterkit_portable.h"

#define NU ((1u << 24) + 1u)
#define G2 4097u

enum { HG, FOG, MEASURED, CDF, TWO_D, TABLES };
static const char *NAMES[TABLES] = {"inverse HG 0.7 (n 64)", "inverse fog 2 um (n 256)",
                                    "measured (n 7)", "Rayleigh CDF (n 64)",
                                    "2-D inverse, 4 slices (n 64)"};

static float data[TABLES][4 * 2 * 257];
static skp_u32 ns[TABLES], len[TABLES];
static sk_table tab[4];
static sk_table2d tab2;

static float u_of(skp_u32 i, int kind) {
    return kind == TWO_D ? (float)(i % G2) / (float)(G2 - 1u) : (float)i * 5.9604645e-08f;
}
static float x_of(skp_u32 i) { return 0.35f + 0.4f * (float)(i / G2) / 4096.0f; }
static skp_u32 count(int kind) { return kind == TWO_D ? G2 * G2 : NU; }

/* The header on this CPU: cos theta and density of table `kind` at i. */
static float cpu(int kind, skp_u32 i, float *pdf) {
    float u = u_of(i, kind);
    switch (kind) {
    case CDF: return skp_table_cdf_sample_cos_pdf(data[kind], ns[kind], u, pdf);
    case TWO_D: return skp_table2d_sample_cos_pdf(data[kind], ns[kind], 4u, 0.4f, 0.1f, x_of(i), u, pdf);
    default: return skp_table_sample_cos_pdf(data[kind], ns[kind], u, pdf);
    }
}

static float library(int kind, skp_u32 i) {
    return kind == TWO_D ? sk_table2d_sample_cos(&tab2, x_of(i), u_of(i, kind))
                         : sk_table_sample_cos(&tab[kind], u_of(i, kind));
}

static int same(float a, float b) { return memcmp(&a, &b, sizeof a) == 0 || (a != a && b != b); }

static const char *KERNEL =
    "#include \"scatterkit_portable.h\"\n"
    "__kernel void run(int kind, __global const float *data, uint n, __global float *out) {\n"
    "    uint i = (uint)get_global_id(0);\n"
    "    float pdf, mu;\n"
    "    if (kind == 3) {\n"
    "        mu = skp_table_cdf_sample_cos_pdf(data, n, (float)i * 5.9604645e-08f, &pdf);\n"
    "    } else if (kind == 4) {\n"
    "        float u = (float)(i % 4097u) / 4096.0f, x = 0.35f + 0.4f * (float)(i / 4097u) / 4096.0f;\n"
    "        mu = skp_table2d_sample_cos_pdf(data, n, 4u, 0.4f, 0.1f, x, u, &pdf);\n"
    "    } else {\n"
    "        mu = skp_table_sample_cos_pdf(data, n, (float)i * 5.9604645e-08f, &pdf);\n"
    "    }\n"
    "    out[2 * i] = mu;\n"
    "    out[2 * i + 1] = pdf;\n"
    "}\n";

static int opencl(const char *include) {
    cl_platform_id platform;
    cl_device_id device;
    cl_uint got = 0;
    cl_int err;
    cl_context ctx;
    cl_command_queue q;
    cl_program prog;
    cl_kernel kern;
    char options[4096];
    float *out;
    int kind, bad_total = 0;
    if (clGetPlatformIDs(1, &platform, &got) != CL_SUCCESS || got == 0) {
        printf("SKIPPED: no OpenCL platform\n");
        return 0;
    }
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 1, &device, &got) != CL_SUCCESS || got == 0) {
        printf("SKIPPED: no OpenCL device\n");
        return 0;
    }
    ctx = clCreateContext(NULL, 1, &device, NULL, NULL, &err);
    q = clCreateCommandQueue(ctx, device, 0, &err);
    prog = clCreateProgramWithSource(ctx, 1, &KERNEL, NULL, &err);
    snprintf(options, sizeof options, "-I %s -cl-fp32-correctly-rounded-divide-sqrt -Werror", include);
    if (clBuildProgram(prog, 1, &device, options, NULL, NULL) != CL_SUCCESS) {
        static char log[1 << 16];
        clGetProgramBuildInfo(prog, device, CL_PROGRAM_BUILD_LOG, sizeof log, log, NULL);
        printf("FAILED: clBuildProgram\n%s\n", log);
        return 1;
    }
    kern = clCreateKernel(prog, "run", &err);
    out = (float *)malloc(2 * sizeof(float) * (size_t)G2 * G2);
    for (kind = 0; kind < TABLES; kind++) {
        size_t global = count(kind);
        skp_u32 i, bad = 0;
        cl_mem in = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                   sizeof(float) * len[kind], data[kind], &err);
        cl_mem o = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, 2 * sizeof(float) * global, NULL, &err);
        if (err != CL_SUCCESS) return 1;
        clSetKernelArg(kern, 0, sizeof(int), &kind);
        clSetKernelArg(kern, 1, sizeof(cl_mem), &in);
        clSetKernelArg(kern, 2, sizeof(cl_uint), &ns[kind]);
        clSetKernelArg(kern, 3, sizeof(cl_mem), &o);
        if (clEnqueueNDRangeKernel(q, kern, 1, NULL, &global, NULL, 0, NULL, NULL) != CL_SUCCESS ||
            clEnqueueReadBuffer(q, o, CL_TRUE, 0, 2 * sizeof(float) * global, out, 0, NULL, NULL) != CL_SUCCESS)
            return 1;
        for (i = 0; i < (skp_u32)global; i++) {
            float pdf, mu = cpu(kind, i, &pdf);
            if (!same(mu, out[2 * i]) || !same(pdf, out[2 * i + 1]) || !same(mu, library(kind, i))) {
                if (bad++ < 3) printf("  %s at %u: %.9g %.9g vs %.9g %.9g\n", NAMES[kind], i, mu, pdf, out[2 * i], out[2 * i + 1]);
            }
        }
        printf("%s opencl: %u compared, %u mismatched\n", NAMES[kind], (unsigned)global, bad);
        bad_total += bad != 0;
        clReleaseMemObject(in);
        clReleaseMemObject(o);
    }
    free(out);
    clReleaseKernel(kern);
    clReleaseProgram(prog);
    clReleaseCommandQueue(q);
    clReleaseContext(ctx);
    return bad_total;
}

int main(int argc, char **argv) {
    sk_phase hg, fog, slices[4];
    float cx[5] = {-1.0f, -0.3f, 0.2f, 0.8f, 1.0f}, cp[5] = {0.1f, 0.3f, 0.0f, 1.5f, 4.0f};
    int kind, bad_total = 0, k;
    if (argc < 3) return 2;
    ns[HG] = 64; ns[FOG] = 256; ns[MEASURED] = 7; ns[CDF] = 64; ns[TWO_D] = 64;
    for (kind = 0; kind < TABLES; kind++) len[kind] = kind == CDF ? ns[kind] + 1u : 2u * (ns[kind] + 1u);
    len[TWO_D] *= 4u;
    if (sk_phase_new_hg(0.7f, &hg) || sk_phase_new_fog_diameter(2.0f, &fog) ||
        sk_table_new_inverse(&hg, data[HG], len[HG], ns[HG], &tab[HG]) ||
        sk_table_new_inverse(&fog, data[FOG], len[FOG], ns[FOG], &tab[FOG]) ||
        sk_table_new_measured(cx, cp, 5, data[MEASURED], len[MEASURED], ns[MEASURED], &tab[MEASURED]) ||
        sk_table_new_rayleigh_cdf(data[CDF], len[CDF], ns[CDF], &tab[CDF]))
        return 3;
    for (k = 0; k < 4; k++)
        if (sk_phase_new_hg(-0.5f + 0.45f * (float)k, &slices[k])) return 3;
    if (sk_table2d_new_inverse(slices, 4, data[TWO_D], len[TWO_D], ns[TWO_D], 0.4f, 0.1f, &tab2)) return 3;
    for (kind = 0; kind < TABLES; kind++) {
        skp_u32 i, bad = 0, n = count(kind), h = 2166136261u, k2 = kind == TWO_D ? 4u : 1u;
        FILE *f = fopen(argv[2], kind == 0 ? "wb" : "ab");
        if (!f) return 4;
        fwrite(&ns[kind], 4, 1, f);
        fwrite(&k2, 4, 1, f);
        fwrite(&len[kind], 4, 1, f);
        fwrite(data[kind], 4, len[kind], f);
        fclose(f);
        for (i = 0; i < n; i++) {
            float pdf, mu = cpu(kind, i, &pdf);
            h = (h ^ skp_bits(mu)) * 16777619u;
            h = (h ^ skp_bits(pdf)) * 16777619u;
            if (!same(mu, library(kind, i)) && bad++ < 3)
                printf("  %s at %u: %.9g vs %.9g\n", NAMES[kind], i, mu, library(kind, i));
        }
        printf("%s cpu: %u compared, %u mismatched\n", NAMES[kind], n, bad);
        printf("hash %d %08x\n", kind, (unsigned)h);
        bad_total += bad != 0;
    }
    return bad_total + opencl(argv[1]);
}
