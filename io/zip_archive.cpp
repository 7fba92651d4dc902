#include "io/zip_archive.hpp"

#include <cstdint>
#include <stdexcept>

namespace shudder::io {

unsigned long crc32_of(const std::string& data) {
  std::uint32_t table[256];
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  std::uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char ch : data) crc = table[(crc ^ ch) & 0xFFu] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

namespace {
void put16(std::string& out, std::uint32_t v) {
  out += static_cast<char>(v & 0xFFu);
  out += static_cast<char>((v >> 8) & 0xFFu);
}
void put32(std::string& out, std::uint32_t v) {
  put16(out, v & 0xFFFFu);
  put16(out, v >> 16);
}
}  // namespace

std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& files) {
  constexpr std::uint32_t kDosDate = (0u << 9) | (1u << 5) | 1u;  // 1980-01-01
  if (files.size() >= 0xFFFFu) throw std::invalid_argument("zip: too many files");
  std::string out, central;
  for (const auto& [name, data] : files) {
    if (name.empty() || name.front() == '/' || name.find("..") != std::string::npos)
      throw std::invalid_argument("zip: bad member name '" + name + "'");
    if (data.size() >= 0xFFFFFFFFu || out.size() + data.size() >= 0xFFFFFFFFu)
      throw std::invalid_argument("zip: archive beyond 4 GB");
    const auto offset = static_cast<std::uint32_t>(out.size());
    const auto crc = static_cast<std::uint32_t>(crc32_of(data));
    const auto size = static_cast<std::uint32_t>(data.size());
    // Local file header.
    put32(out, 0x04034b50u);
    put16(out, 20);  // version needed: 2.0
    put16(out, 0);   // flags
    put16(out, 0);   // method: stored
    put16(out, 0);   // time 00:00
    put16(out, kDosDate);
    put32(out, crc);
    put32(out, size);
    put32(out, size);
    put16(out, static_cast<std::uint32_t>(name.size()));
    put16(out, 0);  // extra field
    out += name;
    out += data;
    // Its central directory entry.
    put32(central, 0x02014b50u);
    put16(central, 0x031E);  // made by: Unix, 3.0
    put16(central, 20);
    put16(central, 0);
    put16(central, 0);
    put16(central, 0);
    put16(central, kDosDate);
    put32(central, crc);
    put32(central, size);
    put32(central, size);
    put16(central, static_cast<std::uint32_t>(name.size()));
    put16(central, 0);               // extra
    put16(central, 0);               // comment
    put16(central, 0);               // disk
    put16(central, 0);               // internal attributes
    put32(central, 0100644u << 16);  // external: a regular file, rw-r--r--
    put32(central, offset);
    central += name;
  }
  const auto central_offset = static_cast<std::uint32_t>(out.size());
  out += central;
  // End of central directory.
  put32(out, 0x06054b50u);
  put16(out, 0);
  put16(out, 0);
  put16(out, static_cast<std::uint32_t>(files.size()));
  put16(out, static_cast<std::uint32_t>(files.size()));
  put32(out, static_cast<std::uint32_t>(central.size()));
  put32(out, central_offset);
  put16(out, 0);
  return out;
}

}  // namespace shudder::io
