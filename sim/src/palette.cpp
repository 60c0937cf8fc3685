// The drawing palette of the real game (Tango colours of qt-gui ColorPicker) and the eraser.

#include <array>
#include <optional>
#include <string_view>

#include "freeplay/sim/screen.hpp"

namespace freeplay::sim {
namespace {

struct PaletteEntry {
  PaletteColour colour;
  std::string_view name;
  std::array<unsigned char, 3> rgb;
};

constexpr std::array<PaletteEntry, 9> kEntries = {{
    {PaletteColour::Yellow, "yellow", {0xfc, 0xe9, 0x4f}},
    {PaletteColour::Orange, "orange", {0xfc, 0xaf, 0x3e}},
    {PaletteColour::Green, "green", {0x73, 0xd2, 0x16}},
    {PaletteColour::Black, "black", {0x2e, 0x34, 0x36}},
    {PaletteColour::Blue, "blue", {0x34, 0x65, 0xa4}},
    {PaletteColour::Purple, "purple", {0xad, 0x7f, 0xa8}},
    {PaletteColour::Red, "red", {0xef, 0x29, 0x29}},
    {PaletteColour::White, "white", {0xee, 0xee, 0xec}},
    {PaletteColour::Eraser, "eraser", {0, 0, 0}},
}};

const PaletteEntry& entry(PaletteColour colour) {
  for (const auto& e : kEntries) {
    if (e.colour == colour) return e;
  }
  return kEntries.back();
}

}  // namespace

std::string_view palette_name(PaletteColour colour) { return entry(colour).name; }

std::optional<PaletteColour> palette_from_name(std::string_view name) {
  for (const auto& e : kEntries) {
    if (e.name == name) return e.colour;
  }
  return std::nullopt;
}

std::string_view palette_names() { return "yellow, orange, green, black, blue, purple, red, white, eraser"; }

std::array<unsigned char, 3> palette_rgb(PaletteColour colour) { return entry(colour).rgb; }

}  // namespace freeplay::sim
