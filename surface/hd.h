// SEROSA_HD: marks functions that Thrust may call on the device. CUDA 13's CCCL no longer defines
// __host__/__device__ for host compilers, so g++ sees an empty macro and nvcc sees
// __host__ __device__.
#pragma once

#if defined(__CUDACC__)
#define SEROSA_HD __host__ __device__
#else
#define SEROSA_HD
#endif
