// Loop functions of the energy-replenishment study: see energy_loop_functions.h.
#include "energy_loop_functions.h"

#include <algorithm>
#include <cstdio>
#include <map>

#include <argos3/core/simulator/simulator.h>
#include <argos3/plugins/robots/e-puck/simulator/epuck_entity.h>

using namespace argos;

void CEnergyLoopFunctions::Init(TConfigurationNode& t_node) {
    if (NodeExists(t_node, "energy")) {
        TConfigurationNode& tEnergy = GetNode(t_node, "energy");
        GetNodeAttributeOrDefault(tEnergy, "move", m_fMove, m_fMove);
        GetNodeAttributeOrDefault(tEnergy, "work", m_fWork, m_fWork);
        GetNodeAttributeOrDefault(tEnergy, "core", m_fCore, m_fCore);
        GetNodeAttributeOrDefault(tEnergy, "charge", m_fCharge, m_fCharge);
        GetNodeAttributeOrDefault(tEnergy, "transfer", m_fTransfer, m_fTransfer);
        GetNodeAttributeOrDefault(tEnergy, "loss", m_fLoss, m_fLoss);
    }
    if (NodeExists(t_node, "output")) {
        TConfigurationNode& tOutput = GetNode(t_node, "output");
        GetNodeAttributeOrDefault(tOutput, "path", m_strOutput, m_strOutput);
        GetNodeAttributeOrDefault(tOutput, "trace", m_strTrace, m_strTrace);
    }
    std::map<std::string, SRobot> mapRobots;   // in id order, whatever the space's order
    for (auto& cPair : GetSpace().GetEntitiesByType("e-puck")) {
        auto* pcEPuck = any_cast<CEPuckEntity*>(cPair.second);
        auto* pcAgent = dynamic_cast<energy::Agent*>(&pcEPuck->GetControllableEntity().GetController());
        if (pcAgent == nullptr) {
            THROW_ARGOSEXCEPTION("e-puck " << pcEPuck->GetId() << " does not run an energy-study controller");
        }
        mapRobots[pcEPuck->GetId()] = SRobot{pcEPuck->GetId(), pcAgent, &pcEPuck->GetEmbodiedEntity()};
    }
    for (auto& cPair : mapRobots) m_vecRobots.push_back(cPair.second);
    Reset();
}

void CEnergyLoopFunctions::Reset() {
    m_sTotals = STotals();
    if (!m_strTrace.empty()) {
        m_cTrace.close();
        m_cTrace.open(m_strTrace, std::ios::trunc);
        m_cTrace << "step,id,x,y,energy,capacity,moving,working,serving,partner,depleted\n";
    }
}

// Core, moving and working costs; work counted; a robot that reaches zero is depleted.
void CEnergyLoopFunctions::Spend(SRobot& s_robot) {
    energy::Battery& sBattery = s_robot.Agent->GetBattery();
    const bool bWorking = s_robot.Agent->AgentRole() == energy::Role::Worker && s_robot.Agent->Working() &&
                          energy::InStrip(Position(s_robot), energy::kWorkX);
    const double fCost = m_fCore + (s_robot.Agent->Moving() ? m_fMove : 0.0) + (bWorking ? m_fWork : 0.0);
    const double fSpent = std::min(fCost, sBattery.Energy);
    sBattery.Energy -= fSpent;
    m_sTotals.Consumed += fSpent;
    if (bWorking && fSpent >= fCost) {   // the step's work is done only if its energy was there
        m_sTotals.Work += 1;
        m_sTotals.WorkEnergy += m_fWork;
        m_sTotals.WorkXMin = std::min(m_sTotals.WorkXMin, Position(s_robot));
        m_sTotals.WorkXMax = std::max(m_sTotals.WorkXMax, Position(s_robot));
    }
    if (sBattery.Energy <= 0.0) {
        sBattery.Energy = 0.0;
        sBattery.Depleted = true;
    }
}

// A serving charger gives to its worker when they name each other and are within 14 cm: it
// pays the rate, the worker gets rate * (1 - loss), never beyond its capacity.
void CEnergyLoopFunctions::Transfer(SRobot& s_charger) {
    energy::Agent& cCharger = *s_charger.Agent;
    if (!cCharger.Serving() || cCharger.Partner() == energy::kNobody || cCharger.GetBattery().Depleted) return;
    for (SRobot& sWorker : m_vecRobots) {
        energy::Agent& cWorker = *sWorker.Agent;
        if (cWorker.AgentRole() != energy::Role::Worker || cWorker.Index() != cCharger.Partner()) continue;
        if (cWorker.Partner() != cCharger.Index() || cWorker.GetBattery().Depleted) return;
        const CVector3& cA = s_charger.Body->GetOriginAnchor().Position;
        const CVector3& cB = sWorker.Body->GetOriginAnchor().Position;
        if (Distance(cA, cB) > energy::kAtChargerRange) return;
        energy::Battery& sGive = cCharger.GetBattery();
        energy::Battery& sTake = cWorker.GetBattery();
        const double fXi = 1.0 - m_fLoss;
        const double fGiven = std::min({m_fTransfer, sGive.Energy, (sTake.Capacity - sTake.Energy) / fXi});
        sGive.Energy -= fGiven;
        sTake.Energy += fGiven * fXi;
        m_sTotals.Transferred += fGiven;
        m_sTotals.Lost += fGiven * m_fLoss;
        return;
    }
}

