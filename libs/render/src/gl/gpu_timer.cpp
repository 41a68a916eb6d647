#include "shanshui/render/gpu_timer.h"

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"

namespace shanshui::render {

// Timestamps (glQueryCounter) at pass boundaries rather than GL_TIME_ELAPSED ranges: Mesa's
// llvmpipe reports the first elapsed-time range of a context as the time since boot.

namespace {
void deleteQueries(std::vector<GLuint>& q) {
  if (!q.empty() && !memoryRanOut()) glDeleteQueries(static_cast<GLsizei>(q.size()), q.data());
  q.clear();
}
}  // namespace

GpuTimer::~GpuTimer() {
  deleteQueries(frame_.queries);
  for (Frame& f : late_) deleteQueries(f.queries);
  for (Frame& f : spare_) deleteQueries(f.queries);
}

void GpuTimer::stamp() {
  Frame& f = frame_;
  if (f.stamps == f.queries.size()) {
    GLuint q = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &q);
    f.queries.push_back(q);
  }
  glQueryCounter(f.queries[f.stamps++], GL_TIMESTAMP);
}

void GpuTimer::begin(const std::string& name) {
  SHANSHUI_CHECK(!open_);
  if (frame_.stamps == 0 || !last_was_end_) stamp();
  frame_.names.push_back(name);
  open_ = true;
}

void GpuTimer::end() {
  SHANSHUI_CHECK(open_);
  stamp();
  open_ = false;
  last_was_end_ = true;
  frame_.ends.push_back(frame_.stamps - 1);
}

void GpuTimer::gap() {
  SHANSHUI_CHECK(!open_);
  last_was_end_ = false;
}

std::vector<PassTime> GpuTimer::read(Frame& f) {
  std::vector<GLuint64> t(f.stamps);
  for (std::size_t i = 0; i < f.stamps; ++i) glGetQueryObjectui64v(f.queries[i], GL_QUERY_RESULT, &t[i]);
  std::vector<PassTime> out;
  out.reserve(f.names.size());
  for (std::size_t i = 0; i < f.names.size(); ++i) {
    const std::size_t e = f.ends[i];
    out.push_back({f.names[i], static_cast<double>(t[e] - t[e - 1]) * 1e-6});
  }
  return out;
}

void GpuTimer::clear(Frame& f) {
  f.names.clear();
  f.ends.clear();
  f.stamps = 0;
}

std::vector<PassTime> GpuTimer::collect() {
  SHANSHUI_CHECK(!open_);
  std::vector<PassTime> out = read(frame_);
  clear(frame_);
  last_was_end_ = false;
  return out;
}

void GpuTimer::endFrame() {
  SHANSHUI_CHECK(!open_);
  Frame next;
  if (!spare_.empty()) {
    next = std::move(spare_.back());
    spare_.pop_back();
  }
  late_.push_back(std::move(frame_));
  frame_ = std::move(next);
  last_was_end_ = false;
}

std::optional<std::vector<PassTime>> GpuTimer::collectLate(bool wait) {
  if (late_.empty()) return std::nullopt;
  Frame& f = late_.front();
  if (!wait && f.stamps > 0) {
    GLuint available = GL_FALSE;
    glGetQueryObjectuiv(f.queries[f.stamps - 1], GL_QUERY_RESULT_AVAILABLE, &available);
    if (available == GL_FALSE) return std::nullopt;
  }
  std::vector<PassTime> out = read(f);
  clear(f);
  spare_.push_back(std::move(f));
  late_.pop_front();
  return out;
}

}  // namespace shanshui::render
