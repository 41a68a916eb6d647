// A GoogleTest fixture that opens one headless GL 4.5 context per test suite.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "shanshui/render/gl_context.h"

namespace shanshui::test {

class HeadlessGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { context_ = render::GlContext::create({.kind = render::ContextKind::Headless}); }
  static void TearDownTestSuite() { context_.reset(); }
  static inline std::unique_ptr<render::GlContext> context_;
};

}  // namespace shanshui::test
