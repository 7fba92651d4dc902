#pragma once
// The one place where a command's exceptions become exit codes and a single stderr line:
//   io::InputError                      -> 2  "shudder: error: FILE:LINE: key ...: ..."
//   std::invalid_argument (model checks) -> 2  "shudder: error: CONTEXT: ..."
//   any other std::exception             -> 1  "shudder: WHAT failed: ..." (numerical/internal)
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include "io/input_error.hpp"

namespace shudder::app {

template <class Body>
int guarded(const std::string& context, const char* what, Body&& body) {
  try {
    return body();
  } catch (const io::InputError& e) {
    std::cerr << "shudder: error: " << e.what() << "\n";
    return 2;
  } catch (const std::invalid_argument& e) {
    std::cerr << "shudder: error: " << context << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "shudder: " << what << " failed: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace shudder::app
