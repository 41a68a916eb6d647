#include "shanshui/render/shader_program.h"

#include <algorithm>
#include <cstring>
#include <regex>
#include <sstream>
#include <type_traits>

#include <glm/gtc/type_ptr.hpp>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/render/shader_library.h"

namespace shanshui::render {

namespace {

void expand(const std::string& file, PreprocessedShader& out, std::string& text, int depth,
            const std::vector<std::string>* defines) {
  if (depth > 16) throw makeError(file, ": #include nested more than 16 deep (a cycle?)");
  const int sourceId = static_cast<int>(out.files.size());
  out.files.push_back(file);
  std::istringstream in{std::string(shaderSource(file))};
  std::string line;
  static const std::regex includeRe(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
  int lineNo = 0;
  bool sawVersion = false;
  while (std::getline(in, line)) {
    ++lineNo;
    std::smatch m;
    if (std::regex_match(line, m, includeRe)) {
      text += "#line 1 " + std::to_string(out.files.size()) + "\n";
      expand(m[1].str(), out, text, depth + 1, nullptr);
      text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(sourceId) + "\n";
      continue;
    }
    text += line + "\n";
    if (defines && !sawVersion && line.rfind("#version", 0) == 0) {
      sawVersion = true;
      for (const std::string& d : *defines) {
        const auto eq = d.find('=');
        text += "#define " + (eq == std::string::npos ? d : d.substr(0, eq) + " " + d.substr(eq + 1)) + "\n";
      }
      text += "#line " + std::to_string(lineNo + 1) + " " + std::to_string(sourceId) + "\n";
    }
  }
  if (defines && !sawVersion) throw makeError(file, ": no #version line");
}

GLenum stageOf(const std::string& file) {
  const auto dot = file.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : file.substr(dot);
  if (ext == ".vert") return GL_VERTEX_SHADER;
  if (ext == ".frag") return GL_FRAGMENT_SHADER;
  if (ext == ".geom") return GL_GEOMETRY_SHADER;
  if (ext == ".comp") return GL_COMPUTE_SHADER;
  if (ext == ".tesc") return GL_TESS_CONTROL_SHADER;
  if (ext == ".tese") return GL_TESS_EVALUATION_SHADER;
  throw makeError(file, ": unknown shader stage (expected .vert .frag .geom .comp .tesc .tese)");
}

}  // namespace

PreprocessedShader preprocessShader(const std::string& file, const std::vector<std::string>& defines) {
  PreprocessedShader out;
  expand(file, out, out.text, 0, &defines);
  return out;
}

std::string mapShaderLog(const std::string& log, const std::vector<std::string>& files) {
  static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex nvidia(R"(^(\d+)\((\d+)\)\s*:\s*(.*)$)");
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::smatch m;
    std::string mapped = line;
    auto name = [&](const std::string& id) {
      const std::size_t k = std::stoul(id);
      return k < files.size() ? files[k] : "source " + id;
    };
    if (std::regex_match(line, m, mesa)) {
      mapped = name(m[1]) + ":" + m[2].str() + ":" + m[3].str() + ": " + m[4].str();
    } else if (std::regex_match(line, m, nvidia)) {
      mapped = name(m[1]) + ":" + m[2].str() + ": " + m[3].str();
    }
    if (!out.empty()) out += "; ";
    out += mapped;
  }
  return out;
}

Program::Program(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
  std::vector<std::pair<std::string, GLenum>> stages;
  for (const std::string& file : files) stages.emplace_back(file, stageOf(file));
  build(stages, defines);
}

Program Program::pixelCompute(const std::string& frag, std::vector<std::string> defines) {
  defines.emplace_back("PIXEL_COMPUTE");
  Program p;
  p.build({{frag, GL_COMPUTE_SHADER}}, defines);
  return p;
}

void Program::build(const std::vector<std::pair<std::string, GLenum>>& stages,
                    const std::vector<std::string>& defines) {
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) glDeleteShader(s);
  };
  for (const auto& [file, stage] : stages) {
    const PreprocessedShader pre = preprocessShader(file, defines);
    const GLuint s = glCreateShader(stage);
    shaders.push_back(s);
    const char* src = pre.text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint len = 0;
      glGetShaderiv(s, GL_INFO_LOG_LENGTH, &len);
      std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
      glGetShaderInfoLog(s, len, nullptr, log.data());
      cleanup();
      throw makeError("shader compile failed: ", mapShaderLog(log.c_str(), pre.files));
    }
  }
  id_ = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(id_, s);
  glLinkProgram(id_);
  cleanup();
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint len = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(std::max(len, 1)), '\0');
    glGetProgramInfoLog(id_, len, nullptr, log.data());
    glDeleteProgram(id_);
    id_ = 0;
    std::string names;
    std::vector<std::string> files;
    for (const auto& stage : stages) {
      names += (names.empty() ? "" : " + ") + stage.first;
      files.push_back(stage.first);
    }
    throw makeError("shader link failed (", names, "): ", mapShaderLog(log.c_str(), files));
  }
}

