#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>
#include <cstring>
#include <thread>

#include "freeplay/core/memory.hpp"

namespace {

// Keeps the compiler from leaving out a block's allocation and writes.
void keep(void* block) { asm volatile("" : : "r"(block) : "memory"); }

long minor_faults() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_minflt;
}

// Minor page faults while a block of `bytes` is written after an equal block was written and freed on this thread.
long faults_writing_a_block_again(std::size_t bytes) {
  void* first = std::malloc(bytes);
  std::memset(first, 1, bytes);
  keep(first);
  std::free(first);
  const long before = minor_faults();
  void* second = std::malloc(bytes);
  std::memset(second, 2, bytes);
  keep(second);
  const long faults = minor_faults() - before;
  std::free(second);
  return faults;
}

}  // namespace

TEST(Memory, AFreedBlockIsReusedWithoutFaultingItsPagesInAgain) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer replaces glibc's allocator";
#endif
  freeplay::keep_freed_memory_for_reuse();
  constexpr std::size_t kBytes = 24u << 20;  // 6 144 pages: glibc would unmap or trim it on free by default
  EXPECT_LT(faults_writing_a_block_again(kBytes), 100);
  long worker_faults = 0;  // episodes run on worker threads, whose arenas glibc otherwise shrinks on free
  std::thread worker([&] { worker_faults = faults_writing_a_block_again(kBytes); });
  worker.join();
  EXPECT_LT(worker_faults, 100);
}
