#include "frame_board.h"

namespace iarap::serve {

std::uint64_t FrameBoard::publish(SessionFrame frame) {
  std::uint64_t sequence = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    sequence = frame.sequence = next_sequence_++;
    latest_ = std::make_shared<const SessionFrame>(std::move(frame));
  }
  changed_.notify_all();
  return sequence;
}

std::shared_ptr<const SessionFrame> FrameBoard::wait_newer(std::uint64_t after,
                                                           std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const bool newer =
      changed_.wait_for(lock, timeout, [&] { return closed_ || (latest_ && latest_->sequence > after); });
  if (!newer || closed_) return nullptr;
  return latest_;
}

std::uint64_t FrameBoard::latest_sequence() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_sequence_ - 1;
}

void FrameBoard::close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  changed_.notify_all();
}

} // namespace iarap::serve
