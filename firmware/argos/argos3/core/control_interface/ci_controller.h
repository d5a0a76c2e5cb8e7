// DECLARATION-ONLY stand-in for ARGoS 3's <argos3/core/control_interface/ci_controller.h>.
// REGISTER_CONTROLLER here only checks the class at compile time; the real macro registers it
// with ARGoS's plugin factory. Compile-only; link against a real ARGoS install.
#ifndef ARGOS_CI_CONTROLLER_H
#define ARGOS_CI_CONTROLLER_H

#include <string>
#include <type_traits>

#include <argos3/core/utility/configuration/argos_configuration.h>

namespace argos {
class CCI_Controller {
public:
    virtual ~CCI_Controller();
    virtual void Init(TConfigurationNode& t_node) = 0;
    virtual void ControlStep() = 0;
    virtual void Reset();
    virtual void Destroy();
    const std::string& GetId() const;
    template <typename ACTUATOR_IMPL>
    ACTUATOR_IMPL* GetActuator(const std::string& str_actuator_type);
    template <typename SENSOR_IMPL>
    SENSOR_IMPL* GetSensor(const std::string& str_sensor_type);
};
}  // namespace argos

#define REGISTER_CONTROLLER(CLASSNAME, LABEL) \
    static_assert(std::is_base_of<argos::CCI_Controller, CLASSNAME>::value, LABEL " must derive from CCI_Controller");

#endif
