#pragma once
// Runs f, expects it to throw anisodyn::InputError, and returns the error for inspection.
#include <gtest/gtest.h>

#include "anisodyn/core/error.hpp"

namespace anisodyn::testing_support {

template <class F>
InputError input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("none");
}

}  // namespace anisodyn::testing_support
