// A tiny built-in 5x7 pixel font (digits, capitals, a few signs) for labels drawn in the image:
// text becomes one small square per lit pixel, so it needs no texture and no font file.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace weir {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;
constexpr int kGlyphAdvance = 6;  // glyph width plus one column of space

// Rows top to bottom, bit 4 the leftmost column. Lower case maps to upper case; characters the
// font lacks draw as '?'.
const std::array<std::uint8_t, kGlyphHeight>& glyphRows(char c);

// Width in pixels of text drawn at integer `scale`.
int textWidth(const std::string& text, int scale);

// Appends two triangles (12 floats of x, y) per lit pixel of the text, whose top-left corner is at
// (x, top) in pixel coordinates with y growing upwards (so rows go down from `top`).
void appendTextTriangles(const std::string& text, float x, float top, int scale,
                         std::vector<float>& xy);

}  // namespace weir
