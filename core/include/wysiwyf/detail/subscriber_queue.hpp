#pragma once
// A bounded keep-last queue of samples for one input port. Slots are reused: after warm-up a
// push copies into existing storage and a take swaps buffers, so steady state allocates nothing.
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "wysiwyf/detail/doorbell.hpp"

namespace wysiwyf::detail {

// What the kernel reads of any input queue for its diagnostics.
class QueueCounters {
 public:
  virtual ~QueueCounters() = default;
  virtual std::uint64_t received() const = 0;
  virtual std::uint64_t dropped() const = 0;  // pushed out unread by newer samples (keep-last)

  // A data-triggered component's doorbell, rung after every push (set before the run starts).
  void set_doorbell(Doorbell* doorbell) { doorbell_ = doorbell; }

 protected:
  void ring() {
    if (doorbell_) doorbell_->ring();
  }

 private:
  Doorbell* doorbell_ = nullptr;
};

template <class T>
class SubscriberQueue final : public QueueCounters {
 public:
  explicit SubscriberQueue(int depth)
      : slots_(static_cast<std::size_t>(depth < 1 ? 1 : depth)), origins_(slots_.size(), nullptr) {}

  // `origin`: the process that wrote the sample (its DDS participant's name, kept by the channel
  // for the run), or null for this process. Returns how many samples wait now, this one included.
  std::size_t push(const T& sample, const std::string* origin = nullptr) {
    return store([&](T& slot) { slot = sample; }, origin);
  }

  // Like push, but moves the sample in by swapping buffers with the slot it lands in: no copy.
  // `sample` is left holding that slot's previous contents.
  void push_swap(T& sample, const std::string* origin = nullptr) {
    (void)store(
        [&](T& slot) {
          using std::swap;
          swap(slot, sample);
        },
        origin);
  }

  // Oldest unread sample into out; false when none.
  bool take(T& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (count_ == 0) return false;
    using std::swap;
    swap(out, slots_[head_]);
    taken_origin_ = origins_[head_];
    head_ = (head_ + 1) % slots_.size();
    --count_;
    return true;
  }

  // Newest unread sample into out, discarding older unread ones; false when none.
  bool take_latest(T& out) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (count_ == 0) return false;
    using std::swap;
    const std::size_t newest = (head_ + count_ - 1) % slots_.size();
    swap(out, slots_[newest]);
    taken_origin_ = origins_[newest];
    head_ = 0;
    count_ = 0;
    return true;
  }

  // The origin of the sample the last take returned (the taking thread's; null: this process).
  const std::string* taken_origin() const { return taken_origin_; }

  std::size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return count_;
  }
  std::size_t capacity() const { return slots_.size(); }
  std::uint64_t received() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }
  std::uint64_t dropped() const override {
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
  }

 private:
  // `put` fills the slot the next sample lands in (keep-last: a full queue drops its oldest
  // first); then the doorbell rings, outside the lock. Returns the samples waiting.
  template <class Put>
  std::size_t store(Put&& put, const std::string* origin) {
    std::size_t waiting = 0;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const std::size_t n = slots_.size();
      if (count_ == n) {
        head_ = (head_ + 1) % n;
        --count_;
        ++dropped_;
      }
      put(slots_[(head_ + count_) % n]);
      origins_[(head_ + count_) % n] = origin;
      waiting = ++count_;
      ++received_;
    }
    ring();
    return waiting;
  }

  mutable std::mutex mutex_;
  std::vector<T> slots_;
  std::vector<const std::string*> origins_;  // each slot's sample's
  const std::string* taken_origin_ = nullptr;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  std::uint64_t received_ = 0;
  std::uint64_t dropped_ = 0;
};

}  // namespace wysiwyf::detail
