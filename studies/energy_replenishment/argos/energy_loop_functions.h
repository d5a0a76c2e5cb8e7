// Loop functions of the energy-replenishment study: the per-step energy accounting of every
// robot (design/STUDIES.md: core, moving and working costs, charging in the charging strip,
// transfers from a mobile charger to the one worker it serves), the work counted in the work
// strip, and the trial's result written as one JSON object.
//
// <loop_functions library="..." label="energy_loop_functions">
//   <energy move="0.1" work="0.1" core="0.005" charge="1" transfer="1" loss="0"/>   per step
//   <output path="result.json" trace=""/>   trace: a CSV of every robot's step (tests)
// </loop_functions>
#ifndef ENERGY_LOOP_FUNCTIONS_H
#define ENERGY_LOOP_FUNCTIONS_H

#include <fstream>
#include <string>
#include <vector>

#include <argos3/core/simulator/entity/embodied_entity.h>
#include <argos3/core/simulator/loop_functions.h>

#include "energy_agent.h"

class CEnergyLoopFunctions : public argos::CLoopFunctions {
public:
    void Init(argos::TConfigurationNode& t_node) override;
    void Reset() override;
    void PostStep() override;
    void PostExperiment() override;

private:
    struct SRobot {
        std::string Id;
        energy::Agent* Agent;
        argos::CEmbodiedEntity* Body;
    };
    struct STotals {
        long Work = 0;              // units: one per worker-step of working in the work strip
        double WorkEnergy = 0;      // energy spent working
        double Consumed = 0;        // energy spent by all robots (core, moving, working)
        double Lost = 0;            // energy lost in transfers
        double Charged = 0;         // energy taken from the charging strip
        double Transferred = 0;     // energy given by chargers
        double MaxFill = 0;         // highest energy / capacity of any robot at any step
        double WorkXMin = 1e9, WorkXMax = -1e9;   // where work was counted
    };

    double Position(const SRobot& s_robot) const { return s_robot.Body->GetOriginAnchor().Position.GetX(); }
    void Spend(SRobot& s_robot);
    void Transfer(SRobot& s_charger);

    double m_fMove = 0.1, m_fWork = 0.1, m_fCore = 0.005, m_fCharge = 1.0, m_fTransfer = 1.0, m_fLoss = 0.0;
    std::string m_strOutput, m_strTrace;
    std::ofstream m_cTrace;
    std::vector<SRobot> m_vecRobots;
    STotals m_sTotals;
};

#endif
