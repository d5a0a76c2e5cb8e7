// The benchmark's baseline (benchmarks/energy_study.py): an empty controller on the same robots,
// sensors and loop functions as the study's, so that a trial's time minus this one's is what the
// VM and the application layer cost. It does nothing and never moves.
#include <argos3/core/control_interface/ci_controller.h>
#include <argos3/core/utility/configuration/argos_configuration.h>

#include "energy_agent.h"

class CEnergyIdleController : public argos::CCI_Controller, public energy::Agent {
public:
    void Init(argos::TConfigurationNode& t_node) override {   // the capacity of the robot it stands in for
        if (argos::NodeExists(t_node, "energy")) {
            argos::GetNodeAttributeOrDefault(argos::GetNode(t_node, "energy"), "capacity", m_sBattery.Capacity, 100.0);
        }
        m_sBattery.Energy = m_sBattery.Capacity;
    }
    void ControlStep() override {}
    energy::Role AgentRole() const override { return GetId()[0] == 'c' ? energy::Role::Charger : energy::Role::Worker; }
    std::uint8_t Index() const override { return 0; }
    std::uint8_t Partner() const override { return energy::kNobody; }
    bool Moving() const override { return false; }
    bool Working() const override { return false; }
    bool Serving() const override { return false; }
    energy::Battery& GetBattery() override { return m_sBattery; }

private:
    energy::Battery m_sBattery;
};

REGISTER_CONTROLLER(CEnergyIdleController, "energy_idle_controller")
