// Test helper: the message of the support::UserError that f throws.
#pragma once

#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>

#include <string>

namespace vgroove::testing_files {

// The message of the UserError that f throws ("" and a test failure if it throws none).
template <class F>
std::string user_error_of(F&& f) {
  try {
    f();
  } catch (const support::UserError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no UserError thrown";
  return "";
}

}  // namespace vgroove::testing_files
