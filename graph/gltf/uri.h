// URI references as glTF stores them (glTF 2.0 sec. 3.3 "URIs": RFC 3986 references, so a file
// name with spaces, '#' or '%' must be percent-encoded).
#pragma once

#include <string>
#include <string_view>

namespace lamina::gltf {

// A relative URI reference naming the file `name` (no directories): every byte but RFC 3986's
// unreserved characters (letters, digits, '-', '.', '_', '~') as %XX. '+' is encoded too, since
// some readers decode it as a space (form encoding).
std::string uri_encode(std::string_view name);

// The file name a URI reference stands for: each %XX decoded, everything else kept ('+' too). A
// '%' not followed by two hex digits stays as it is.
std::string uri_decode(std::string_view uri);

}  // namespace lamina::gltf
