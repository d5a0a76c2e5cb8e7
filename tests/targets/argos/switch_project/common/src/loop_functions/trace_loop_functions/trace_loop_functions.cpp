#include "trace_loop_functions.h"

#include <argos3/plugins/robots/e-puck/simulator/epuck_entity.h>
#include <utility/robot_log.h>

/****************************************/
/****************************************/

void CTraceLoopFunctions::Init(TConfigurationNode& t_tree) {
    std::string strTrace;
    GetNodeAttribute(t_tree, "trace", strTrace);
    m_cTrace.open(strTrace, std::ios::out | std::ios::trunc);
}

/****************************************/
/****************************************/

void CTraceLoopFunctions::PostStep() {
    CSpace::TMapPerType& cEPucks = GetSpace().GetEntitiesByType("e-puck");
    for(auto it = cEPucks.begin(); it != cEPucks.end(); ++it) {
        CEPuckEntity& cEPuck = *any_cast<CEPuckEntity*>(it->second);
        m_cTrace << GetSpace().GetSimulationClock() << " " << cEPuck.GetId() << " "
                 << FormatPosition(cEPuck.GetEmbodiedEntity().GetOriginAnchor().Position) << std::endl;
    }
}

/****************************************/
/****************************************/

void CTraceLoopFunctions::PostExperiment() {
    CSpace::TMapPerType& cEPucks = GetSpace().GetEntitiesByType("e-puck");
    for(auto it = cEPucks.begin(); it != cEPucks.end(); ++it) {
        CEPuckEntity& cEPuck = *any_cast<CEPuckEntity*>(it->second);
        LOG << "summary " << cEPuck.GetId() << " "
            << FormatPosition(cEPuck.GetEmbodiedEntity().GetOriginAnchor().Position) << std::endl;
    }
}

/****************************************/
/****************************************/

REGISTER_LOOP_FUNCTIONS(CTraceLoopFunctions, "trace_loop_functions")
