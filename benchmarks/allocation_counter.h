// Counts the calls of the global operator new of a benchmark program, so a benchmark can report
// the allocations of the code it times as a counter (allocations per step). Include this header
// in exactly one source file of a program: it replaces the global operator new and delete
// (every form the program can call), which forward to malloc and free after counting. Counting
// is a relaxed atomic increment; it does not change what the timed code computes.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace phdslam::benchmarks {

/// Calls of operator new (any form) since the program started.
inline std::atomic<std::uint64_t>& AllocationCount() {
  static std::atomic<std::uint64_t> count{0};
  return count;
}

inline void* CountedAllocate(std::size_t size, std::size_t alignment) {
  AllocationCount().fetch_add(1, std::memory_order_relaxed);
  if (size == 0) size = 1;
  void* p = alignment <= alignof(std::max_align_t)
                ? std::malloc(size)
                : std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
  if (p == nullptr) throw std::bad_alloc();
  return p;
}

}  // namespace phdslam::benchmarks

// NOLINTBEGIN(misc-new-delete-overloads)
void* operator new(std::size_t size) {
  return phdslam::benchmarks::CountedAllocate(size, alignof(std::max_align_t));
}
void* operator new[](std::size_t size) {
  return phdslam::benchmarks::CountedAllocate(size, alignof(std::max_align_t));
}
void* operator new(std::size_t size, std::align_val_t alignment) {
  return phdslam::benchmarks::CountedAllocate(size, static_cast<std::size_t>(alignment));
}
void* operator new[](std::size_t size, std::align_val_t alignment) {
  return phdslam::benchmarks::CountedAllocate(size, static_cast<std::size_t>(alignment));
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t /*size*/) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t /*size*/) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t /*alignment*/) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t /*alignment*/) noexcept { std::free(p); }
void operator delete(void* p, std::size_t /*size*/, std::align_val_t /*alignment*/) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t /*size*/, std::align_val_t /*alignment*/) noexcept {
  std::free(p);
}
// NOLINTEND(misc-new-delete-overloads)
