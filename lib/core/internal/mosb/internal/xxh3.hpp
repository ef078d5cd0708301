// XXH3 for the library: on x86-64 the system libxxhash's runtime-dispatch entry points pick the
// widest vector unit the CPU has (AVX2/AVX-512), about twice the speed of the portable default.
#pragma once

#if defined(__x86_64__) && __has_include(<xxh_x86dispatch.h>)
#include <xxh_x86dispatch.h>
#endif
#include <xxhash.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>

namespace mosb {

// XXH3-64 of bytes given piece by piece (a section's checksum, §8, over a file read in chunks).
class Xxh3Stream {
 public:
  Xxh3Stream() : state_(XXH3_createState(), &XXH3_freeState) {
    if (!state_) throw std::bad_alloc();
    XXH3_64bits_reset(state_.get());
  }
  void update(const void* data, std::size_t size) { XXH3_64bits_update(state_.get(), data, size); }
  std::uint64_t digest() const { return XXH3_64bits_digest(state_.get()); }

 private:
  std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state_;
};

}  // namespace mosb
