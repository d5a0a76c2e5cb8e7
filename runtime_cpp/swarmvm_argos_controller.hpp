// The part of every generated ARGoS e-puck controller that does not depend on the supervisor:
// reading <params>, building the VM, one VM step per control step, range-and-bearing messages,
// reset and report. A generated `{name}_base.h` derives from it and binds the supervisor's
// events by name; the user's controller derives from that and writes the checks and actions.
//
// <params> of the controller in the .argos file (every element optional):
//   <SCT path="x.svm"/>   a table image (or a supervisor.yaml with its .svm beside it); without
//                         it the image compiled into the controller runs
//   <options inputs="level" control="after-inputs" policy="uniform" seed="..."
//            seed_per_robot="true" rng="xorshift32|argos"/>     (docs/semantics.md)
//   <wheels speed="5"/>   the speed (cm/s) the skeleton's actions drive at
//   <report trace="..." summary="..." script="..."/>           (swarmvm_argos_report.hpp)
//
// A controller that needs its own set-up or per-step work overrides Init, ControlStep or Reset
// and calls this class's version in it.
#ifndef SWARMVM_ARGOS_CONTROLLER_HPP
#define SWARMVM_ARGOS_CONTROLLER_HPP

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <argos3/core/control_interface/ci_controller.h>
#include <argos3/core/utility/configuration/argos_configuration.h>
#include <argos3/plugins/robots/generic/control_interface/ci_differential_steering_actuator.h>
#include <argos3/plugins/robots/generic/control_interface/ci_range_and_bearing_actuator.h>
#include <argos3/plugins/robots/generic/control_interface/ci_range_and_bearing_sensor.h>

#include "swarmvm_argos.hpp"
#include "swarmvm_argos_report.hpp"

namespace swarmvm {

using argos::CARGoSException;   // THROW_ARGOSEXCEPTION names it unqualified

class ArgosController : public argos::CCI_Controller {
public:
    void Init(argos::TConfigurationNode& t_node) override {
        m_pcWheels = GetActuator<argos::CCI_DifferentialSteeringActuator>("differential_steering");
        m_pcRABAct = GetActuator<argos::CCI_RangeAndBearingActuator>("range_and_bearing");
        m_pcRABSens = GetSensor<argos::CCI_RangeAndBearingSensor>("range_and_bearing");
        try {
            Image cImage = ReadImage(t_node);
            Options sOptions = ReadOptions(t_node);
            m_pcVM = std::make_unique<ArgosVM>(std::move(cImage), sOptions, ReadRng(t_node));
            if (argos::NodeExists(t_node, "wheels")) {
                argos::GetNodeAttributeOrDefault(argos::GetNode(t_node, "wheels"), "speed", m_fSpeed, m_fSpeed);
            }
            BindEvents(*m_pcVM);
            m_cReport.init(t_node, GetId(), *m_pcVM);
        } catch (const std::exception& ex) {
            THROW_ARGOSEXCEPTION(m_strName << ": " << ex.what());
        }
        Reset();
    }

    // One VM step: the messages heard, the checks polled, at most one action (which may send).
    // A check or action that throws stops the experiment with an ARGoS error naming the
    // controller, the robot, the event and the callback (swarmvm::CallbackError); the step is
    // not reported, and the VM is left as its policy says (docs/semantics.md).
    void ControlStep() override {
        ReadMessages();
        m_pcRABAct->ClearData();   // a message is broadcast for one control step
        try {
            m_cReport.record(*m_pcVM, m_pcVM->step());
        } catch (const CallbackError& ex) {
            THROW_ARGOSEXCEPTION(m_strName << " on robot " << GetId() << ": " << ex.what());
        }
    }

    void Reset() override {
        m_pcVM->reset();
        m_cReport.reset();
        m_vecHeard.clear();
        m_pcRABAct->ClearData();
        m_pcWheels->SetLinearVelocity(0.0, 0.0);
    }

    void Destroy() override {
        if (m_pcVM) m_cReport.finish(*m_pcVM);
        m_pcVM.reset();
    }

protected:
    // `image` is the table image compiled in (kept, not copied); `name` prefixes errors.
    ArgosController(const unsigned char* image, std::size_t size, std::string name)
        : m_pucImage(image), m_unImageSize(size), m_strName(std::move(name)) {}

