// DECLARATION-ONLY stand-in for ARGoS 3's
// <argos3/plugins/robots/generic/control_interface/ci_differential_steering_actuator.h>.
// Compile-only; link against a real ARGoS install.
#ifndef ARGOS_CI_DIFFERENTIAL_STEERING_ACTUATOR_H
#define ARGOS_CI_DIFFERENTIAL_STEERING_ACTUATOR_H

#include <argos3/core/utility/datatypes/datatypes.h>

namespace argos {
class CCI_DifferentialSteeringActuator {
public:
    virtual ~CCI_DifferentialSteeringActuator();
    // Wheel speeds in cm/s.
    virtual void SetLinearVelocity(Real f_left_velocity, Real f_right_velocity) = 0;
};
}  // namespace argos

#endif
