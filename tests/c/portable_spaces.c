/* Model constants in every memory space, and programs of several units:
 * - the table of tests/c/portable_media.h built on the host with skp_*_new,
 *   hashed on the host, then uploaded as it is and read by OpenCL kernels
 *   from a __constant and from a __global buffer, in OpenCL C 1.2, 2.0 and
 *   3.0 (the versions the device takes), over PM_N indices each;
 * - two OpenCL programs that both include the header, compiled apart with
 *   clCompileProgram and joined with clLinkProgram, each kernel run.
 * Prints "host <hash>", "<space> <version> <hash>" per build and
 * "link: ok"; tests/c_abi/portable.rs compares every hash with the Rust
 * module's. Arguments: the include directory of the header, that of the
 * test headers. "SKIPPED: <why>" (exit 0) without an OpenCL device. */
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "portable_media.h"

static const char *KERNELS =
    "#include \"portable_media.h\"\n"
    "__kernel void from_constant(__constant const pm_medium *media, __global uint *out) {\n"
    "    SKP_BEGIN\n"
    "    uint k = (uint)get_global_id(0), h;\n"
    "    PM_HASH(media, k, h);\n"
    "    out[k] = h;\n"
    "}\n"
    "__kernel void from_global(__global const pm_medium *media, __global uint *out) {\n"
    "    SKP_BEGIN\n"
    "    uint k = (uint)get_global_id(0), h;\n"
    "    PM_HASH(media, k, h);\n"
    "    out[k] = h;\n"
    "}\n";

/* Two programs for the link: each includes the header (its static table
   and functions), the second calls a function the first defines. */
static const char *UNIT_A =
    "#include \"scatterkit_portable.h\"\n"
    "float unit_a_cos(float u) { return skp_rayleigh_sample_cos(u); }\n"
    "__kernel void unit_a(__global float *out) { out[0] = skp_rayleigh_sample_cos(0.3f); }\n";
static const char *UNIT_B =
    "#include \"scatterkit_portable.h\"\n"
    "float unit_a_cos(float u);\n"
    "__kernel void unit_b(__global float *out) {\n"
    "    skp_hg h;\n"
    "    skp_hg_new(0.5f, &h);\n"
    "    out[1] = unit_a_cos(0.3f) + skp_hg_sample_cos(h, 0.3f) + skp_rayleigh_sample_cos(0.7f);\n"
    "}\n";

static int fail(const char *what, cl_int err) {
    printf("FAILED: %s (%d)\n", what, (int)err);
    return 1;
}

/* FNV-1a over the per-index hashes, in index order. */
static skp_u32 combine(const skp_u32 *h, skp_u32 n) {
    skp_u32 acc = 2166136261u, i;
    for (i = 0; i < n; i++) acc = (acc ^ h[i]) * 16777619u;
    return acc;
}

static void print_log(cl_program prog, cl_device_id device) {
    static char log[1 << 16];
    clGetProgramBuildInfo(prog, device, CL_PROGRAM_BUILD_LOG, sizeof log, log, NULL);
    printf("%s\n", log);
}

