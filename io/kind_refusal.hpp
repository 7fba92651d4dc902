#pragma once
// Calling a model kind's capability (rig_models/model.hpp) on a scenario's model: the kind's
// refusal (rig_models::KindNotSupported) becomes the input error (exit 2) that names the file
// and key the user should change, e.g. "scenario.type" or the CLI option that asked for it.
#include <string>
#include <utility>
#include <variant>

#include "io/input_error.hpp"
#include "rig_models/model.hpp"

namespace shudder::io {

/// std::visit(capability, model), with a refusal rethrown as InputError(path, 0, key, reason).
template <class Capability>
decltype(auto) visit_kind(const std::string& path, const std::string& key, const rig_models::Model& model,
                          Capability&& capability) {
  try {
    return std::visit(std::forward<Capability>(capability), model);
  } catch (const rig_models::KindNotSupported& e) {
    throw InputError(path, 0, key, e.what());
  }
}

}  // namespace shudder::io
