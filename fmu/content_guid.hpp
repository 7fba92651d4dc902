#pragma once
// The FMU's GUID as a name-based UUID (RFC 4122 section 4.3, version 5: SHA-1) of the
// modelDescription.xml text, so the GUID changes whenever the description does (a variable,
// a unit, a capability flag) and an importer cannot pair a description with a library built
// from another one. fmu/model_description.cpp computes it over the text written with
// kGuidPlaceholder in the guid attribute, then puts it in the XML and in the header the
// library is compiled with; tests/fmu recomputes it from the packed XML.
#include <array>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace shudder::fmu {

inline constexpr std::string_view kGuidPlaceholder = "{GUID}";

/// SHA-1 (FIPS 180-4) of `data`.
inline std::array<std::uint8_t, 20> sha1(std::string_view data) {
  std::uint32_t h[5] = {0x67452301u, 0xEFCDAB89u, 0x98BADCFEu, 0x10325476u, 0xC3D2E1F0u};
  std::string m(data);
  const std::uint64_t bits = static_cast<std::uint64_t>(data.size()) * 8u;
  m += static_cast<char>(0x80);
  while (m.size() % 64 != 56) m += '\0';
  for (int i = 7; i >= 0; --i) m += static_cast<char>((bits >> (8 * i)) & 0xFFu);
  const auto rotl = [](std::uint32_t x, int n) { return (x << n) | (x >> (32 - n)); };
  for (std::size_t block = 0; block < m.size(); block += 64) {
    std::uint32_t w[80];
    for (int t = 0; t < 16; ++t) {
      w[t] = 0;
      for (int b = 0; b < 4; ++b) w[t] = (w[t] << 8) | static_cast<std::uint8_t>(m[block + 4 * t + b]);
    }
    for (int t = 16; t < 80; ++t) w[t] = rotl(w[t - 3] ^ w[t - 8] ^ w[t - 14] ^ w[t - 16], 1);
    std::uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4];
    for (int t = 0; t < 80; ++t) {
      std::uint32_t f, k;
      if (t < 20)
        f = (b & c) | (~b & d), k = 0x5A827999u;
      else if (t < 40)
        f = b ^ c ^ d, k = 0x6ED9EBA1u;
      else if (t < 60)
        f = (b & c) | (b & d) | (c & d), k = 0x8F1BBCDCu;
      else
        f = b ^ c ^ d, k = 0xCA62C1D6u;
      const std::uint32_t temp = rotl(a, 5) + f + e + k + w[t];
      e = d, d = c, c = rotl(b, 30), b = a, a = temp;
    }
    h[0] += a, h[1] += b, h[2] += c, h[3] += d, h[4] += e;
  }
  std::array<std::uint8_t, 20> out{};
  for (int i = 0; i < 5; ++i)
    for (int b = 0; b < 4; ++b) out[4 * i + b] = static_cast<std::uint8_t>(h[i] >> (24 - 8 * b));
  return out;
}

/// RFC 4122 version-5 UUID of `name` in the namespace `ns` (16 bytes), as {8-4-4-4-12} in
/// lower-case hex with braces (the form FMI tools write).
inline std::string uuid_v5(const std::array<std::uint8_t, 16>& ns, std::string_view name) {
  std::string input(reinterpret_cast<const char*>(ns.data()), ns.size());
  input += name;
  const auto digest = sha1(input);
  std::array<std::uint8_t, 16> u{};
  for (int i = 0; i < 16; ++i) u[i] = digest[i];
  u[6] = static_cast<std::uint8_t>((u[6] & 0x0Fu) | 0x50u);  // version 5
  u[8] = static_cast<std::uint8_t>((u[8] & 0x3Fu) | 0x80u);  // RFC 4122 variant
  std::string s = "{";
  char hex[3];
  for (int i = 0; i < 16; ++i) {
    if (i == 4 || i == 6 || i == 8 || i == 10) s += '-';
    std::snprintf(hex, sizeof hex, "%02x", u[i]);
    s += hex;
  }
  return s + "}";
}

/// The RFC 4122 URL namespace (6ba7b811-9dad-11d1-80b4-00c04fd430c8); the name hashed in it
/// is "shudder-fmu:" followed by the description's text with the placeholder GUID.
inline constexpr std::array<std::uint8_t, 16> kUrlNamespace = {0x6b, 0xa7, 0xb8, 0x11, 0x9d, 0xad, 0x11, 0xd1,
                                                               0x80, 0xb4, 0x00, 0xc0, 0x4f, 0xd4, 0x30, 0xc8};

inline std::string content_guid(std::string_view description_with_placeholder) {
  return uuid_v5(kUrlNamespace, std::string("shudder-fmu:") + std::string(description_with_placeholder));
}

}  // namespace shudder::fmu
