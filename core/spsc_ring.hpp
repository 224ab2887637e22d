#pragma once
// Lock-free single-producer / single-consumer ring. The only queue between threads on the motion
// path: planner -> pulse thread (edges), pulse thread -> trace writer, backend -> control thread.
// Capacity is fixed at construction (power of two) so that neither side ever allocates.
#include <atomic>
#include <cstddef>
#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>

namespace stepmod {

inline constexpr std::size_t kCacheLine = 64;

template <typename T>
class SpscRing {
  static_assert(std::is_trivially_copyable_v<T>, "ring slots are copied without constructors");

 public:
  explicit SpscRing(std::size_t capacity_pow2)
      : capacity_(capacity_pow2), mask_(capacity_pow2 - 1), slots_(new T[capacity_pow2]) {
    if (capacity_pow2 < 2 || (capacity_pow2 & mask_) != 0) {
      throw std::invalid_argument("SpscRing capacity must be a power of two >= 2");
    }
  }
  SpscRing(const SpscRing&) = delete;
  SpscRing& operator=(const SpscRing&) = delete;

  std::size_t capacity() const noexcept { return capacity_; }

  // Producer side.
  std::size_t free_slots() const noexcept {
    return capacity_ -
           (head_.load(std::memory_order_relaxed) - tail_.load(std::memory_order_acquire));
  }
  bool try_push(const T& v) noexcept {
    const std::size_t h = head_.load(std::memory_order_relaxed);
    if (h - tail_cache_ == capacity_) {
      tail_cache_ = tail_.load(std::memory_order_acquire);
      if (h - tail_cache_ == capacity_) return false;
    }
    slots_[h & mask_] = v;
    head_.store(h + 1, std::memory_order_release);
    return true;
  }

  // Consumer side.
  const T* peek() noexcept {
    const std::size_t t = tail_.load(std::memory_order_relaxed);
    if (t == head_cache_) {
      head_cache_ = head_.load(std::memory_order_acquire);
      if (t == head_cache_) return nullptr;
    }
    return &slots_[t & mask_];
  }
  void pop() noexcept {
    tail_.store(tail_.load(std::memory_order_relaxed) + 1, std::memory_order_release);
  }
  // How many elements the consumer has popped in all (it tells whether a pass popped any).
  std::size_t popped() const noexcept { return tail_.load(std::memory_order_relaxed); }
  bool try_pop(T& out) noexcept {
    const T* p = peek();
    if (p == nullptr) return false;
    out = *p;
    pop();
    return true;
  }
  // Either side, approximate.
  std::size_t size() const noexcept {
    return head_.load(std::memory_order_acquire) - tail_.load(std::memory_order_acquire);
  }
  bool empty() const noexcept { return size() == 0; }

 private:
  const std::size_t capacity_;
  const std::size_t mask_;
  std::unique_ptr<T[]> slots_;
  alignas(kCacheLine) std::atomic<std::size_t> head_{0};  // written by the producer
  std::size_t tail_cache_{0};                             // producer's view of tail_
  alignas(kCacheLine) std::atomic<std::size_t> tail_{0};  // written by the consumer
  std::size_t head_cache_{0};                             // consumer's view of head_
};

}  // namespace stepmod
