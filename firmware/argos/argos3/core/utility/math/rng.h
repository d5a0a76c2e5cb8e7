// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/utility/math/rng.h> (CRandom::CRNG,
// the simulator's seeded random streams). Compile-only; link against a real ARGoS install.
#ifndef ARGOS_RNG_H
#define ARGOS_RNG_H

#include <string>

#include <argos3/core/utility/datatypes/datatypes.h>
#include <argos3/core/utility/math/range.h>

namespace argos {
class CRandom {
public:
    class CRNG {
    public:
        UInt32 Uniform(const CRange<UInt32>& c_range);
        Real Uniform(const CRange<Real>& c_range);
    };
    static CRNG* CreateRNG(const std::string& str_category);
};
}  // namespace argos

#endif
