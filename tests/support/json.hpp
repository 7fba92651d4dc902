#pragma once
// A minimal strict JSON reader for tests (no JSON library in the dependencies): recursive
// descent over RFC 8259, so "valid JSON" is checked on the whole text, not on substrings.
// Throws std::runtime_error with the offset on anything else (trailing commas, NaN, bare control
// characters, duplicate keys, trailing text).
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace shudder::test {

struct Json {
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject } type = Type::kNull;
  bool boolean = false;
  double number = 0.0;
  std::string text;         // kString
  std::vector<Json> items;  // kArray
  // A named struct rather than std::pair: libstdc++'s pair needs a complete Json here, which
  // clang (the sanitizer build) enforces; vector<incomplete> is allowed since C++17.
  struct Member;
  std::vector<Member> members;  // kObject, in text order

  bool has(const std::string& k) const;
  const Json& operator[](const std::string& k) const;
  const Json& operator[](std::size_t i) const {
    if (type != Type::kArray || i >= items.size()) throw std::runtime_error("bad array index");
    return items[i];
  }
  double num() const {
    if (type != Type::kNumber) throw std::runtime_error("not a number");
    return number;
  }
  const std::string& str() const {
    if (type != Type::kString) throw std::runtime_error("not a string");
    return text;
  }
  bool is_null() const { return type == Type::kNull; }
};

struct Json::Member {
  std::string first;
  Json second;
};

inline bool Json::has(const std::string& k) const {
  for (const auto& m : members)
    if (m.first == k) return true;
  return false;
}

inline const Json& Json::operator[](const std::string& k) const {
  if (type != Type::kObject) throw std::runtime_error("not an object looking up '" + k + "'");
  for (const auto& m : members)
    if (m.first == k) return m.second;
  throw std::runtime_error("no key '" + k + "'");
}

// Recursive descent over RFC 8259; throws std::runtime_error with the offset on anything else
// (trailing commas, NaN, bare control characters, duplicate keys, trailing text).
class Parser {
 public:
  explicit Parser(const std::string& s) : s_(s) {}
  Json parse() {
    Json v = value();
    ws();
    if (i_ != s_.size()) fail("text after the value");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw std::runtime_error("JSON error at offset " + std::to_string(i_) + ": " + why);
  }
  void ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (s_.compare(i_, w.size(), w) != 0) return false;
    i_ += w.size();
    return true;
  }
  Json value() {
    ws();
    Json v;
    const char c = peek();
    if (c == '{') {
      v.type = Json::Type::kObject;
      ++i_;
      ws();
      if (peek() == '}') return ++i_, v;
      for (;;) {
        ws();
        std::string k = string();
        if (v.has(k)) fail("duplicate key '" + k + "'");
        ws();
        expect(':');
        v.members.push_back(Json::Member{std::move(k), value()});
        ws();
        if (peek() == ',') {
          ++i_;
          continue;
        }
        expect('}');
        return v;
      }
    }
    if (c == '[') {
      v.type = Json::Type::kArray;
      ++i_;
      ws();
      if (peek() == ']') return ++i_, v;
      for (;;) {
        v.items.push_back(value());
        ws();
        if (peek() == ',') {
          ++i_;
          continue;
        }
        expect(']');
        return v;
      }
    }
    if (c == '"') {
      v.type = Json::Type::kString;
      v.text = string();
      return v;
    }
    if (literal("null")) return v;
    if (literal("true")) {
      v.type = Json::Type::kBool;
      v.boolean = true;
      return v;
    }
    if (literal("false")) {
      v.type = Json::Type::kBool;
      return v;
    }
    v.type = Json::Type::kNumber;
    v.number = number();
    return v;
  }
  static bool digit(char c) { return c >= '0' && c <= '9'; }
  double number() {
    const std::size_t start = i_;
    if (peek() == '-') ++i_;
    if (peek() == '0')
      ++i_;
    else if (digit(peek()))
      while (digit(peek())) ++i_;
    else
      fail("expected a value");
    if (peek() == '.') {
      ++i_;
      if (!digit(peek())) fail("digit expected after '.'");
      while (digit(peek())) ++i_;
    }
    if (peek() == 'e' || peek() == 'E') {
      ++i_;
      if (peek() == '+' || peek() == '-') ++i_;
      if (!digit(peek())) fail("digit expected in the exponent");
      while (digit(peek())) ++i_;
    }
    return std::strtod(s_.substr(start, i_ - start).c_str(), nullptr);
  }
  std::string string() {
    expect('"');
    std::string out;
    for (;;) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) fail("unescaped control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      const char e = peek();
      ++i_;
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          if (i_ + 4 > s_.size()) fail("short \\u escape");
          const unsigned long code = std::stoul(s_.substr(i_, 4), nullptr, 16);
          i_ += 4;
          if (code >= 0x80) fail("test parser handles only ASCII \\u escapes");
          out += static_cast<char>(code);
          break;
        }
        default: fail("bad escape");
      }
    }
  }
  const std::string& s_;
  std::size_t i_ = 0;
};

inline Json parse(const std::string& text) { return Parser(text).parse(); }

}  // namespace shudder::test
