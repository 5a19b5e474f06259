// Warps per SM on a Turing SM (compute capability 7.5, Quadro RTX 8000) for a
// kernel's registers per thread and stack bytes, by NVIDIA's own occupancy
// rules (cuda_occupancy.h, shipped with the CUDA toolkit: header only, no GPU
// needed). Reads "name registers" lines on stdin; prints, per block size of
// 1, 2, 4 and 8 warps, the warps resident per SM and which limit binds.
#include <cuda_occupancy.h>

#include <cstdio>
#include <iostream>
#include <string>

int main() {
    cudaOccDeviceProp prop{};
    prop.computeMajor = 7;
    prop.computeMinor = 5;
    prop.maxThreadsPerBlock = 1024;
    prop.maxThreadsPerMultiprocessor = 1024;  // 32 warps
    prop.regsPerBlock = 65536;
    prop.regsPerMultiprocessor = 65536;
    prop.warpSize = 32;
    prop.sharedMemPerBlock = 48 * 1024;
    prop.sharedMemPerMultiprocessor = 64 * 1024;
    prop.numSms = 72;  // Quadro RTX 8000 (TU102)
    prop.sharedMemPerBlockOptin = 64 * 1024;
    prop.reservedSharedMemPerBlock = 0;
    std::string name;
    int regs = 0;
    while (std::cin >> name >> regs) {
        std::printf("%s %d", name.c_str(), regs);
        for (const int warps : {1, 2, 4, 8}) {
            cudaOccFuncAttributes attr{};
            attr.maxThreadsPerBlock = 1024;
            attr.numRegs = regs;
            attr.sharedSizeBytes = 0;
            attr.partitionedGCConfig = PARTITIONED_GC_OFF;
            attr.shmemLimitConfig = FUNC_SHMEM_LIMIT_DEFAULT;
            attr.maxDynamicSharedSizeBytes = 0;
            attr.numBlockBarriers = 0;
            cudaOccDeviceState state{};
            cudaOccResult res{};
            const cudaOccError e = cudaOccMaxActiveBlocksPerMultiprocessor(&res, &prop, &attr, &state, warps * 32, 0);
            if (e != CUDA_OCC_SUCCESS) {
                std::printf(" err");
                continue;
            }
            const char* lim = (res.limitingFactors & OCC_LIMIT_REGISTERS) ? "regs"
                              : (res.limitingFactors & OCC_LIMIT_BLOCKS) ? "blocks"
                              : (res.limitingFactors & OCC_LIMIT_WARPS) ? "warps" : "-";
            std::printf(" %d:%s", res.activeBlocksPerMultiprocessor * warps, lim);
        }
        std::printf("\n");
    }
}
