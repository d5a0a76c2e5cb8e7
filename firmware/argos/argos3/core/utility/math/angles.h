// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/utility/math/angles.h>.
// Compile-only; link against a real ARGoS install.
#ifndef ARGOS_ANGLES_H
#define ARGOS_ANGLES_H

#include <argos3/core/utility/datatypes/datatypes.h>

namespace argos {
class CRadians {
public:
    CRadians();
    Real GetValue() const;
};
}  // namespace argos

#endif
