// Per-pixel passes as fragment or compute shaders (issue 47 item 2): one GLSL source ending
// with pixel_main.glsl runs as a fragment shader over a full-screen triangle or, on a GPU,
// as a compute shader over the same pixels.
#pragma once

#include <string>
#include <vector>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include "shanshui/render/gl_resources.h"
#include "shanshui/render/shader_program.h"

namespace shanshui::render {

//! Whether the per-pixel passes run as compute shaders (Program::pixelCompute) rather than
//! as fragment shaders over a full-screen triangle, in the current context: yes on a GPU,
//! no on a software rasteriser (llvmpipe, softpipe), which shades a fragment pass faster (its
//! depth test skips the pixels another draw covers before they are shaded, where a compute
//! shader's branch runs both sides). SHANSHUI_PIXEL_PASSES=compute or =fragment overrides
//! it (the tests draw both ways on llvmpipe and compare the pictures); any other value is an
//! error naming it.
bool pixelPassesAsCompute();

//! Whether the strokes' ink is gathered by each pixel from the stroke centres near it
//! (ink_lines.frag writes each centre's ink and reach, ink.frag takes the most any centre
//! within the widest reach gives it) instead of stamped by each centre with image atomics:
//! the same ink to within rounding, no atomics. Only with compute per-pixel passes; off
//! unless SHANSHUI_STROKES=gather (=stamp, or unset, keeps the atomics) until a GPU has
//! timed both; any other value is an error naming it.
bool strokesGathered();

//! Runs `p` (made by Program::pixelCompute, in use) over the pixels [x0, x1) × [y0, y1) of
//! `rect` in 8x8 groups, then makes its stores visible to whatever reads them next:
//! textures, images, framebuffers and read-back.
void dispatchPixels(const Program& p, const glm::ivec4& rect);

//! `frag` as a compute shader when `compute`, else with fullscreen.vert.
Program pixelProgram(const std::string& frag, const std::vector<std::string>& defines, bool compute);

//! Shades the pixels of `rect` with `p` (from pixelProgram, in use) into `target`'s colour
//! attachments: a compute shader writes them as the images 7, 6, … (`formats`: the
//! attachments' own), a fragment shader draws its triangle into `target` under the frame's
//! scissor (a vertex array must be bound).
void shadePixels(const Program& p, bool compute, const Framebuffer& target, const std::vector<GLenum>& formats,
                 const glm::ivec4& rect);

}  // namespace shanshui::render
