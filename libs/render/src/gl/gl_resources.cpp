#include "shanshui/render/gl_resources.h"

#include <algorithm>
#include <utility>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/image/convert.h"
#include "shanshui/render/gl_check.h"

namespace shanshui::render {

Texture2D::Texture2D(int width, int height, GLenum internal_format, int levels)
    : width_(width), height_(height), format_(internal_format) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384) {
    throw makeError("texture size ", width, "x", height, " is out of range (1..16384)");
  }
  glCreateTextures(GL_TEXTURE_2D, 1, &id_);
  glTextureStorage2D(id_, levels, internal_format, width, height);
  glTextureParameteri(id_, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(id_, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(id_, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(id_, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  checkGlAllocation(("a " + std::to_string(width) + "x" + std::to_string(height) + " texture").c_str());
}

Texture2D Texture2D::fromImage(const image::Image& img, GLenum internal_format) {
  if (img.empty()) throw makeError("cannot upload an empty image");
  Texture2D t(img.width, img.height, internal_format);
  const image::Image rgba = image::toRgba(img);
  // GL's first row is the bottom one.
  std::vector<float> flipped(rgba.pixels.size());
  const std::size_t row = static_cast<std::size_t>(rgba.width) * 4;
  for (int y = 0; y < rgba.height; ++y) {
    std::copy_n(&rgba.pixels[static_cast<std::size_t>(y) * row], row,
                &flipped[static_cast<std::size_t>(rgba.height - 1 - y) * row]);
  }
  glTextureSubImage2D(t.id_, 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, flipped.data());
  SHANSHUI_GL_CHECK("Texture2D upload");
  return t;
}

Texture2D Texture2D::tiledFromImage(const image::Image& img, GLenum internal_format, GLenum min_filter) {
  if (img.empty()) throw makeError("cannot upload an empty image");
  int levels = 1;
  while ((std::max(img.width, img.height) >> levels) > 0) ++levels;
  Texture2D t(img.width, img.height, internal_format, levels);
  const image::Image rgba = image::toRgba(img);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.id_, 0, 0, 0, img.width, img.height, GL_RGBA, GL_FLOAT, rgba.pixels.data());
  glGenerateTextureMipmap(t.id_);
  glTextureParameteri(t.id_, GL_TEXTURE_MIN_FILTER, min_filter);
  glTextureParameteri(t.id_, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(t.id_, GL_TEXTURE_WRAP_T, GL_REPEAT);
  SHANSHUI_GL_CHECK("Texture2D tiled upload");
  return t;
}

Texture2D::~Texture2D() {
  if (id_ && !memoryRanOut()) glDeleteTextures(1, &id_);  // see memoryRanOut()
}

Texture2D::Texture2D(Texture2D&& o) noexcept
    : id_(std::exchange(o.id_, 0)), width_(o.width_), height_(o.height_), format_(o.format_) {}

Texture2D& Texture2D::operator=(Texture2D&& o) noexcept {
  if (this != &o) {
    if (id_) glDeleteTextures(1, &id_);
    id_ = std::exchange(o.id_, 0);
    width_ = o.width_;
    height_ = o.height_;
    format_ = o.format_;
  }
  return *this;
}

image::Image Texture2D::download(int channels) const {
  static const GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  if (channels < 1 || channels > 4) throw makeError("download: ", channels, " channels (expected 1-4)");
  image::Image img(width_, height_, channels);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  const bool depth =
      format_ == GL_DEPTH_COMPONENT32F || format_ == GL_DEPTH_COMPONENT24 || format_ == GL_DEPTH_COMPONENT16;
  if (depth && channels != 1) throw makeError("download: a depth texture has 1 channel, not ", channels);
  glGetTextureImage(id_, 0, depth ? GL_DEPTH_COMPONENT : formats[channels - 1], GL_FLOAT,
                    static_cast<GLsizei>(img.pixels.size() * sizeof(float)), img.pixels.data());
  SHANSHUI_GL_CHECK("Texture2D download");
  const std::size_t row = static_cast<std::size_t>(width_) * channels;
  for (int y = 0; y < height_ / 2; ++y) {
    std::swap_ranges(img.pixels.begin() + static_cast<std::ptrdiff_t>(y * row),
                     img.pixels.begin() + static_cast<std::ptrdiff_t>((y + 1) * row),
                     img.pixels.begin() + static_cast<std::ptrdiff_t>((height_ - 1 - y) * row));
  }
  return img;
}

Framebuffer::Framebuffer(int width, int height, const std::vector<GLenum>& colour_formats, bool depth)
    : name_(GlName<FramebufferKind>::create()), width_(width), height_(height) {
  const GLuint id = name_.id();
  std::vector<GLenum> buffers;
  for (std::size_t i = 0; i < colour_formats.size(); ++i) {
    colours_.emplace_back(width, height, colour_formats[i]);
    glNamedFramebufferTexture(id, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i), colours_.back().id(), 0);
    buffers.push_back(static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i));
  }
  glNamedFramebufferDrawBuffers(id, static_cast<GLsizei>(buffers.size()), buffers.data());
  if (depth) {
    depth_ = Texture2D(width, height, GL_DEPTH_COMPONENT32F);
    glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  }
  const GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    throw makeError("framebuffer ", width, "x", height, " is incomplete (status 0x", std::hex, status, std::dec, ")",
                    addressSpaceLimitNote());
  }
  SHANSHUI_GL_CHECK("Framebuffer create");
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, name_.id());
  glViewport(0, 0, width_, height_);
}

}  // namespace shanshui::render
