// A GoogleTest fixture that opens one headless GL 4.5 debug context per test suite and
// fails any test during which the driver reported a GL error or a high-severity message
// (KHR_debug), in every build type.
#pragma once

#include <memory>

#include <gtest/gtest.h>

#include "shanshui/render/gl_context.h"

namespace shanshui::test {

class HeadlessGl : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = render::GlContext::create({.kind = render::ContextKind::Headless, .debug = true});
  }
  static void TearDownTestSuite() { context_.reset(); }
  void SetUp() override { render::GlContext::takeDebugMessages(); }
  void TearDown() override {
    for (const std::string& m : render::GlContext::takeDebugMessages()) ADD_FAILURE() << "GL debug output: " << m;
  }
  static inline std::unique_ptr<render::GlContext> context_;
};

}  // namespace shanshui::test
