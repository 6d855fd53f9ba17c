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

// Success when f throws a UserError whose message contains `part`; otherwise a failure that prints
// the message (or says none was thrown).
template <class F>
::testing::AssertionResult user_error_contains(F&& f, const std::string& part) {
  try {
    f();
  } catch (const support::UserError& e) {
    if (std::string(e.what()).find(part) != std::string::npos) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "the message \"" << e.what() << "\" lacks \"" << part << "\"";
  }
  return ::testing::AssertionFailure() << "no UserError thrown";
}

}  // namespace vgroove::testing_files
