#include "leader.h"

#include <argos3/core/utility/configuration/argos_configuration.h>
#include <argos3/core/utility/logging/argos_log.h>

/****************************************/
/****************************************/

CLeader::CLeader() :
    m_pcWheels(NULL),
    m_pcPosition(NULL),
    m_pcRNG(NULL),
    sct(NULL),
    m_bMoving(false),
    m_unStep(0),
    m_unAnswered(0) {}

/****************************************/
/****************************************/

CLeader::~CLeader() {
    delete sct;
}

/****************************************/
/****************************************/

void CLeader::Init(TConfigurationNode& t_node) {
    m_pcWheels   = GetActuator<CCI_DifferentialSteeringActuator>("differential_steering");
    m_pcPosition = GetSensor  <CCI_PositioningSensor           >("positioning"          );
    m_pcRNG      = CRandom::CreateRNG("argos");

    GetNodeAttribute(GetNode(t_node, "SCT"), "path", m_strSCTPath);

    /* Init SCT controller */
    sct = new SCTPub(m_strSCTPath);

    /* Register controllable events */
    sct->add_callback(this, sct->events["EV_start"],    &CLeader::Callback_Start,    NULL, NULL);
    sct->add_callback(this, sct->events["EV_stop"],     &CLeader::Callback_Stop,     NULL, NULL);
    sct->add_callback(this, sct->events["EV_respond"],  &CLeader::Callback_Respond,  NULL, NULL);
    sct->add_callback(this, sct->events["EV_message"],  &CLeader::Callback_Message,  NULL, NULL);
    sct->add_callback(this, sct->events["EV_exchange"], &CLeader::Callback_Exchange, NULL, NULL);

    /* Register uncontrollable events */
    sct->add_callback(this, sct->events["EV_pressStart"],     NULL, &CLeader::Check_PressStart,     NULL);
    sct->add_callback(this, sct->events["EV_pressStop"],      NULL, &CLeader::Check_PressStop,      NULL);
    sct->add_callback(this, sct->events["EV__requestL"],      NULL, &CLeader::Check__RequestL,      NULL);
    sct->add_callback(this, sct->events["EV_inputMessage"],   NULL, &CLeader::Check_InputMessage,   NULL);
    sct->add_callback(this, sct->events["EV_inputExchange"],  NULL, &CLeader::Check_InputExchange,  NULL);
}

/****************************************/
/****************************************/

void CLeader::ControlStep() {
    m_unStep++;
    m_strCalls = "";

    /* A worker asks for the leader now and then */
    if(m_pcRNG->Uniform(CRange<UInt32>(0, 10)) < 3)
        m_queRequests.push(m_unStep);

    sct->run_step();

    if(m_bMoving) {
        Real fTurn = m_pcRNG->Uniform(CRange<Real>(-1, 1));
        m_pcWheels->SetLinearVelocity(5 - 2 * fTurn, 5 + 2 * fTurn);
    } else {
        m_pcWheels->SetLinearVelocity(0, 0);
    }
    LOG << "step " << GetId() << " " << m_unStep << " " << sct->get_current_state_string() << m_strCalls
        << " waiting=" << m_queRequests.size() << " answered=" << m_unAnswered << std::endl;
}

/****************************************/
/****************************************/

void CLeader::Callback_Start(void* data)    { m_strCalls += " start";    m_bMoving = true; }
void CLeader::Callback_Stop(void* data)     { m_strCalls += " stop";     m_bMoving = false; }
void CLeader::Callback_Message(void* data)  { m_strCalls += " message"; }
void CLeader::Callback_Exchange(void* data) { m_strCalls += " exchange"; }

void CLeader::Callback_Respond(void* data) {
    m_strCalls += " respond";
    if(!m_queRequests.empty()) {
        m_queRequests.pop();
        m_unAnswered++;
    }
}

/****************************************/
/****************************************/

unsigned char CLeader::Check_PressStart(void* data) { m_strCalls += " ?pressStart"; return m_unStep % 40 == 5; }
unsigned char CLeader::Check_PressStop(void* data)  { m_strCalls += " ?pressStop";  return m_unStep % 40 == 30; }

unsigned char CLeader::Check__RequestL(void* data) {
    m_strCalls += " ?_requestL";
    return !m_queRequests.empty();
}

unsigned char CLeader::Check_InputMessage(void* data) {
    m_strCalls += " ?inputMessage";
    const CVector3& cPosition = m_pcPosition->GetReading().Position;
    return cPosition.GetX() * cPosition.GetX() + cPosition.GetY() * cPosition.GetY() > 0.36;
}

unsigned char CLeader::Check_InputExchange(void* data) {
    m_strCalls += " ?inputExchange";
    return m_queRequests.size() > 2;
}

/****************************************/
/****************************************/

REGISTER_CONTROLLER(CLeader, "leader_controller")
