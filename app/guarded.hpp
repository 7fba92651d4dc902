#pragma once
// The one place where a command's exceptions become exit codes and a single stderr line:
//   io::InputError                      -> 2  "shudder: error: FILE:LINE: key ...: ..."
//   std::invalid_argument (model checks) -> 2  "shudder: error: CONTEXT: ..."
//   std::bad_alloc                       -> 2  "shudder: error: CONTEXT: ran out of memory; ..."
//                                              (the input asked for more than the machine has;
//                                              commands that know the size say it themselves)
//   any other std::exception             -> 1  "shudder: WHAT failed: ..." (numerical/internal)
#include <exception>
#include <iostream>
#include <new>
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
  } catch (const std::bad_alloc&) {
    std::cerr << "shudder: error: " << context
              << ": ran out of memory; reduce the duration, sample_rate_Hz or the number of cases\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "shudder: " << what << " failed: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace shudder::app
