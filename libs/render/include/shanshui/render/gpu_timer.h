// GPU time per pass with timestamp queries, read at once or a few frames late.
#pragma once

#include <cstddef>
#include <deque>
#include <optional>
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
  //! Waits for the GPU and returns the passes timed since the last collect() or
  //! endFrame(), in order.
  std::vector<PassTime> collect();

  //! Closes the frame's stamps without waiting for them: the GPU goes on with the next
  //! frame while this one's times are read later, by collectLate().
  void endFrame();
  //! The oldest frame closed by endFrame() and not read yet, in order of closing: nothing
  //! when there is none, or (unless `wait`) when the GPU has not reached its last stamp.
  std::optional<std::vector<PassTime>> collectLate(bool wait);
  //! Frames closed by endFrame() and not read yet.
  std::size_t framesLate() const { return late_.size(); }

 private:
  struct Frame {
    std::vector<GLuint> queries;  //!< timestamp queries, reused between frames
    std::size_t stamps = 0;       //!< used by this frame
    std::vector<std::string> names;
    std::vector<std::size_t> ends;  //!< index of each pass's closing stamp
  };
  void stamp();
  static std::vector<PassTime> read(Frame& f);
  static void clear(Frame& f);
  Frame frame_;               //!< being recorded
  std::deque<Frame> late_;    //!< closed, not read yet
  std::vector<Frame> spare_;  //!< read, its queries free for another frame
  bool open_ = false;
  bool last_was_end_ = false;
};

}  // namespace shanshui::render
