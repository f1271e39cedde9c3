#pragma once
// Base64 (RFC 4648, with padding): how bytes travel inside JSON and HTML
// (the viewer's pictures and three.js, the recordings' compressed images).
#include <cstddef>
#include <cstdint>
#include <string>

namespace edgevio {

std::string base64(const std::uint8_t* data, std::size_t size);

}  // namespace edgevio
