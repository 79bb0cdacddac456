/* The portable tier as OpenCL C: portable_cases.h compiled into a kernel by
 * the platform's OpenCL compiler (pocl on the CPU in CI), run over every
 * index, the results read back and hashed as tests/c/portable.c hashes its
 * own. Arguments: the include directory of the header, that of
 * portable_cases.h. Prints "SKIPPED: <why>" and exits 0 when no OpenCL
 * platform or device answers. */
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "portable_cases.h"

static const char *KERNEL =
    "#include \"portable_cases.h\"\n"
    "__kernel void run(int c, uint k0, __global float *out, __global const float *maj) {\n"
    "    uint i = (uint)get_global_id(0);\n"
    "    float o[4];\n"
    "    pc_case(c, k0 + i, maj, o);\n"
    "    out[4 * i] = o[0]; out[4 * i + 1] = o[1];\n"
    "    out[4 * i + 2] = o[2]; out[4 * i + 3] = o[3];\n"
    "}\n";

#define CHUNK (1u << 22)

static int fail(const char *what, cl_int err) {
    printf("FAILED: %s (%d)\n", what, (int)err);
    return 1;
}

int main(int argc, char **argv) {
    cl_platform_id platform;
    cl_device_id device;
    cl_uint n = 0;
    cl_int err;
    cl_context ctx;
    cl_command_queue q;
    cl_program prog;
    cl_kernel kern;
    cl_mem buf, majb;
    float maj[PC_MAJ_N];
    char options[4096];
    float *out;
    int c;
    if (argc < 3) {
        printf("usage: %s <include dir> <tests/c dir>\n", argv[0]);
        return 2;
    }
    if (clGetPlatformIDs(1, &platform, &n) != CL_SUCCESS || n == 0) {
        printf("SKIPPED: no OpenCL platform\n");
        return 0;
    }
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 1, &device, &n) != CL_SUCCESS || n == 0) {
        printf("SKIPPED: no OpenCL device\n");
        return 0;
    }
    {
        char name[256];
        clGetDeviceInfo(device, CL_DEVICE_NAME, sizeof name, name, NULL);
        printf("device: %s\n", name);
    }
    ctx = clCreateContext(NULL, 1, &device, NULL, NULL, &err);
    if (err != CL_SUCCESS) return fail("clCreateContext", err);
    q = clCreateCommandQueue(ctx, device, 0, &err);
    if (err != CL_SUCCESS) return fail("clCreateCommandQueue", err);
    prog = clCreateProgramWithSource(ctx, 1, &KERNEL, NULL, &err);
    if (err != CL_SUCCESS) return fail("clCreateProgramWithSource", err);
    snprintf(options, sizeof options,
             "-I %s -I %s -cl-fp32-correctly-rounded-divide-sqrt -Werror", argv[1], argv[2]);
    err = clBuildProgram(prog, 1, &device, options, NULL, NULL);
    if (err != CL_SUCCESS) {
        static char log[1 << 16];
        clGetProgramBuildInfo(prog, device, CL_PROGRAM_BUILD_LOG, sizeof log, log, NULL);
        printf("%s\n", log);
        return fail("clBuildProgram", err);
    }
    kern = clCreateKernel(prog, "run", &err);
    if (err != CL_SUCCESS) return fail("clCreateKernel", err);
    buf = clCreateBuffer(ctx, CL_MEM_WRITE_ONLY, 4 * sizeof(float) * CHUNK, NULL, &err);
    if (err != CL_SUCCESS) return fail("clCreateBuffer", err);
    for (c = 0; c < (int)PC_MAJ_N; c++) {
        maj[c] = pc_maj((skp_u32)c);
    }
    /* The majorant grid as a renderer would hold it: a device buffer. */
    majb = clCreateBuffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof maj, maj, &err);
    if (err != CL_SUCCESS) return fail("clCreateBuffer", err);
    out = (float *)malloc(4 * sizeof(float) * CHUNK);
    for (c = 0; c < PC_CASES; c++) {
        skp_u32 k0;
        for (k0 = 0; k0 < PC_N; k0 += CHUNK) {
            size_t global = CHUNK;
            skp_u32 b;
            clSetKernelArg(kern, 0, sizeof(int), &c);
            clSetKernelArg(kern, 1, sizeof(cl_uint), &k0);
            clSetKernelArg(kern, 2, sizeof(cl_mem), &buf);
            clSetKernelArg(kern, 3, sizeof(cl_mem), &majb);
            err = clEnqueueNDRangeKernel(q, kern, 1, NULL, &global, NULL, 0, NULL, NULL);
            if (err != CL_SUCCESS) return fail("clEnqueueNDRangeKernel", err);
            err = clEnqueueReadBuffer(q, buf, CL_TRUE, 0, 4 * sizeof(float) * CHUNK, out, 0, NULL, NULL);
            if (err != CL_SUCCESS) return fail("clEnqueueReadBuffer", err);
            for (b = 0; b < CHUNK >> 16; b++) {
                skp_u32 h = 2166136261u, j;
                for (j = b << 16; j < (b + 1u) << 16; j++) {
                    int i;
                    for (i = 0; i < 4; i++) {
                        skp_u32 w = skp_bits(out[4 * j + i]);
                        w = (w & 0x7fffffffu) > 0x7f800000u ? 0x7fc00000u : w;
                        h = (h ^ w) * 16777619u;
                    }
                }
                printf("%d %u %08x\n", c, (unsigned)((k0 >> 16) + b), (unsigned)h);
            }
        }
    }
    free(out);
    clReleaseMemObject(buf);
    clReleaseMemObject(majb);
    clReleaseKernel(kern);
    clReleaseProgram(prog);
    clReleaseCommandQueue(q);
    clReleaseContext(ctx);
    return 0;
}
