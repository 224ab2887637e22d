#pragma once
// 3202 backplane words and bits, named as in the 3202 manual (shared/spec/manuals/003_...;
// digest MODULES.md section 5). Tables only for now: stepmodctl decodes a 3202's image by these
// names; the 3202 dialect (module and PLC side) will take its constants from them the way
// words_3601.hpp does. Each channel has 8 DINTs at b = 8 * channel; indices below are relative
// to b. Values are native 32-bit integers (digest 2.3). Header-only, ground layer only.
#include <array>
#include <cstdint>

#include "core/bit_table.hpp"

namespace stepmod::module::m3202 {

inline constexpr unsigned kWordsPerChannel = 8;

// Output DINTs per channel, command mode (digest 5.4); configuration mode (5.1): 0 configuration
// bits, 1 starting speed.
inline constexpr std::array<NamedWord, 5> kOutputWords = {{{0, "Command Word"},
                                                           {1, "Target Position"},
                                                           {2, "Programmed Speed"},
                                                           {3, "Acceleration"},
                                                           {4, "Deceleration"}}};

// Input DINTs per channel, command mode (digest 5.6) and configuration mode (5.3).
inline constexpr std::array<NamedWord, 6> kInputWords = {{{0, "Status Word"},
                                                          {1, "Position"},
                                                          {2, "Encoder"},
                                                          {3, "Capture"},
                                                          {1, "Starting Speed"},
                                                          {3, "Firmware Revision"}}};

// Configuration bits (digest 5.2).
inline constexpr std::array<NamedBit, 19> kConfigBits = {{
    {0, "Capture Input Used"},
    {1, "External Input Used"},
    {2, "Home Input Used"},
    {3, "E-Stop Input Used"},
    {4, "CW Limit Used"},
    {5, "CCW Limit Used"},
    {6, "Backplane Home Proximity"},
    {8, "Quadrature Encoder"},
    {9, "Diagnostic Feedback"},
    {10, "Step+Direction Output (0 = CW/CCW)"},
    {12, "Marker Homing (0 = home switch)"},
    {16, "Capture Input Active High"},
    {17, "External Input Active High"},
    {18, "Home Input Active High"},
    {19, "E-Stop Input Active High"},
    {20, "CW Limit Active High"},
    {21, "CCW Limit Active High"},
    {28, "Disable Channel"},
    {31, "Configuration Mode"},
}};

// Configuration-mode echo (digest 5.3): the configuration bits except these.
inline constexpr std::array<NamedBit, 4> kConfigEchoBits = {{
    {13, "Configuration Error"},
    {28, "Channel Disabled"},
    {30, "Module OK"},
    {31, "Configuration Mode"},
}};

// Command word (digest 5.5).
inline constexpr std::array<NamedBit, 19> kCommandBits = {{
    {0, "Absolute Move"},
    {1, "Relative Move"},
    {2, "Hold Move"},
    {3, "Resume Move"},
    {4, "Immediate Stop"},
    {5, "Find Home CW"},
    {6, "Find Home CCW"},
    {7, "Manual Move CW"},
    {8, "Manual Move CCW"},
    {9, "Preset Position"},
    {10, "Preset Encoder"},
    {11, "Reset Errors"},
    {12, "Run Blend Move CW"},
    {13, "Run Blend Move CCW"},
    {16, "S-Curve Acceleration (0 = constant)"},
    {17, "Trapezoidal S-Curve (0 = triangular)"},
    {18, "Encoder Move"},
    {29, "Backplane Home Proximity"},
    {31, "Configuration Mode"},
}};

// Status word (digest 5.7). Note Home Invalid and Invalid Profile sit at bits 14/15 here, not
// at 8/9 as on the 3601/3602.
inline constexpr std::array<NamedBit, 25> kStatusBits = {{
    {0, "Moving CW"},
    {1, "Moving CCW"},
    {2, "Hold State"},
    {3, "Stopped"},
    {4, "At Home"},
    {5, "Accelerating"},
    {6, "Decelerating"},
    {7, "Move Complete"},
    {8, "Blend Move Running"},
    {10, "Position Invalid"},
    {11, "Input Error"},
    {12, "Command Error"},
    {13, "Configuration Error"},
    {14, "Home Invalid"},
    {15, "Invalid Profile"},
    {16, "Capture Input Active"},
    {17, "External Input Active"},
    {18, "Home Input Active"},
    {19, "E-Stop Input Active"},
    {20, "CW Limit Active"},
    {21, "CCW Limit Active"},
    {28, "Channel Disabled"},
    {29, "Backplane Home Proximity Echo"},
    {30, "Module OK"},
    {31, "Configuration Mode"},
}};

}  // namespace stepmod::module::m3202