Program::~Program() {
  if (id_ && !memoryRanOut()) glDeleteProgram(id_);  // a driver out of memory may hang: leave it
}

Program::Program(Program&& other) noexcept : id_(other.id_), uniforms_(std::move(other.uniforms_)) {
  other.id_ = 0;
  other.uniforms_.clear();
}

Program& Program::operator=(Program&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteProgram(id_);
    id_ = other.id_;
    uniforms_ = std::move(other.uniforms_);
    other.id_ = 0;
    other.uniforms_.clear();
  }
  return *this;
}

namespace {
std::uint64_t uniforms_set = 0;  // GL calls come from one thread
}  // namespace

std::uint64_t uniformsSet() {
  return uniforms_set;
}

void Program::use() const {
  glUseProgram(id_);
}
Program::Uniform& Program::uniform(const char* name) const {
  const auto at = std::lower_bound(uniforms_.begin(), uniforms_.end(), name,
                                   [](const Uniform& u, const char* n) { return std::strcmp(u.name.c_str(), n) < 0; });
  if (at != uniforms_.end() && at->name == name) return *at;
  return *uniforms_.insert(at, Uniform{name, glGetUniformLocation(id_, name)});
}

GLint Program::location(const char* name) const {
  return uniform(name).location;
}

template <typename T>
bool Program::changes(Uniform& u, const T& v) const {
  static_assert(sizeof(T) <= sizeof(u.value) && std::is_trivially_copyable_v<T>);
  if (u.location < 0) return false;  // not active: the driver would ignore it
  if (u.size == sizeof(T) && std::memcmp(u.value.data(), &v, sizeof(T)) == 0) return false;
  std::memcpy(u.value.data(), &v, sizeof(T));
  u.size = sizeof(T);
  ++uniforms_set;
  return true;
}

void Program::set(const char* name, int v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform1i(id_, u.location, v);
}
void Program::set(const char* name, unsigned v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform1ui(id_, u.location, v);
}
void Program::set(const char* name, float v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform1f(id_, u.location, v);
}
void Program::set(const char* name, const glm::vec2& v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform2fv(id_, u.location, 1, &v.x);
}
void Program::set(const char* name, const glm::ivec2& v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform2iv(id_, u.location, 1, &v.x);
}
void Program::set(const char* name, const glm::ivec4& v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform4iv(id_, u.location, 1, &v.x);
}
void Program::set(const char* name, const glm::vec3& v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform3fv(id_, u.location, 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::vec4& v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniform4fv(id_, u.location, 1, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat3& v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniformMatrix3fv(id_, u.location, 1, GL_FALSE, glm::value_ptr(v));
}
void Program::set(const char* name, const glm::mat4& v) const {
  Uniform& u = uniform(name);
  if (changes(u, v)) glProgramUniformMatrix4fv(id_, u.location, 1, GL_FALSE, glm::value_ptr(v));
}

}  // namespace shanshui::render
