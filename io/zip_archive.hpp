#pragma once
// A zip archive (PKWARE APPNOTE 6.3, the format an FMU is) of files stored uncompressed, in
// memory: local headers, data, central directory. Method 0 (stored) is what every unzip and FMI
// tool reads; the FMU's largest member, the shared library, barely compresses anyway. Times are
// fixed (1980-01-01 00:00) so the same inputs give the same bytes. Files only (directories are
// implied by the names); names use '/' and must be relative. No ZIP64: < 4 GB, < 65535 files.
#include <string>
#include <utility>
#include <vector>

namespace shudder::io {

/// (name in the archive, contents) -> the archive's bytes. std::invalid_argument for a name
/// that is empty, absolute or holds "..", or an archive beyond the limits above.
std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& files);

/// CRC-32 (IEEE 802.3, the zip checksum) of `data`.
unsigned long crc32_of(const std::string& data);

}  // namespace shudder::io
