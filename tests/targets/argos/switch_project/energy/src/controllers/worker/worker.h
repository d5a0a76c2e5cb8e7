#ifndef WORKER_H
#define WORKER_H

/* A worker of the energy study's kind: it works at one end of the arena and charges at the
 * other, as its supervisor (the default variant of sct.h: callbacks by event name) allows. */

#include <argos3/core/control_interface/ci_controller.h>
#include <argos3/plugins/robots/generic/control_interface/ci_differential_steering_actuator.h>
#include <argos3/plugins/robots/generic/control_interface/ci_positioning_sensor.h>
#include <utility/sct.h>

using namespace argos;

class CWorker : public CCI_Controller {

public:

    CWorker();
    virtual ~CWorker();

    virtual void Init(TConfigurationNode& t_node);
    virtual void ControlStep();
    virtual void Reset() {}
    virtual void Destroy() {}

private:

    /* Callbacks of the controllable events */
    void Callback_MoveToWork(void* data);
    void Callback_Work(void* data);
    void Callback_MoveToCharge(void* data);
    void Callback_Charge(void* data);

    /* Checks of the uncontrollable events */
    unsigned char Check_HighEnergy(void* data);
    unsigned char Check_LowEnergy(void* data);
    unsigned char Check_AtWork(void* data);
    unsigned char Check_NotAtWork(void* data);
    unsigned char Check_AtCharger(void* data);
    unsigned char Check_NotAtCharger(void* data);

    /* Drives towards the work (+1) or charging (-1) end of the arena */
    void DriveTowards(Real f_direction);

    CCI_DifferentialSteeringActuator* m_pcWheels;
    CCI_PositioningSensor* m_pcPosition;
    CRandom::CRNG* m_pcRNG;

    std::string m_strSCTPath;
    SCT* sct;

    Real m_fEnergy;
    Real m_fDirection;
    UInt32 m_unStep;
    std::string m_strCalls;

};

#endif
