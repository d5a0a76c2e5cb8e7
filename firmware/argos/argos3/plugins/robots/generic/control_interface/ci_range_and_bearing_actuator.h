// DECLARATION-ONLY stand-in for ARGoS 3's
// <argos3/plugins/robots/generic/control_interface/ci_range_and_bearing_actuator.h>.
// Compile-only; link against a real ARGoS install.
#ifndef ARGOS_CI_RANGE_AND_BEARING_ACTUATOR_H
#define ARGOS_CI_RANGE_AND_BEARING_ACTUATOR_H

#include <cstddef>

#include <argos3/core/utility/datatypes/byte_array.h>

namespace argos {
class CCI_RangeAndBearingActuator {
public:
    virtual ~CCI_RangeAndBearingActuator();
    size_t GetSize() const;
    void SetData(const CByteArray& c_data);
    void SetData(size_t un_idx, UInt8 un_value);
    void ClearData();
};
}  // namespace argos

#endif
