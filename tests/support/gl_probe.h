// Runs a compute shader that evaluates GLSL functions at given points, for tests that hold
// them to a CPU reference or to a brute force (noise_probe.comp, wash_probe.comp): the
// inputs in the storage buffer at binding 0, one output per input at binding 1, u_count the
// number of inputs, 64 invocations a work group. The program's own uniforms are set before.
#pragma once

#include <vector>

#include "shanshui/render/shader_program.h"

namespace shanshui::test {

template <typename Out, typename In>
std::vector<Out> runProbe(const render::Program& program, const std::vector<In>& inputs) {
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], static_cast<GLsizeiptr>(inputs.size() * sizeof(In)), inputs.data(), 0);
  glNamedBufferStorage(buffers[1], static_cast<GLsizeiptr>(inputs.size() * sizeof(Out)), nullptr, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  program.use();
  program.set("u_count", static_cast<int>(inputs.size()));
  glDispatchCompute(static_cast<GLuint>((inputs.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<Out> values(inputs.size());
  glGetNamedBufferSubData(buffers[1], 0, static_cast<GLsizeiptr>(values.size() * sizeof(Out)), values.data());
  glDeleteBuffers(2, buffers);
  return values;
}

}  // namespace shanshui::test
