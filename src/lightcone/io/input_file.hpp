// Reading a whole input file (a scene, a mesh, an image) safely: only regular files, and no
// more than a stated size, so that a FIFO, a device such as /dev/zero or a huge file ends in a
// clear error instead of a hang or an allocation of gigabytes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace lightcone {

inline constexpr std::uintmax_t kMaxSceneFileBytes = std::uintmax_t{64} << 20;  // 64 MiB
inline constexpr std::uintmax_t kMaxAssetFileBytes = std::uintmax_t{2} << 30;   // 2 GiB

// The file's bytes; throws InputError "FILE: ..." when it is missing, not a regular file, larger
// than max_bytes, or unreadable. `what` names what the file should be ("scene file").
std::string read_input_file(const std::filesystem::path& file, const std::string& what,
                            std::uintmax_t max_bytes);

// The same checks without the throw: the bytes, or nullopt with `reason` saying what is wrong
// ("it is a directory", "it is not a regular file (...)", "N bytes, more than the limit ...").
std::optional<std::string> try_read_input_file(const std::filesystem::path& file,
                                               std::uintmax_t max_bytes, std::string& reason);

}  // namespace lightcone
