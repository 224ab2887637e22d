#pragma once
// The conditions only the 3602's interpolated move has (interpolated_move.cpp), with their items
// of the 3602's Command Error list: the lettered I items (error_reason.hpp: 6x). The conditions
// it shares with single-axis moves (ranges CE-05, Vp < Vs CE-06, absolute with Position Invalid
// CE-07, a move while moving CE-04, the planner's full queue CE-S1) use the shared items
// (module/axis/error_items.hpp). docs/error-reasons.md lists both.
#include <array>

#include "module/axis/error_reason.hpp"

namespace stepmod::module::m3602::items {

using axis::Item;
using L = axis::ErrorList;

// 3602-CE-03: a command MSW bit together with the interpolation bits 9..14.
inline constexpr Item kPathWithCommandBit{
    L::kCommand, {0, 3, 0}, "an MSW command bit with the path bits"};
// 3602-CE-I2 (A46): a command on axis 2 while a path runs (Immediate Stop too: it does not stop
// the path).
inline constexpr Item kPathAxis2Command{
    L::kCommand, {0, 62, 0}, "a command on axis 2 while a path runs"};
// 3602-CE-I3: either axis unconfigured, disabled or in configuration mode.
inline constexpr Item kPathAxesNotReady{
    L::kCommand, {0, 63, 0}, "a path with an axis not ready for it"};
// 3602-CE-I5 / IP-18: reserved words of the block (8, 9, the method's unused ones of 12..15).
inline constexpr Item kPathReserved{
    L::kCommand, {0, 65, 0}, "reserved words of a path block not 0"};
// 3602-CE-I6 (A34): LSW bits 10..14 not one of the manual's methods.
inline constexpr Item kPathPattern{L::kCommand, {0, 66, 0}, "path bits 10..14 name no method"};
// 3602-CE-I7 (A36): a circle the module cannot draw.
inline constexpr Item kPathGeometry{
    L::kCommand, {0, 67, 0}, "a circular path the module cannot draw"};

inline constexpr std::array kAll{&kPathWithCommandBit, &kPathAxis2Command, &kPathAxesNotReady,
                                 &kPathReserved,       &kPathPattern,      &kPathGeometry};

}  // namespace stepmod::module::m3602::items
