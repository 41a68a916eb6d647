// Compiling and linking GLSL programs from shaders/ with compile-time variants.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

namespace shanshui::render {

//! How many uniform values Program::set has sent to the driver in this process (the
//! benchmark reports them per frame: each is a call into the driver). A value a program
//! already holds is not sent again, and does not count.
std::uint64_t uniformsSet();

//! GLSL after include expansion: `#include "file.glsl"` is inlined and `#line` directives
//! are inserted so that the driver's line numbers can be mapped back to files. Source
//! number k in a driver message refers to files[k].
struct PreprocessedShader {
  std::string text;
  std::vector<std::string> files;
};

//! Expands includes and inserts `#define NAME` (or `NAME VALUE`) lines after `#version`.
//! Files come from the embedded library (shaders/).
PreprocessedShader preprocessShader(const std::string& file, const std::vector<std::string>& defines);

//! Rewrites a driver info log ("0:12(5): error: ..." from Mesa, "0(12) : error ..." from
//! NVIDIA) into "file.frag:12: error: ..." lines.
std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files);

//! A linked program. Stages come from the file extensions (.vert .frag .geom .comp).
//! Defines select compile-time variants: code a scene does not use is not compiled.
class Program {
 public:
  Program() = default;
  //! Throws Error with mapped file:line messages when compiling or linking fails.
  Program(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});
  //! A per-pixel fragment shader (one that ends by including pixel_main.glsl) compiled as a
  //! compute shader, with PIXEL_COMPUTE added to `defines`; run it with dispatchPixels.
  static Program pixelCompute(const std::string& frag, std::vector<std::string> defines);
  ~Program();
  Program(Program&& other) noexcept;
  Program& operator=(Program&& other) noexcept;
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  GLuint id() const { return id_; }
  void use() const;
  void set(const char* name, int v) const;
  void set(const char* name, unsigned v) const;
  void set(const char* name, float v) const;
  void set(const char* name, const glm::vec2& v) const;
  void set(const char* name, const glm::ivec2& v) const;
  void set(const char* name, const glm::ivec4& v) const;
  void set(const char* name, const glm::vec3& v) const;
  void set(const char* name, const glm::vec4& v) const;
  void set(const char* name, const glm::mat3& v) const;
  void set(const char* name, const glm::mat4& v) const;
  //! A uniform's location, asked of the driver once per name and program and then kept:
  //! passes set their uniforms by name every frame (issue 47: CPU submission).
  GLint location(const char* name) const;

 private:
  //! A uniform asked for by name: its location (-1: not active) and the value last sent.
  struct Uniform {
    std::string name;
    GLint location = -1;
    std::size_t size = 0;  //!< bytes of `value` in use; 0 before the first set
    std::array<unsigned char, sizeof(glm::mat4)> value{};
  };
  Uniform& uniform(const char* name) const;
  //! Whether `v` must go to the driver: a location that is active and a value other than the
  //! one it holds (then kept as held).
  template <typename T>
  bool changes(Uniform& u, const T& v) const;

  //! Compiles each file as the given stage and links them.
  void build(const std::vector<std::pair<std::string, GLenum>>& stages, const std::vector<std::string>& defines);

  GLuint id_ = 0;
  //! The uniforms asked for, sorted by name.
  mutable std::vector<Uniform> uniforms_;
};

}  // namespace shanshui::render