int main(int argc, char **argv) {
    static const char *VERSIONS[3] = {"CL1.2", "CL2.0", "CL3.0"};
    cl_platform_id platform;
    cl_device_id device;
    cl_uint n = 0;
    cl_int err;
    cl_context ctx;
    cl_command_queue q;
    cl_mem media_buf, out_buf;
    pm_medium media[PM_MEDIA];
    skp_u32 *hashes, k, m;
    char options[4096], cver[256];
    int v, built = 0;
    if (argc < 3) {
        printf("usage: %s <include dir> <tests/c dir>\n", argv[0]);
        return 2;
    }
    for (m = 0; m < PM_MEDIA; m++) {
        if (!pm_medium_new(m, &media[m])) return fail("pm_medium_new", (cl_int)m);
    }
    hashes = (skp_u32 *)malloc(sizeof(skp_u32) * PM_N);
    for (k = 0; k < PM_N; k++) {
        skp_u32 h;
        PM_HASH(media, k, h);
        hashes[k] = h;
    }
    printf("host %08x\n", (unsigned)combine(hashes, PM_N));
    if (clGetPlatformIDs(1, &platform, &n) != CL_SUCCESS || n == 0) {
        printf("SKIPPED: no OpenCL platform\n");
        return 0;
    }
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 1, &device, &n) != CL_SUCCESS || n == 0) {
        printf("SKIPPED: no OpenCL device\n");
        return 0;
    }
    clGetDeviceInfo(device, CL_DEVICE_OPENCL_C_VERSION, sizeof cver, cver, NULL);
    printf("device OpenCL C: %s\n", cver);
    ctx = clCreateContext(NULL, 1, &device, NULL, NULL, &err);
    if (err != CL_SUCCESS) return fail("clCreateContext", err);
    q = clCreateCommandQueue(ctx, device, 0, &err);
    if (err != CL_SUCCESS) return fail("clCreateCommandQueue", err);
    /* The table as it is on the host: the structs hold floats alone. */
    media_buf = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof media, media, &err);
    if (err != CL_SUCCESS) return fail("clCreateBuffer", err);
    out_buf = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, sizeof(skp_u32) * PM_N, NULL, &err);
    if (err != CL_SUCCESS) return fail("clCreateBuffer", err);
    for (v = 0; v < 3; v++) {
        int s;
        cl_program prog = clCreateProgramWithSource(ctx, 1, &KERNELS, NULL, &err);
        if (err != CL_SUCCESS) return fail("clCreateProgramWithSource", err);
        snprintf(options, sizeof options,
                 "-cl-std=%s -I %s -I %s -cl-fp32-correctly-rounded-divide-sqrt -Werror", VERSIONS[v],
                 argv[1], argv[2]);
        err = clBuildProgram(prog, 1, &device, options, NULL, NULL);
        if (err != CL_SUCCESS) {
            print_log(prog, device);
            printf("%s: not built by this device (%d)\n", VERSIONS[v], (int)err);
            clReleaseProgram(prog);
            continue;
        }
        built++;
        for (s = 0; s < 2; s++) {
            const char *name = s == 0 ? "from_constant" : "from_global";
            size_t global = PM_N;
            cl_kernel kern = clCreateKernel(prog, name, &err);
            if (err != CL_SUCCESS) return fail("clCreateKernel", err);
            clSetKernelArg(kern, 0, sizeof(cl_mem), &media_buf);
            clSetKernelArg(kern, 1, sizeof(cl_mem), &out_buf);
            err = clEnqueueNDRangeKernel(q, kern, 1, NULL, &global, NULL, 0, NULL, NULL);
            if (err != CL_SUCCESS) return fail("clEnqueueNDRangeKernel", err);
            err = clEnqueueReadBuffer(q, out_buf, CL_TRUE, 0, sizeof(skp_u32) * PM_N, hashes, 0, NULL, NULL);
            if (err != CL_SUCCESS) return fail("clEnqueueReadBuffer", err);
            printf("%s %s %08x\n", s == 0 ? "__constant" : "__global", VERSIONS[v],
                   (unsigned)combine(hashes, PM_N));
            clReleaseKernel(kern);
        }
        clReleaseProgram(prog);
    }
    printf("built: %d of 3 versions\n", built);
    /* Two units, compiled apart, linked. */
    {
        const char *srcs[2];
        cl_program units[2], linked;
        cl_kernel ka, kb;
        float got[2];
        size_t one = 1;
        int i;
        srcs[0] = UNIT_A;
        srcs[1] = UNIT_B;
        snprintf(options, sizeof options, "-cl-std=CL1.2 -I %s -cl-fp32-correctly-rounded-divide-sqrt",
                 argv[1]);
        for (i = 0; i < 2; i++) {
            units[i] = clCreateProgramWithSource(ctx, 1, &srcs[i], NULL, &err);
            if (err != CL_SUCCESS) return fail("clCreateProgramWithSource", err);
            err = clCompileProgram(units[i], 1, &device, options, 0, NULL, NULL, NULL, NULL);
            if (err != CL_SUCCESS) {
                print_log(units[i], device);
                return fail("clCompileProgram", err);
            }
        }
        linked = clLinkProgram(ctx, 1, &device, "", 2, units, NULL, NULL, &err);
        if (err != CL_SUCCESS) {
            print_log(linked, device);
            return fail("clLinkProgram", err);
        }
        ka = clCreateKernel(linked, "unit_a", &err);
        if (err != CL_SUCCESS) return fail("clCreateKernel unit_a", err);
        kb = clCreateKernel(linked, "unit_b", &err);
        if (err != CL_SUCCESS) return fail("clCreateKernel unit_b", err);
        clSetKernelArg(ka, 0, sizeof(cl_mem), &out_buf);
        clSetKernelArg(kb, 0, sizeof(cl_mem), &out_buf);
        if (clEnqueueNDRangeKernel(q, ka, 1, NULL, &one, NULL, 0, NULL, NULL) != CL_SUCCESS ||
            clEnqueueNDRangeKernel(q, kb, 1, NULL, &one, NULL, 0, NULL, NULL) != CL_SUCCESS ||
            clEnqueueReadBuffer(q, out_buf, CL_TRUE, 0, sizeof got, got, 0, NULL, NULL) != CL_SUCCESS) {
            return fail("running the linked kernels", 0);
        }
        {
            skp_hg h;
            float want;
            skp_hg_new(0.5f, &h);
            want = skp_rayleigh_sample_cos(0.3f) + skp_hg_sample_cos(h, 0.3f) + skp_rayleigh_sample_cos(0.7f);
            if (memcmp(&got[0], &(float){skp_rayleigh_sample_cos(0.3f)}, 4) || memcmp(&got[1], &want, 4)) {
                printf("FAILED: the linked kernels gave %.9g %.9g\n", got[0], got[1]);
                return 1;
            }
        }
        printf("link: ok (two programs, each with the header, compiled apart and linked)\n");
        clReleaseKernel(ka);
        clReleaseKernel(kb);
        clReleaseProgram(linked);
        clReleaseProgram(units[0]);
        clReleaseProgram(units[1]);
    }
    free(hashes);
    clReleaseMemObject(media_buf);
    clReleaseMemObject(out_buf);
    clReleaseCommandQueue(q);
    clReleaseContext(ctx);
    return 0;
}
