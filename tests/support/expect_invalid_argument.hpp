#pragma once
// Expects a callable to throw std::invalid_argument whose message contains a given fragment.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace growshell::test_support {

/// A test failure unless `call()` throws std::invalid_argument with `fragment` in its message.
template <class F>
void expect_invalid_argument_containing(F&& call, const std::string& fragment) {
  try {
    call();
    ADD_FAILURE() << "no exception; expected one naming \"" << fragment << "\"";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace growshell::test_support
