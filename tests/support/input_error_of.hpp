#pragma once
// The InputError a piece of code throws, for tests of error messages.

#include <gtest/gtest.h>

#include "core/error.hpp"

namespace peg3d::testing {

/// The InputError `f` throws; fails the test when it throws none.
template <class F>
InputError input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("none");
}

}  // namespace peg3d::testing
