// Arrays of megabytes (the CSR a builder sorts, an unpacked image) in anonymous memory asked for in
// transparent huge pages. On the VMs mosb is benchmarked on a page fault costs about 12 us, more
// than filling the 4 KiB page it maps: the FLA-size CSR build spent ~150 ms of its ~500 ms in
// faults. A huge page takes one fault per 2 MiB. The advice is ignored where unsupported.
#pragma once

#include <sys/mman.h>

#include <cstddef>
#include <cstdint>
#include <new>
#include <utility>
#include <vector>

namespace mosb {

// Below this, an array comes from operator new: a mapping per array would cost more than it saves.
inline constexpr std::size_t kLargeArrayBytes = std::size_t{1} << 20;

inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// The length map_large maps for `bytes`: whole huge pages.
inline std::size_t large_mapping_length(std::size_t bytes) {
  return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

// `bytes` of zeroed anonymous memory in huge pages where available; populated at once (one call
// instead of a fault per page) when `populate`. Throws std::bad_alloc. The mapping is whole huge
// pages on a 2 MiB boundary (mapped larger, then trimmed): huge pages back only the aligned 2 MiB
// a mapping covers, and an unaligned one of a few MiB got next to none.
inline void* map_large(std::size_t bytes, bool populate) {
  constexpr std::size_t kHuge = kHugePageBytes;
  const std::size_t mapped = large_mapping_length(bytes) + kHuge;
  void* raw = ::mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  auto* first = static_cast<char*>(raw);
  char* p = first + (kHuge - reinterpret_cast<std::uintptr_t>(first) % kHuge) % kHuge;
  if (p > first) ::munmap(first, static_cast<std::size_t>(p - first));
  char* end = p + large_mapping_length(bytes);
  if (first + mapped > end) ::munmap(end, static_cast<std::size_t>(first + mapped - end));
  ::madvise(p, bytes, MADV_HUGEPAGE);
  if (populate) ::madvise(p, bytes, MADV_POPULATE_WRITE);
  return p;
}

inline void unmap_large(void* p, std::size_t bytes) noexcept {
  ::munmap(p, large_mapping_length(bytes));
}

// A std::vector allocator that maps arrays of kLargeArrayBytes and more with map_large, and leaves
// elements uninitialized unless a value is given: for arrays written in full before they are read.
template <class T>
struct LargeArrayAllocator {
  using value_type = T;
  LargeArrayAllocator() = default;
  template <class U>
  explicit LargeArrayAllocator(const LargeArrayAllocator<U>&) {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kLargeArrayBytes) return static_cast<T*>(map_large(bytes, false));
    return static_cast<T*>(::operator new(bytes));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kLargeArrayBytes)
      unmap_large(p, bytes);
    else
      ::operator delete(p);
  }
  template <class U>
  void construct(U* p) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <class U>
  bool operator==(const LargeArrayAllocator<U>&) const {
    return true;
  }
};

template <class T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

}  // namespace mosb
