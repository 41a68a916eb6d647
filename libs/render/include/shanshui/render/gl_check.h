// GL error checks: after each pass in debug builds (SHANSHUI_GL_DEBUG), free in release.
#pragma once

namespace shanshui::render {

//! Throws Error naming `where` and the GL error if glGetError() reports one.
void checkGlError(const char* where);

//! After allocating GPU memory (in every build): throws one line naming `what` and, when one
//! is set, the address-space limit, if the driver reported GL_OUT_OF_MEMORY.
void checkGlAllocation(const char* what);

}  // namespace shanshui::render

#ifdef SHANSHUI_GL_DEBUG
#define SHANSHUI_GL_CHECK(where) ::shanshui::render::checkGlError(where)
#else
#define SHANSHUI_GL_CHECK(where) \
  do {                           \
  } while (false)
#endif
