/* libFuzzer target for fogrt_load_ply_memory: any input must load or fail with a file:line
   message, without crashing, leaking or leaving the scene unusable; a successful load is
   also built unless -DFUZZ_NO_BUILD (see fuzz_common.h).
   Build and run: make fuzz-ply (see mk/cli.mk). */
#include "fuzz_common.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    return fuzz_load_one(data, size, fogrt_load_ply_memory, "fuzz.ply");
}
