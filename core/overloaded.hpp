#pragma once
// The visitor of a closed set of alternatives: std::visit(overloaded{[](const A&) {...},
// [](const B&) {...}}, v). Write one lambda per alternative and no generic `auto` one, so that
// an alternative added to the variant and not handled is a compile error.

namespace shudder {

template <class... Ts>
struct overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
overloaded(Ts...) -> overloaded<Ts...>;

}  // namespace shudder
