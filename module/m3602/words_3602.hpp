#pragma once
// 3602 backplane words and bits, named as in the 3602 manual (shared/spec/manuals/002_...;
// digest MODULES.md section 4). Tables only for now: stepmodctl decodes a 3602's image by these
// names; the 3602 dialect (module and PLC side) will take its constants from them the way
// words_3601.hpp does. Each axis has 8 words at b = 8 * axis; indices below are relative to b.
// 32-bit values are binary splits (digest 2.2). Header-only, ground layer only.
#include <array>
#include <cstdint>

#include "core/bit_table.hpp"

namespace stepmod::module::m3602 {

inline constexpr unsigned kWordsPerAxis = 8;

// Output words per axis, command mode (digest 4.5); configuration mode (4.1): 0/1 configuration
// bits, 2/3 starting speed, 4 homing timeout.
inline constexpr std::array<NamedWord, 8> kOutputWords = {{{0, "Command Bits MSW"},
                                                           {1, "Command Bits LSW"},
                                                           {2, "Target Position MSW"},
                                                           {3, "Target Position LSW"},
                                                           {4, "Programmed Speed MSW"},
                                                           {5, "Programmed Speed LSW"},
                                                           {6, "Acceleration"},
                                                           {7, "Deceleration"}}};

// Input words per axis, command mode (digest 4.9) and configuration mode (4.4: echoes).
inline constexpr std::array<NamedWord, 9> kInputWords = {{{0, "Status Bits MSW"},
                                                          {1, "Status Bits LSW"},
                                                          {2, "Position MSW"},
                                                          {3, "Position LSW"},
                                                          {6, "Capture MSW"},
                                                          {7, "Capture LSW"},
                                                          {2, "Starting Speed MSW"},
                                                          {3, "Starting Speed LSW"},
                                                          {4, "Homing Timeout"}}};

// Configuration bits MSW (digest 4.2; the manual's bit columns were reconstructed there).
// CW/CCW input function: 00 not used, 01 overtravel limit, 10 emergency stop, 11 invalid.
inline constexpr std::array<NamedBit, 9> kConfigMswBits = {{
    {0, "Capture Input Enabled"},
    {1, "External Input Enabled"},
    {2, "Home Input Enabled"},
    {3, "CW Input Function (1 = limit, 2 = E-stop)", 2},
    {5, "CCW Input Function (1 = limit, 2 = E-stop)", 2},
    {7, "Backplane Home Proximity"},
    {10, "Step+Direction Output (0 = CW/CCW)"},
    {14, "Disable Axis"},
    {15, "Configuration Mode"},
}};

// Configuration bits LSW: active level per input, 1 = active high (digest 4.3).
inline constexpr std::array<NamedBit, 5> kConfigLswBits = {{
    {0, "Capture Input Active High"},
    {1, "External Input Active High"},
    {2, "Home Input Active High"},
    {3, "CW Input Active High"},
    {4, "CCW Input Active High"},
}};

// Command bits MSW (digest 4.6).
inline constexpr std::array<NamedBit, 14> kCommandMswBits = {{
    {0, "Absolute Move"},
    {1, "Relative Move"},
    {2, "Hold Move"},
    {3, "Resume Move"},
    {4, "Immediate Stop"},
    {5, "Find Home CW"},
    {6, "Find Home CCW"},
    {7, "Jog CW (Registration CW)"},
    {8, "Jog CCW (Registration CCW)"},
    {9, "Preset Position"},
    {11, "Reset Errors"},
    {12, "Run Blend Move CW"},
    {13, "Run Blend Move CCW"},
    {15, "Configuration Mode"},
}};

// Command bits LSW (digest 4.7).
inline constexpr std::array<NamedBit, 12> kCommandLswBits = {{
    {0, "S-Curve Acceleration (0 = constant)"},
    {1, "Trapezoidal S-Curve (0 = triangular)"},
    {2, "Program Minimum Registration Distance"},
    {4, "Program Blend Move"},
    {5, "Blend Move Data Transmit"},
    {6, "Backplane Home Proximity"},
    {7, "General-Purpose Output"},
    {9, "Absolute Interpolated Coordinates"},
    {10, "Linear Interpolated Move"},
    {11, "Via-Point Circular Move"},
    {12, "CW Circular Move"},
    {13, "CCW Circular Move"},
}};

// Status bits MSW (digest 4.10).
inline constexpr std::array<NamedBit, 16> kStatusMswBits = {{
    {0, "CW Motion"},
    {1, "CCW Motion"},
    {2, "Hold State"},
    {3, "Axis Stopped"},
    {4, "At Home"},
    {5, "Accelerating"},
    {6, "Decelerating"},
    {7, "Move Complete"},
    {8, "Home Invalid"},
    {9, "Invalid Profile"},
    {10, "Position Invalid"},
    {11, "Input Error"},
    {12, "Command Error"},
    {13, "Configuration Error"},
    {14, "Axis Enabled"},
    {15, "Configuration Mode"},
}};

// Status bits LSW (digest 4.11).
inline constexpr std::array<NamedBit, 11> kStatusLswBits = {{
    {0, "Capture Input Active"},
    {1, "External Input Active"},
    {2, "Home Input Active"},
    {3, "CW Input Active"},
    {4, "CCW Input Active"},
    {8, "Blend Move Running"},
    {9, "Blend Block Acknowledge"},
    {10, "Min. Registration Distance Set"},
    {11, "Interpolated Move Running"},
    {12, "Backplane Home Proximity Echo"},
    {13, "General-Purpose Output"},
}};

}  // namespace stepmod::module::m3602
