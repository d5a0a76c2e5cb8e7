// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/utility/datatypes/datatypes.h>.
// swarmvm ships it only so that generated controllers can be compiled (not linked) where ARGoS
// is not installed; build against a real ARGoS install for anything else.
#ifndef ARGOS_DATATYPES_H
#define ARGOS_DATATYPES_H

#include <cstdint>

namespace argos {
typedef double Real;
typedef std::uint8_t UInt8;
typedef std::uint16_t UInt16;
typedef std::uint32_t UInt32;
typedef std::int32_t SInt32;
}  // namespace argos

#endif
