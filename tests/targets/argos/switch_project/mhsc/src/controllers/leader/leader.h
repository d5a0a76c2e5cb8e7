#ifndef LEADER_H
#define LEADER_H

/* A leader of the multi-human swarm control study's kind: an operator starts and stops it, it
 * answers the requests of its workers and exchanges messages, as its supervisor allows (the
 * variant of sct.h with callbacks by event index). Like the published controllers, it uses
 * std::queue from what sct.h includes. */

#include <argos3/core/control_interface/ci_controller.h>
#include <argos3/plugins/robots/generic/control_interface/ci_differential_steering_actuator.h>
#include <argos3/plugins/robots/generic/control_interface/ci_positioning_sensor.h>
#include <utility/sct.h>

using namespace argos;

class CLeader : public CCI_Controller {

public:

    CLeader();
    virtual ~CLeader();

    virtual void Init(TConfigurationNode& t_node);
    virtual void ControlStep();
    virtual void Reset() {}
    virtual void Destroy() {}

private:

    /* Callbacks of the controllable events */
    void Callback_Start(void* data);
    void Callback_Stop(void* data);
    void Callback_Respond(void* data);
    void Callback_Message(void* data);
    void Callback_Exchange(void* data);

    /* Checks of the uncontrollable events */
    unsigned char Check_PressStart(void* data);
    unsigned char Check_PressStop(void* data);
    unsigned char Check__RequestL(void* data);
    unsigned char Check_InputMessage(void* data);
    unsigned char Check_InputExchange(void* data);

    CCI_DifferentialSteeringActuator* m_pcWheels;
    CCI_PositioningSensor* m_pcPosition;
    CRandom::CRNG* m_pcRNG;

    std::string m_strSCTPath;
    SCT* sct;

    bool m_bMoving;
    UInt32 m_unStep;
    UInt32 m_unAnswered;
    std::queue<UInt32> m_queRequests;
    std::string m_strCalls;

};

#endif
