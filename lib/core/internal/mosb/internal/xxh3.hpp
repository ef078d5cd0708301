// XXH3 for the library: on x86-64 the system libxxhash's runtime-dispatch entry points pick the
// widest vector unit the CPU has (AVX2/AVX-512), about twice the speed of the portable default.
#pragma once

#if defined(__x86_64__) && __has_include(<xxh_x86dispatch.h>)
#include <xxh_x86dispatch.h>
#endif
#include <xxhash.h>
