// The gate every file a program reads passes through.
//
// A file is read only if it is a regular file (or a link to one), readable, not empty and no
// larger than the bound its caller gives for that kind of input; a FIFO, a device such as
// /dev/zero, a directory or a socket is refused with one line naming it, so no input can
// block a program or be read without end. Decoders then check that what a header promises
// fits the memory budget below before they allocate it.
#pragma once

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <string_view>

namespace shanshui {

// Size bounds for the kinds of input, in bytes.
inline constexpr std::uintmax_t kMaxTextInputBytes = std::uintmax_t{16} << 20;    //!< manifests, shaders, tables
inline constexpr std::uintmax_t kMaxMediaInputBytes = std::uintmax_t{4} << 30;    //!< images, rasters, meshes
inline constexpr std::uintmax_t kMaxSidecarInputBytes = std::uintmax_t{1} << 20;  //!< .prj and similar

//! Throws unless `path` names an existing, readable, non-empty regular file (or a link to
//! one) of at most `max_bytes`: directories, devices, FIFOs and sockets are refused, so an
//! input can never be endless. `what` says what was expected ("an image", "a mesh").
//! Returns the file's size.
std::uintmax_t checkInputFile(const std::filesystem::path& path, std::string_view what,
                              std::uintmax_t max_bytes = kMaxMediaInputBytes);

//! The last file that passed checkInputFile in this process (empty if none): what an
//! allocation failure is most likely about, for its message.
std::string lastInputFile();

//! Reads a whole file that passes checkInputFile(path, what, max_bytes).
std::string readInputFile(const std::filesystem::path& path, std::string_view what, std::uintmax_t max_bytes);

//! Reads a stream to its end (standard input given as '-'), refusing more than `max_bytes`:
//! the bound is checked while reading, so /dev/zero on stdin ends in an error, not in
//! memory exhaustion. `name` and `what` are for messages.
std::string readInputStream(std::FILE* stream, std::string_view name, std::string_view what, std::uintmax_t max_bytes);

// ---- memory budget --------------------------------------------------------------------

//! The most memory one decoded input may take, in bytes. Defaults to half the machine's
//! physical memory, lowered to the address-space limit (ulimit -v) when one is set; the
//! environment variable SHANSHUI_MAX_MEMORY (bytes, or with a K/M/G suffix) or a tool's
//! --max-memory option sets it.
std::uintmax_t memoryBudget();
//! Sets the budget (0 restores the default).
void setMemoryBudget(std::uintmax_t bytes);
//! Parses "512M", "2G", "1048576" (K, M, G, T are powers of 1024); throws naming `source`.
std::uintmax_t parseByteSize(std::string_view text, std::string_view source);

//! " under an address-space limit of N MiB (ulimit -v)" when one is set, else empty: for
//! messages about memory or a driver that fails to start, whose likeliest cause it is.
std::string addressSpaceLimitNote();

//! "512 bytes", "96 KiB", "3.5 MiB", "4.0 GiB": a size for messages. Inline, so the
//! modules loaded at run time (which do not link this library) can use it.
inline std::string byteCount(std::uintmax_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  if (bytes < (std::uintmax_t{1} << 20)) return std::to_string((bytes + 512) >> 10) + " KiB";
  const bool gib = bytes >= (std::uintmax_t{1} << 30);
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %s",
                static_cast<double>(bytes) / static_cast<double>(gib ? 1u << 30 : 1u << 20), gib ? "GiB" : "MiB");
  return text;
}

//! Throws, naming `name`, when `bytes` (what decoding `name` as `what` will allocate,
//! computed from its header) exceeds memoryBudget(). The message says how to raise it.
//! (The image codecs have their own check, which also runs inside the OpenImageIO module.)
void checkMemoryNeed(std::string_view name, std::string_view what, std::uintmax_t bytes);

}  // namespace shanshui
