// Large arrays that are written once and then read at random (a whole library's edge tracks:
// tens of MB) are best backed by the kernel's transparent huge pages: one page fault per 2 MB
// instead of one per 4 KB. Page faults are costly on virtual machines (on the one the figures
// of docs/performance.md come from, 4 KB faults made a quarter of `path`'s time on a whole
// library). Where the kernel has no such pages, or they are off, the advice is ignored; where
// they are on for everything, it changes nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <memory_resource>
#include <utility>
#include <vector>

namespace mg {

constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// The whole huge pages inside [address, address + bytes): the range the advice can cover
// (begin == end when there is none).
std::pair<std::uintptr_t, std::uintptr_t> whole_huge_pages(std::uintptr_t address, std::size_t bytes);

// Advises huge pages for the whole huge pages inside the range (memory not yet written is
// what gains).
void advise_huge_pages(const void* data, std::size_t bytes);

// Reserves room for `count` elements in an empty vector (allocated, not yet written) and
// advises huge pages for it; fill it afterwards.
template <class T>
void reserve_huge(std::vector<T>& values, std::size_t count) {
  values.reserve(count);
  advise_huge_pages(values.data(), values.capacity() * sizeof(T));
}

// One block of memory, huge pages advised, handed out in order (a monotonic buffer resource
// over it, ordinary memory past its end): for data made once, in many pieces, and freed all
// together (a graph file's motion: hundreds of clips of a few hundred KB each, too small for
// huge pages of their own). Allocating from it is for one thread at a time; writing what was
// allocated, for any number.
class HugePageArena {
 public:
  explicit HugePageArena(std::size_t bytes);
  HugePageArena(const HugePageArena&) = delete;
  HugePageArena& operator=(const HugePageArena&) = delete;

  std::pmr::memory_resource* resource() { return &resource_; }

 private:
  std::unique_ptr<std::byte[]> block_;  // not written until handed out
  std::pmr::monotonic_buffer_resource resource_;
};

}  // namespace mg
