#include "roadbrdf/core/diagnostics.h"

#include <mutex>
#include <utility>

namespace roadbrdf {

namespace {

struct FrontEndSink {
  std::mutex mutex;
  std::function<void(const std::string&)> sink;
  std::vector<std::string> unrouted;
};

FrontEndSink& front_end_sink() {
  static FrontEndSink instance;
  return instance;
}

}  // namespace

void set_front_end_warning_sink(std::function<void(const std::string&)> sink) {
  FrontEndSink& f = front_end_sink();
  const std::lock_guard<std::mutex> lock(f.mutex);
  f.sink = std::move(sink);
}

void route_warning(const std::string& message) {
  FrontEndSink& f = front_end_sink();
  std::function<void(const std::string&)> sink;
  {
    const std::lock_guard<std::mutex> lock(f.mutex);
    if (!f.sink) {
      f.unrouted.push_back(message);
      return;
    }
    sink = f.sink;
  }
  sink(message);  // outside the lock: a Python sink takes the GIL
}

std::vector<std::string> take_unrouted_warnings() {
  FrontEndSink& f = front_end_sink();
  const std::lock_guard<std::mutex> lock(f.mutex);
  return std::exchange(f.unrouted, {});
}

}  // namespace roadbrdf
