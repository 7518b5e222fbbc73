// Test helper for the bad-input channel: which field a call rejects.
#pragma once

#include <string>

#include "fogradar/core/error.hpp"

namespace fogradar::test_support {

// The field named by the InvalidParameter that `call` throws, or "accepted" when it throws none.
template <class Call>
std::string rejected_field(Call&& call) {
  try {
    call();
  } catch (const InvalidParameter& error) {
    return error.field();
  }
  return "accepted";
}

}  // namespace fogradar::test_support
