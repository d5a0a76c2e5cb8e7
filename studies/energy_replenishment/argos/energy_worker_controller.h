// The worker of the fixed-charger strategy (the seed's Figure 7b, energy_worker.yaml): works in
// the work strip, drives back to the charging strip when its energy is low, recharges there.
#ifndef ENERGY_WORKER_CONTROLLER_H
#define ENERGY_WORKER_CONTROLLER_H

#include "energy_robot.h"
#include "energy_worker_base.h"

class CEnergyWorkerController : public energy::CEnergyRobot<CEnergyWorkerBase> {
public:
    energy::Role AgentRole() const override { return energy::Role::Worker; }

protected:
    argos::CVector2 Goal() const override;

    bool Check_atCharger() override;
    bool Check_atWork() override;
    bool Check_highEnergy() override;
    bool Check_lowEnergy() override;
    bool Check_notAtCharger() override;
    bool Check_notAtWork() override;

    void On_charge() override;
    void On_moveToCharge() override;
    void On_moveToWork() override;
    void On_work() override;
};

#endif
