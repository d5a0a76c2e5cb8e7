// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/utility/datatypes/byte_array.h>
// (the members swarmvm's generated controllers use). Compile-only; link against real ARGoS.
#ifndef ARGOS_BYTE_ARRAY_H
#define ARGOS_BYTE_ARRAY_H

#include <cstddef>

#include <argos3/core/utility/datatypes/datatypes.h>

namespace argos {
class CByteArray {
public:
    CByteArray();
    CByteArray(std::size_t un_size, UInt8 un_value = 0);
    std::size_t Size() const;
    UInt8& operator[](std::size_t un_index);
    const UInt8& operator[](std::size_t un_index) const;
};
}  // namespace argos

#endif
