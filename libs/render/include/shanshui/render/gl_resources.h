// RAII wrappers for GL objects: vertex arrays, buffers, textures and framebuffers (OpenGL 4.5
// direct state access). Every GL name the renderer creates is owned by one of these.
#pragma once

#include <vector>

#include <epoxy/gl.h>

#include "shanshui/core/atomic_output.h"
#include "shanshui/image/image.h"

namespace shanshui::render {

//! One GL name of a kind (K::create() / K::destroy()), deleted with its owner.
template <typename K>
class GlName {
 public:
  GlName() = default;
  static GlName create() {
    GlName n;
    n.id_ = K::create();
    return n;
  }
  ~GlName() {
    if (id_ && !memoryRanOut()) K::destroy(id_);  // a driver out of memory may hang: leave it
  }
  GlName(GlName&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  GlName& operator=(GlName&& o) noexcept {
    if (this != &o) {
      if (id_) K::destroy(id_);
      id_ = o.id_;
      o.id_ = 0;
    }
    return *this;
  }
  GlName(const GlName&) = delete;
  GlName& operator=(const GlName&) = delete;
  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

 private:
  GLuint id_ = 0;
};

struct VertexArrayKind {
  static GLuint create() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct BufferKind {
  static GLuint create() {
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct FramebufferKind {
  static GLuint create() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct BufferTextureKind {
  static GLuint create() {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    return id;
  }
  static void destroy(GLuint id) { glDeleteTextures(1, &id); }
};
using VertexArray = GlName<VertexArrayKind>;
using Buffer = GlName<BufferKind>;
//! A buffer texture's name (GL_TEXTURE_BUFFER): a view of a Buffer's bytes as texels.
using BufferTexture = GlName<BufferTextureKind>;

class Texture2D {
 public:
  Texture2D() = default;
  //! Immutable storage with `levels` mip levels. internal_format e.g. GL_RGBA8, GL_RGBA32F.
  Texture2D(int width, int height, GLenum internal_format, int levels = 1);
  //! Uploads an Image (1-4 channels, float) into a texture of the given format.
  static Texture2D fromImage(const image::Image& img, GLenum internal_format = GL_RGBA8);
  //! A repeating, mipmapped texture for surface detail (wrinkles, noise). The default
  //! minification filter is bilinear in the nearest mip level: half the fetches of trilinear,
  //! which matters on a software rasteriser; GL_NEAREST_MIPMAP_NEAREST for smooth content.
  static Texture2D tiledFromImage(const image::Image& img, GLenum internal_format,
                                  GLenum min_filter = GL_LINEAR_MIPMAP_NEAREST);
  ~Texture2D();
  Texture2D(Texture2D&& other) noexcept;
  Texture2D& operator=(Texture2D&& other) noexcept;
  Texture2D(const Texture2D&) = delete;
  Texture2D& operator=(const Texture2D&) = delete;

  GLuint id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }
  GLenum format() const { return format_; }
  //! Reads level 0 back as an Image with `channels` channels, row 0 at the top.
  image::Image download(int channels = 4) const;

 private:
  GLuint id_ = 0;
  int width_ = 0;
  int height_ = 0;
  GLenum format_ = 0;
};

//! A framebuffer with colour textures and an optional depth texture.
class Framebuffer {
 public:
  Framebuffer() = default;
  //! Throws Error if the combination is incomplete on this driver (nothing is leaked).
  Framebuffer(int width, int height, const std::vector<GLenum>& colour_formats, bool depth = true);

  GLuint id() const { return name_.id(); }
  int width() const { return width_; }
  int height() const { return height_; }
  const Texture2D& colour(int i = 0) const { return colours_.at(static_cast<std::size_t>(i)); }
  const Texture2D& depth() const { return depth_; }
  //! Binds for drawing and sets the viewport to the whole framebuffer.
  void bind() const;

 private:
  GlName<FramebufferKind> name_;
  int width_ = 0;
  int height_ = 0;
  std::vector<Texture2D> colours_;
  Texture2D depth_;
};

}  // namespace shanshui::render
