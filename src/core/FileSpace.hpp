#pragma once
#include <cstdint>
#include <string>

namespace rondel {

// Reserves `bytes` for the file at `path` (creating it, keeping what it holds; Linux fallocate): "" when
// reserved, or when the file system cannot reserve space (nothing is known in advance then); otherwise why
// not, with the space needed and the space free ("No space left on device (it needs about 2.1 MB; 0.4 MB
// free)"). `injected`: fail as a full disk would (core/FaultInjection.hpp).
std::string reserve_file_space(const std::string& path, std::uint64_t bytes, bool injected = false);

}  // namespace rondel
