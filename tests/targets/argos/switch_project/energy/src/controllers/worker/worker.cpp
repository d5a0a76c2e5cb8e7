#include "worker.h"

#include <argos3/core/utility/configuration/argos_configuration.h>
#include <argos3/core/utility/logging/argos_log.h>

/****************************************/
/****************************************/

CWorker::CWorker() :
    m_pcWheels(NULL),
    m_pcPosition(NULL),
    m_pcRNG(NULL),
    sct(NULL),
    m_fEnergy(75),
    m_fDirection(0),
    m_unStep(0) {}

/****************************************/
/****************************************/

CWorker::~CWorker() {
    delete sct;
}

/****************************************/
/****************************************/

void CWorker::Init(TConfigurationNode& t_node) {
    m_pcWheels   = GetActuator<CCI_DifferentialSteeringActuator>("differential_steering");
    m_pcPosition = GetSensor  <CCI_PositioningSensor           >("positioning"          );
    m_pcRNG      = CRandom::CreateRNG("argos");

    GetNodeAttribute(GetNode(t_node, "SCT"), "path", m_strSCTPath);

    /* Init SCT controller */
    sct = new SCT(m_strSCTPath);

    /* Register controllable events */
    sct->add_callback(this, std::string("EV_moveToWork"),   &CWorker::Callback_MoveToWork,   NULL, NULL);
    sct->add_callback(this, std::string("EV_work"),         &CWorker::Callback_Work,         NULL, NULL);
    sct->add_callback(this, std::string("EV_moveToCharge"), &CWorker::Callback_MoveToCharge, NULL, NULL);
    sct->add_callback(this, std::string("EV_charge"),       &CWorker::Callback_Charge,       NULL, NULL);

    /* Register uncontrollable events */
    sct->add_callback(this, std::string("EV_highEnergy"),   NULL, &CWorker::Check_HighEnergy,   NULL);
    sct->add_callback(this, std::string("EV_lowEnergy"),    NULL, &CWorker::Check_LowEnergy,    NULL);
    sct->add_callback(this, std::string("EV_atWork"),       NULL, &CWorker::Check_AtWork,       NULL);
    sct->add_callback(this, std::string("EV_notAtWork"),    NULL, &CWorker::Check_NotAtWork,    NULL);
    sct->add_callback(this, std::string("EV_atCharger"),    NULL, &CWorker::Check_AtCharger,    NULL);
    sct->add_callback(this, std::string("EV_notAtCharger"), NULL, &CWorker::Check_NotAtCharger, NULL);
}

/****************************************/
/****************************************/

void CWorker::ControlStep() {
    m_unStep++;
    m_strCalls = "";
    sct->run_step();
    DriveTowards(m_fDirection);
    m_fEnergy -= 0.15;
    LOG << "step " << GetId() << " " << m_unStep << " " << sct->get_current_state_string() << m_strCalls
        << " energy=" << m_fEnergy << std::endl;
}

/****************************************/
/****************************************/

void CWorker::DriveTowards(Real f_direction) {
    if(f_direction == 0) {
        m_pcWheels->SetLinearVelocity(0, 0);
        return;
    }
    CRadians cZ, cY, cX;
    m_pcPosition->GetReading().Orientation.ToEulerAngles(cZ, cY, cX);
    CRadians cGoal = f_direction > 0 ? CRadians::ZERO : CRadians::PI;
    Real fTurn = (cGoal - cZ).SignedNormalize().GetValue() + m_pcRNG->Uniform(CRange<Real>(-0.2, 0.2));
    m_pcWheels->SetLinearVelocity(8 - 4 * fTurn, 8 + 4 * fTurn);
}

/****************************************/
/****************************************/

void CWorker::Callback_MoveToWork(void* data)   { m_strCalls += " moveToWork";   m_fDirection = 1; }
void CWorker::Callback_Work(void* data)         { m_strCalls += " work";         m_fDirection = 0; m_fEnergy -= 25; }
void CWorker::Callback_MoveToCharge(void* data) { m_strCalls += " moveToCharge"; m_fDirection = -1; }
void CWorker::Callback_Charge(void* data)       { m_strCalls += " charge";       m_fDirection = 0; m_fEnergy = 95; }

/****************************************/
/****************************************/

unsigned char CWorker::Check_HighEnergy(void* data)   { m_strCalls += " ?highEnergy";   return m_fEnergy > 70; }
unsigned char CWorker::Check_LowEnergy(void* data)    { m_strCalls += " ?lowEnergy";    return m_fEnergy < 30; }
unsigned char CWorker::Check_AtWork(void* data)       { m_strCalls += " ?atWork";       return m_pcPosition->GetReading().Position.GetX() > 0.3; }
unsigned char CWorker::Check_NotAtWork(void* data)    { m_strCalls += " ?notAtWork";    return m_pcPosition->GetReading().Position.GetX() <= 0.3; }
unsigned char CWorker::Check_AtCharger(void* data)    { m_strCalls += " ?atCharger";    return m_pcPosition->GetReading().Position.GetX() < -0.3; }
unsigned char CWorker::Check_NotAtCharger(void* data) { m_strCalls += " ?notAtCharger"; return m_pcPosition->GetReading().Position.GetX() >= -0.3; }

/****************************************/
/****************************************/

REGISTER_CONTROLLER(CWorker, "worker_controller")
