#pragma once
// The one place where a command's exceptions become exit codes and a single stderr line:
//   io::InputError                      -> 2  "shudder: error: FILE:LINE: key ...: ..."
//   std::invalid_argument (model checks) -> 2  "shudder: error: CONTEXT: ..."
//   std::bad_alloc                       -> 2  "shudder: error: CONTEXT: ran out of memory; ..."
//                                              (the input asked for more than the machine has;
//                                              commands that know the size say it themselves)
//   any other std::exception             -> 1  "shudder: WHAT failed: ..." (numerical/internal)
// Front ends other than the CLI (python/) use the same mapping: current_failure() inside their
// own catch, or failure_sink to receive a command's line instead of stderr.
#include <exception>
#include <iostream>
#include <new>
#include <stdexcept>
#include <string>

#include "io/input_error.hpp"

namespace shudder::app {

struct Failure {
  int exit_code = 0;
  std::string line;  // the stderr line, without its newline
};

/// The exit code and line for the exception being handled; call only inside a catch block.
/// Exceptions that are not std::exception propagate, as they always did.
inline Failure current_failure(const std::string& context, const char* what) {
  try {
    throw;
  } catch (const io::InputError& e) {
    return {2, std::string("shudder: error: ") + e.what()};
  } catch (const std::invalid_argument& e) {
    return {2, "shudder: error: " + context + ": " + e.what()};
  } catch (const std::bad_alloc&) {
    return {2, "shudder: error: " + context +
                   ": ran out of memory; reduce the duration, sample_rate_Hz or the number of cases"};
  } catch (const std::exception& e) {
    return {1, std::string("shudder: ") + what + " failed: " + e.what()};
  }
}

/// When set on a thread, guarded() stores its failure there instead of printing it.
inline thread_local Failure* failure_sink = nullptr;

template <class Body>
int guarded(const std::string& context, const char* what, Body&& body) {
  try {
    return body();
  } catch (const std::exception&) {
    Failure f = current_failure(context, what);
    if (failure_sink) {
      *failure_sink = f;
    } else {
      std::cerr << f.line << "\n";
    }
    return f.exit_code;
  }
}

}  // namespace shudder::app
