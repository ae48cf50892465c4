#include "validation/runner/execution/out_of_memory_valve.h"

namespace phdslam::validation {
namespace {

// The valve the installed new_handler serves (new_handler takes no argument).
std::atomic<OutOfMemoryValve*>& ActiveValve() {
  static std::atomic<OutOfMemoryValve*> active{nullptr};
  return active;
}

}  // namespace

OutOfMemoryValve::OutOfMemoryValve(std::size_t chunks, std::size_t chunk_bytes) {
  chunks_.reserve(chunks);
  for (std::size_t i = 0; i < chunks; ++i) {
    std::unique_ptr<char[]> chunk(new (std::nothrow) char[chunk_bytes]);
    if (!chunk) break;  // hold what could be had
    chunks_.push_back(std::move(chunk));
  }
  previous_valve_ = ActiveValve().exchange(this);
  previous_handler_ = std::set_new_handler(&OutOfMemoryValve::Handler);
}

OutOfMemoryValve::~OutOfMemoryValve() {
  std::set_new_handler(previous_handler_);
  ActiveValve().store(previous_valve_);
}

void OutOfMemoryValve::Trip() noexcept {
  tripped_.store(true);
  ReleaseChunk();
}

bool OutOfMemoryValve::ReleaseChunk() noexcept {
  std::unique_ptr<char[]> chunk;  // freed outside the lock
  const std::lock_guard<std::mutex> lock(mutex_);
  if (chunks_.empty()) return false;
  chunk = std::move(chunks_.back());
  chunks_.pop_back();
  return true;
}

void OutOfMemoryValve::Handler() {
  OutOfMemoryValve* valve = ActiveValve().load();
  if (valve == nullptr) throw std::bad_alloc();
  valve->tripped_.store(true);
  if (!valve->ReleaseChunk()) throw std::bad_alloc();  // reserve used up: fail the allocation
}

}  // namespace phdslam::validation