void CEnergyLoopFunctions::PostStep() {
    for (SRobot& sRobot : m_vecRobots) {
        if (!sRobot.Agent->GetBattery().Depleted) Spend(sRobot);
    }
    for (SRobot& sRobot : m_vecRobots) {
        energy::Battery& sBattery = sRobot.Agent->GetBattery();
        if (!sBattery.Depleted && energy::InStrip(Position(sRobot), energy::kChargingX)) {
            const double fGain = std::min(m_fCharge, sBattery.Capacity - sBattery.Energy);
            sBattery.Energy += fGain;
            m_sTotals.Charged += fGain;
        }
    }
    for (SRobot& sRobot : m_vecRobots) {
        if (sRobot.Agent->AgentRole() == energy::Role::Charger) Transfer(sRobot);
    }
    const unsigned long unStep = GetSpace().GetSimulationClock();
    for (SRobot& sRobot : m_vecRobots) {
        const energy::Battery& sBattery = sRobot.Agent->GetBattery();
        m_sTotals.MaxFill = std::max(m_sTotals.MaxFill, sBattery.Energy / sBattery.Capacity);
        if (m_cTrace.is_open()) {
            const CVector3& cAt = sRobot.Body->GetOriginAnchor().Position;
            m_cTrace << unStep << ',' << sRobot.Id << ',' << cAt.GetX() << ',' << cAt.GetY() << ',' << sBattery.Energy
                     << ',' << sBattery.Capacity << ',' << sRobot.Agent->Moving() << ',' << sRobot.Agent->Working()
                     << ',' << sRobot.Agent->Serving() << ',' << int(sRobot.Agent->Partner()) << ','
                     << sBattery.Depleted << '\n';
        }
    }
}

// One JSON object: totals, efficiency (work energy over all energy spent or lost), depleted robots.
void CEnergyLoopFunctions::PostExperiment() {
    int nDepletedWorkers = 0, nDepletedChargers = 0, nWorkers = 0, nChargers = 0;
    double fFinal = 0.0;
    for (SRobot& sRobot : m_vecRobots) {
        const bool bWorker = sRobot.Agent->AgentRole() == energy::Role::Worker;
        (bWorker ? nWorkers : nChargers) += 1;
        if (sRobot.Agent->GetBattery().Depleted) (bWorker ? nDepletedWorkers : nDepletedChargers) += 1;
        fFinal += sRobot.Agent->GetBattery().Energy;
    }
    const double fSpent = m_sTotals.Consumed + m_sTotals.Lost;
    if (m_cTrace.is_open()) m_cTrace.close();
    if (m_strOutput.empty()) return;
    std::FILE* pFile = std::fopen(m_strOutput.c_str(), "w");
    if (pFile == nullptr) THROW_ARGOSEXCEPTION("cannot write " << m_strOutput);
    std::fprintf(pFile,
                 "{\"steps\": %lu, \"workers\": %d, \"chargers\": %d, \"work\": %ld, \"work_energy\": %.6f, "
                 "\"consumed\": %.6f, \"lost\": %.6f, \"charged\": %.6f, \"transferred\": %.6f, "
                 "\"final_energy\": %.6f, \"efficiency\": %.6f, \"depleted\": %d, \"depleted_chargers\": %d, "
                 "\"max_fill\": %.6f, \"work_x_min\": %.6f, \"work_x_max\": %.6f}\n",
                 static_cast<unsigned long>(GetSpace().GetSimulationClock()), nWorkers, nChargers, m_sTotals.Work,
                 m_sTotals.WorkEnergy, m_sTotals.Consumed, m_sTotals.Lost, m_sTotals.Charged, m_sTotals.Transferred,
                 fFinal, fSpent > 0 ? m_sTotals.WorkEnergy / fSpent : 0.0, nDepletedWorkers, nDepletedChargers,
                 m_sTotals.MaxFill, m_sTotals.Work ? m_sTotals.WorkXMin : 0.0, m_sTotals.Work ? m_sTotals.WorkXMax : 0.0);
    std::fclose(pFile);
}

REGISTER_LOOP_FUNCTIONS(CEnergyLoopFunctions, "energy_loop_functions")