    // Binds every check and action of the supervisor's events, by name.
    virtual void BindEvents(ArgosVM& vm) = 0;

    // Was a message with this code heard in this control step?
    bool Heard(std::uint16_t un_code) const {
        return std::find(m_vecHeard.begin(), m_vecHeard.end(), un_code) != m_vecHeard.end();
    }

    // Broadcasts a message code for one control step (the first two bytes of the packet).
    void Send(std::uint16_t un_code) {
        m_pcRABAct->SetData(0, static_cast<argos::UInt8>(un_code & 0xFFu));
        m_pcRABAct->SetData(1, static_cast<argos::UInt8>(un_code >> 8));
    }

    ArgosVM& VM() { return *m_pcVM; }

    argos::CCI_DifferentialSteeringActuator* m_pcWheels = nullptr;
    argos::CCI_RangeAndBearingActuator* m_pcRABAct = nullptr;
    argos::CCI_RangeAndBearingSensor* m_pcRABSens = nullptr;
    argos::Real m_fSpeed = 5.0;   // wheel speed, cm/s

private:
    Image ReadImage(argos::TConfigurationNode& t_node) const {
        std::string strPath;
        if (argos::NodeExists(t_node, "SCT")) {
            argos::GetNodeAttribute(argos::GetNode(t_node, "SCT"), "path", strPath);
        }
        return strPath.empty() ? Image::parse(m_pucImage, m_unImageSize) : Image::load(image_path_for(strPath));
    }

    // The experiment's random_seed drives the VM seed unless <options seed> gives one.
    Options ReadOptions(argos::TConfigurationNode& t_node) const {
        std::string strInputs = "level", strControl = "after-inputs", strPolicy = "uniform";
        argos::UInt32 unSeed = argos::CRandom::GetSeedOf("argos");
        bool bSeedPerRobot = true;
        if (argos::NodeExists(t_node, "options")) {
            argos::TConfigurationNode& tOptions = argos::GetNode(t_node, "options");
            argos::GetNodeAttributeOrDefault(tOptions, "inputs", strInputs, strInputs);
            argos::GetNodeAttributeOrDefault(tOptions, "control", strControl, strControl);
            argos::GetNodeAttributeOrDefault(tOptions, "policy", strPolicy, strPolicy);
            argos::GetNodeAttributeOrDefault(tOptions, "seed", unSeed, unSeed);
            argos::GetNodeAttributeOrDefault(tOptions, "seed_per_robot", bSeedPerRobot, bSeedPerRobot);
        }
        Options sOptions;
        sOptions.inputs = parse_inputs(strInputs);
        sOptions.control = parse_control(strControl);
        sOptions.policy = parse_policy(strPolicy);
        sOptions.seed = bSeedPerRobot ? robot_seed(unSeed, GetId()) : unSeed;
        return sOptions;
    }

    static ArgosRng ReadRng(argos::TConfigurationNode& t_node) {
        std::string strRng = "xorshift32";
        if (argos::NodeExists(t_node, "options")) {
            argos::GetNodeAttributeOrDefault(argos::GetNode(t_node, "options"), "rng", strRng, strRng);
        }
        if (strRng == "argos") return ArgosRng(argos::CRandom::CreateRNG("argos"));
        if (strRng != "xorshift32") {
            THROW_ARGOSEXCEPTION("rng must be xorshift32 or argos, not '" << strRng << "'");
        }
        return ArgosRng();
    }

    void ReadMessages() {
        m_vecHeard.clear();
        for (const argos::CCI_RangeAndBearingSensor::SPacket& sPacket : m_pcRABSens->GetReadings()) {
            if (sPacket.Data.Size() < 2) continue;
            const auto unCode = static_cast<std::uint16_t>(sPacket.Data[0] | (sPacket.Data[1] << 8));
            if (unCode != 0) m_vecHeard.push_back(unCode);
        }
    }

    const unsigned char* m_pucImage;
    std::size_t m_unImageSize;
    std::string m_strName;
    std::unique_ptr<ArgosVM> m_pcVM;
    ArgosReport m_cReport;
    std::vector<std::uint16_t> m_vecHeard;   // message codes heard this control step
};

}  // namespace swarmvm

#endif  // SWARMVM_ARGOS_CONTROLLER_HPP
