// GPU time per pass with timer queries (GL_TIME_ELAPSED), one pass at a time.
#pragma once

#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace shanshui::render {

struct PassTime {
  std::string name;
  double gpu_ms = 0.0;
};

class GpuTimer {
 public:
  GpuTimer() = default;
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  //! Starts timing a pass (passes must not overlap) and ends it. A pass that begins right
  //! where the previous one ended shares its timestamp, so back-to-back passes add up.
  void begin(const std::string& name);
  void end();
  //! Work since the last end() that no pass owns: the next pass starts from a stamp of its
  //! own rather than the last pass's end, so that work counts in neither.
  void gap();
  //! Waits for the GPU and returns the passes timed since the last collect(), in order.
  std::vector<PassTime> collect();

 private:
  void stamp();
  std::vector<GLuint> queries_;  //!< timestamp queries, reused between frames
  std::size_t stamps_ = 0;       //!< used this frame
  std::vector<std::string> names_;
  std::vector<std::size_t> ends_;  //!< index of each pass's closing stamp
  bool open_ = false;
  bool last_was_end_ = false;
};

}  // namespace shanshui::render
