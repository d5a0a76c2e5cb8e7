// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/utility/math/range.h>.
// Compile-only; link against a real ARGoS install.
#ifndef ARGOS_RANGE_H
#define ARGOS_RANGE_H

namespace argos {
template <typename T>
class CRange {
public:
    CRange(const T& t_min, const T& t_max);
    const T& GetMin() const;
    const T& GetMax() const;
};
}  // namespace argos

#endif
