#include "shanshui/render/gpu_timer.h"

#include "shanshui/core/error.h"

namespace shanshui::render {

// Timestamps (glQueryCounter) at pass boundaries rather than GL_TIME_ELAPSED ranges: Mesa's
// llvmpipe reports the first elapsed-time range of a context as the time since boot.

GpuTimer::~GpuTimer() {
  if (!queries_.empty()) glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
}

void GpuTimer::stamp() {
  if (stamps_ == queries_.size()) {
    GLuint q = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &q);
    queries_.push_back(q);
  }
  glQueryCounter(queries_[stamps_++], GL_TIMESTAMP);
}

void GpuTimer::begin(const std::string& name) {
  SHANSHUI_CHECK(!open_);
  if (stamps_ == 0 || !last_was_end_) stamp();
  names_.push_back(name);
  open_ = true;
}

void GpuTimer::end() {
  SHANSHUI_CHECK(open_);
  stamp();
  open_ = false;
  last_was_end_ = true;
  ends_.push_back(stamps_ - 1);
}

void GpuTimer::gap() {
  SHANSHUI_CHECK(!open_);
  last_was_end_ = false;
}

std::vector<PassTime> GpuTimer::collect() {
  SHANSHUI_CHECK(!open_);
  std::vector<GLuint64> t(stamps_);
  for (std::size_t i = 0; i < stamps_; ++i) glGetQueryObjectui64v(queries_[i], GL_QUERY_RESULT, &t[i]);
  std::vector<PassTime> out;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    const std::size_t e = ends_[i];
    out.push_back({names_[i], static_cast<double>(t[e] - t[e - 1]) * 1e-6});
  }
  names_.clear();
  ends_.clear();
  stamps_ = 0;
  last_was_end_ = false;
  return out;
}

}  // namespace shanshui::render
