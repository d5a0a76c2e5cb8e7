// DECLARATION-ONLY stand-in for ARGoS 3's
// <argos3/plugins/robots/generic/control_interface/ci_range_and_bearing_sensor.h>.
// Compile-only; link against a real ARGoS install.
#ifndef ARGOS_CI_RANGE_AND_BEARING_SENSOR_H
#define ARGOS_CI_RANGE_AND_BEARING_SENSOR_H

#include <vector>

#include <argos3/core/utility/datatypes/byte_array.h>
#include <argos3/core/utility/math/angles.h>

namespace argos {
class CCI_RangeAndBearingSensor {
public:
    struct SPacket {
        Real Range;
        CRadians HorizontalBearing;
        CRadians VerticalBearing;
        CByteArray Data;
    };
    typedef std::vector<SPacket> TReadings;

    virtual ~CCI_RangeAndBearingSensor();
    const TReadings& GetReadings() const;
};
}  // namespace argos

#endif
