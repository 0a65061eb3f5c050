// Shared by the OBJ and PLY reader tests: expect an InputError at a line, with a text.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "integrator/geometry/mesh_io.h"
#include "sensor/base/input_error.h"

namespace camsim::test {

// Runs fn, expects InputError at `line` whose message contains `text`.
inline void expectError(const std::function<void()>& fn, int line, const std::string& text) {
  try {
    fn();
    ADD_FAILURE() << "no InputError; expected line " << line << " '" << text << "'";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, line) << e.what();
    EXPECT_NE(e.message().find(text), std::string::npos) << e.what();
    EXPECT_EQ(e.where().file, "test") << e.what();
  }
}

inline void expectObjError(const std::string& text, int line, const std::string& what) {
  SCOPED_TRACE(text);
  expectError([&] { parseObj(text, "test"); }, line, what);
}

inline void expectPlyError(const std::string& bytes, int line, const std::string& what) {
  SCOPED_TRACE(bytes.substr(0, 300));
  expectError([&] { parsePly(bytes, "test"); }, line, what);
}

}  // namespace camsim::test
