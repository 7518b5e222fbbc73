// Bytes toml++ must not see. Debian 12's toml++ 3.3.0 reaches __builtin_unreachable (undefined
// behaviour: a crash or worse) on a non-ASCII character outside a string or comment, e.g. in a bare
// key (marzer/tomlplusplus issue #295, fixed upstream after 3.3.0). Found by tests/fuzz.
#pragma once

#include <string_view>

namespace fogradar::experiment::detail {

// Throws InvalidParameter (field "toml") "<source_name>:<line>: ..." for the first byte >= 0x80
// outside a string or comment, and for the first invalid UTF-8 sequence anywhere (TOML is UTF-8).
void require_toml_safe_bytes(std::string_view text, std::string_view source_name);

}  // namespace fogradar::experiment::detail
