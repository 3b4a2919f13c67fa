#include "motiongraph/core/huge_pages.h"

#include <algorithm>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace mg {

std::pair<std::uintptr_t, std::uintptr_t> whole_huge_pages(std::uintptr_t address, std::size_t bytes) {
  const std::uintptr_t begin = (address + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  const std::uintptr_t end = (address + bytes) / kHugePageBytes * kHugePageBytes;
  return begin < end ? std::pair{begin, end} : std::pair{begin, begin};
}

void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  const auto [begin, end] = whole_huge_pages(reinterpret_cast<std::uintptr_t>(data), bytes);
  // Advice only: an error (no such pages in this kernel) leaves the memory as it was.
  if (begin < end) (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

HugePageArena::HugePageArena(std::size_t bytes)
    : block_(new std::byte[std::max<std::size_t>(bytes, 1)]), resource_(block_.get(), std::max<std::size_t>(bytes, 1)) {
  advise_huge_pages(block_.get(), bytes);
}

}  // namespace mg
