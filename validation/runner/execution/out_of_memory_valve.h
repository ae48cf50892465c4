// The runner's answer to running out of memory: a reserve of address space released chunk by
// chunk from a std::new_handler. The first failed allocation frees a chunk and succeeds on retry,
// and the valve is marked tripped: the runner then starts no new run, lets the runs in progress
// finish (on the reserve), keeps everything finished and says so. Only when the reserve is used
// up does operator new throw std::bad_alloc, which the runner records as the run's failure.
//
// Why not just catch std::bad_alloc: JSON values (nlohmann) allocate in their destructors, so an
// exception thrown while one is being built terminates the program during unwinding when no
// memory is left. Keeping allocations succeeding avoids that.
//
// std::new_handler is a process-wide function pointer, so one valve is active at a time: the
// constructor installs it (remembering the handler and valve it replaces) and the destructor
// restores them. The chunks are never touched, so they cost address space, not resident memory.
#pragma once

#include <atomic>
#include <cstddef>
#include <memory>
#include <mutex>
#include <new>
#include <vector>

namespace phdslam::validation {

class OutOfMemoryValve {
 public:
  OutOfMemoryValve(std::size_t chunks, std::size_t chunk_bytes);
  OutOfMemoryValve(const OutOfMemoryValve&) = delete;
  OutOfMemoryValve& operator=(const OutOfMemoryValve&) = delete;
  OutOfMemoryValve(OutOfMemoryValve&&) = delete;
  OutOfMemoryValve& operator=(OutOfMemoryValve&&) = delete;
  ~OutOfMemoryValve();

  /// True once an allocation has failed while the valve was installed.
  [[nodiscard]] bool tripped() const { return tripped_.load(); }

  /// Marks the valve tripped (a std::bad_alloc seen elsewhere) and frees one chunk.
  void Trip() noexcept;

 private:
  static void Handler();
  /// Frees one chunk; false when none is left.
  bool ReleaseChunk() noexcept;

  std::mutex mutex_;  // guards chunks_
  std::vector<std::unique_ptr<char[]>> chunks_;
  std::atomic<bool> tripped_{false};
  std::new_handler previous_handler_ = nullptr;
  OutOfMemoryValve* previous_valve_ = nullptr;
};

}  // namespace phdslam::validation
