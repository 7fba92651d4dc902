#pragma once
// The declarations of every network component type and signal kind: each key with its kind,
// unit, default (or required), allowed range and meaning. The reader (io/network_scenario.cpp)
// reads every key through its declaration (so defaults and ranges live here only), and
// docs/formats/network_file.md's reference tables are generated from the same declarations
// (network_reference_markdown; the test NetworkComponents.DocsTablesEqualTheDeclarations).

#include <optional>
#include <string>
#include <vector>

#include "io/toml_reader.hpp"

namespace shudder::io {

enum class KeyKind { kNumber, kInteger, kNode, kNodeOrGround, kComponent, kSignal, kChoice, kTable };

struct KeyDecl {
  std::string key;
  KeyKind kind = KeyKind::kNumber;
  std::string unit;                // "" for none
  std::optional<double> fallback;  // numbers, integers: the default; absent: required unless `optional_note`
  Range range;                     // numbers, integers
  std::string meaning;
  std::string optional_note;         // a key that is neither required nor defaulted: what happens without it
  std::vector<std::string> choices;  // kChoice; the first is the default
};

struct ComponentDecl {
  std::string type;
  std::string what;  // one line
  std::vector<KeyDecl> keys;
  const KeyDecl& key(const std::string& name) const;  // std::logic_error for an undeclared key
};

const std::vector<ComponentDecl>& network_component_decls();
const std::vector<ComponentDecl>& signal_kind_decls();
const ComponentDecl& component_decl(const std::string& type);
const ComponentDecl& signal_decl(const std::string& kind);
std::vector<std::string> component_types();
std::vector<std::string> signal_kinds();

/// Reads a number or integer key of `decl` from `t`: its default and range from the declaration.
double read_number(TomlTable& t, const ComponentDecl& decl, const std::string& key);
/// Whether `t` gives the key (for keys with an optional_note).
bool gives(const TomlTable& t, const std::string& key);

/// docs/formats/network_file.md's reference: one table per component type, one for the signal kinds.
std::string network_reference_markdown();

}  // namespace shudder::io
