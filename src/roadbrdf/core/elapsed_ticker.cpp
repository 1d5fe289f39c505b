#include "roadbrdf/core/elapsed_ticker.h"

#include <chrono>

namespace roadbrdf {

ElapsedTicker::ElapsedTicker(ProgressBar& bar, double period) {
  const auto step = std::chrono::duration<double>(period);
  thread_ = std::thread([this, &bar, step] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, step, [this] { return done_; })) bar.update(0, 1);
  });
}

ElapsedTicker::~ElapsedTicker() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

}  // namespace roadbrdf
