// Names a client gives (upload and scenario names, Content-Type values, paths in messages) made safe to
// echo in a message or a file name.
#pragma once
#include <string>

namespace iarap::serve {

// name reduced to [A-Za-z0-9._-] (at most 64 characters; "mesh" when nothing is left).
std::string safe_label(const std::string& name);
// safe_label(name) without its extension, for a download's file name.
std::string file_stem(const std::string& name);
// The extension after the last '.', lower-cased ("" without one).
std::string lower_extension(const std::string& name);

} // namespace iarap::serve
